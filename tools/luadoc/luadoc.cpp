// tumble_luadoc: generates the Lua API reference from the doc blocks on the
// bindings (runtime/script/*.cpp and internal/*.cpp), after Defold's way:
// the docs live next to the code they describe.
//
//   tumble_luadoc --source ROOT --out DIR [--check]
//
// writes DIR/docs/lua-api.md (Markdown) and DIR/scripts/tumble/api.lua (Lua
// Language Server annotations). With --check it also compares both with the
// checked-in files under ROOT and fails if they differ (CI runs this).
//
// A doc block is a run of `///` lines whose first line is one of
//   /// @module NAME            a table of functions (world, game, ...)
//   /// @class NAME[: PARENT]   a type: userdata with methods or a table shape
//   /// @function NAME          NAME is f, table.f or Class:method
//   /// @alias NAME TYPE text   a type name for a union, e.g. Vec3|number[]
// followed by free text (the description) and tags:
//   /// @param NAME[?] TYPE description (unit)     ? = optional; NAME may be ...
//   /// @return TYPE[?] description                one line per returned value
//   /// @field NAME[?] TYPE description            for @class
//   /// @example code                               one line of example code
// TYPE is a Lua Language Server type: number, integer, string, boolean,
// table, function, any, Body, Vec3, Body[], number|boolean, fun(a: T): R.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "script/vehicle_defs.h"

namespace fs = std::filesystem;

namespace {

struct Item {
  std::string name, type, text;  // param / return / field
  bool optional = false;
};

struct Block {
  std::string kind;  // module, class, function
  std::string name, parent;
  std::string where;  // file:line, for messages
  std::vector<std::string> description, examples;
  std::vector<Item> params, returns, fields;
};

std::string trim(const std::string& s) {
  auto b = s.find_first_not_of(" \t");
  auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// Splits "TYPE rest" where TYPE may hold spaces inside parentheses.
std::pair<std::string, std::string> splitType(const std::string& s) {
  int depth = 0;
  std::size_t i = 0;
  for (; i < s.size(); ++i) {
    if (s[i] == '(') ++depth;
    if (s[i] == ')') --depth;
    if (depth == 0 && (s[i] == ' ' || s[i] == '\t')) break;
  }
  return {s.substr(0, i), trim(i < s.size() ? s.substr(i) : std::string())};
}

std::pair<std::string, std::string> splitWord(const std::string& s) {
  auto sp = s.find_first_of(" \t");
  if (sp == std::string::npos) return {s, ""};
  return {s.substr(0, sp), trim(s.substr(sp))};
}

bool parseStream(std::istream& in, const std::string& shown, std::vector<Block>& out) {
  std::string line;
  Block* cur = nullptr;
  int n = 0;
  bool ok = true;
  while (std::getline(in, line)) {
    ++n;
    std::string t = trim(line);
    if (t.rfind("///", 0) != 0 || t.rfind("///<", 0) == 0) {
      cur = nullptr;
      continue;
    }
    std::string body = t.size() > 3 && t[3] == ' ' ? t.substr(4) : t.substr(3);
    body = body.empty() ? body : (body[0] == ' ' ? body.substr(1) : body);
    std::string where = shown + ":" + std::to_string(n);
    if (body.rfind("@alias ", 0) == 0) {  // one line: @alias NAME TYPE description
      auto [tag, rest] = splitWord(body);
      auto [name, more] = splitWord(rest);
      Block b;
      b.kind = "alias";
      b.name = name;
      b.where = where;
      Item item;
      std::tie(item.type, item.text) = splitType(more);
      b.returns.push_back(item);
      out.push_back(b);
      cur = &out.back();
      continue;
    }
    if (body.rfind("@module ", 0) == 0 || body.rfind("@class ", 0) == 0 || body.rfind("@function ", 0) == 0) {
      auto [tag, rest] = splitWord(body);
      out.push_back(Block{});
      cur = &out.back();
      cur->kind = tag.substr(1);
      cur->where = where;
      auto colon = rest.find(':');
      if (cur->kind == "class" && colon != std::string::npos) {
        cur->name = trim(rest.substr(0, colon));
        cur->parent = trim(rest.substr(colon + 1));
      } else {
        cur->name = trim(rest);
      }
      continue;
    }
    if (!cur) continue;  // an ordinary /// comment
    if (body.rfind("@param ", 0) == 0 || body.rfind("@field ", 0) == 0) {
      auto [name, rest] = splitWord(trim(body.substr(7)));
      Item item;
      item.optional = !name.empty() && name.back() == '?';
      item.name = item.optional ? name.substr(0, name.size() - 1) : name;
      std::tie(item.type, item.text) = splitType(rest);
      if (item.type.empty()) {
        std::cerr << where << ": " << body.substr(0, 6) << " " << name << " needs a type\n";
        ok = false;
      }
      (body[1] == 'p' ? cur->params : cur->fields).push_back(item);
    } else if (body.rfind("@return ", 0) == 0) {
      Item item;
      std::tie(item.type, item.text) = splitType(trim(body.substr(8)));
      item.optional = !item.type.empty() && item.type.back() == '?';
      cur->returns.push_back(item);
    } else if (body.rfind("@example", 0) == 0) {
      cur->examples.push_back(body.size() > 9 ? body.substr(9) : std::string());
    } else if (!body.empty() && body[0] == '@') {
      std::cerr << where << ": unknown tag " << splitWord(body).first << "\n";
      ok = false;
    } else {
      cur->description.push_back(body);
    }
  }
  return ok;
}

std::string join(const std::vector<std::string>& lines, const std::string& sep) {
  std::string s;
  for (const auto& l : lines) s += (s.empty() ? "" : sep) + l;
  return s;
}

std::string escapeCell(const std::string& s) {
  std::string r;
  for (char c : s) r += c == '|' ? std::string("\\|") : std::string(1, c);
  return r;
}

std::string anchor(const std::string& name) {
  std::string a;
  for (char c : name)
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') a += char(std::tolower(c));
  return a;
}

std::string signature(const Block& f) {
  std::string s = f.name + "(";
  for (std::size_t i = 0; i < f.params.size(); ++i) {
    const Item& p = f.params[i];
    s += (i ? ", " : "") + (p.optional ? "[" + p.name + "]" : p.name);
  }
  return s + ")";
}

// Which table or class a function belongs to: "world" for world.box, "Body"
// for Body:position, "" for a global.
std::string ownerOf(const std::string& name) {
  auto p = name.find_first_of(".:");
  return p == std::string::npos ? std::string() : name.substr(0, p);
}

void markdownFunction(std::ostream& md, const Block& f) {
  md << "### `" << signature(f) << "`\n\n";
  if (!f.description.empty()) md << join(f.description, "\n") << "\n\n";
  if (!f.params.empty()) {
    md << "| Parameter | Type | Description |\n|---|---|---|\n";
    for (const Item& p : f.params)
      md << "| `" << p.name << "`" << (p.optional ? " (optional)" : "") << " | `" << escapeCell(p.type) << "` | "
         << escapeCell(p.text) << " |\n";
    md << "\n";
  }
  for (const Item& r : f.returns)
    md << "**Returns** `" << r.type << "`" << (r.text.empty() ? "" : " — " + r.text) << "\n\n";
  if (!f.examples.empty()) md << "```lua\n" << join(f.examples, "\n") << "\n```\n\n";
}

void markdownFields(std::ostream& md, const Block& c) {
  if (c.fields.empty()) return;
  md << "| Field | Type | Description |\n|---|---|---|\n";
  for (const Item& f : c.fields)
    md << "| `" << f.name << "`" << (f.optional ? " (optional)" : "") << " | `" << escapeCell(f.type) << "` | "
       << escapeCell(f.text) << " |\n";
  md << "\n";
}

struct Api {
  std::vector<Block> blocks;
  std::vector<const Block*> modules, classes, functions, aliases;
};

std::string markdown(const Api& api) {
  std::ostringstream md;
  md << "# Tumble Lua API reference\n\n"
        "<!-- Generated by tools/luadoc from the doc blocks in runtime/script/*.cpp. Do not edit by hand:\n"
        "     change the doc block and run `cmake --build build --target luadoc`. -->\n\n"
        "Every mod scenario runs in its own sandbox with these globals and tables, plus the safe parts of the\n"
        "standard library: `assert error ipairs next pairs pcall xpcall rawequal rawget rawlen rawset select\n"
        "tonumber tostring type getmetatable setmetatable`, `math` (seeded from `--seed`), `string` (no `dump`), `table`, `utf8`,\n"
        "`coroutine` and `os.clock/time/date/difftime`. Not available: `io`, `debug`, `package`, `dofile`,\n"
        "`loadfile`, `os.execute/exit/getenv/remove/rename`, binary chunks; reading one of them raises an error\n"
        "that says so. Units are SI (m, kg, s, rad, N); Y is up. Editors: point the Lua Language Server at\n"
        "`scripts/tumble/api.lua` (see its header) for completion and type checks.\n\n";
  md << "## Contents\n\n";
  md << "- [Scenario files](#scenario-files)\n- [Global functions](#global-functions)\n";
  for (const Block* m : api.modules) md << "- [`" << m->name << "`](#" << anchor("module-" + m->name) << ")\n";
  for (const Block* c : api.classes)
    if (std::any_of(api.functions.begin(), api.functions.end(), [&](const Block* f) { return ownerOf(f->name) == c->name; }))
      md << "- [`" << c->name << "`](#" << anchor("type-" + c->name) << ")\n";
  md << "- [Data types](#data-types)\n\n";

  auto classNamed = [&](const std::string& n) -> const Block* {
    for (const Block* c : api.classes)
      if (c->name == n) return c;
    return nullptr;
  };
  md << "## Scenario files\n\n";
  for (const char* n : {"Scenario", "Ctx"}) {
    if (const Block* c = classNamed(n)) {
      md << "### `" << c->name << "`\n\n";
      if (!c->description.empty()) md << join(c->description, "\n") << "\n\n";
      markdownFields(md, *c);
    }
  }
  md << "## Global functions\n\n";
  for (const Block* f : api.functions)
    if (ownerOf(f->name).empty()) markdownFunction(md, *f);
  for (const Block* m : api.modules) {
    md << "<a id=\"" << anchor("module-" + m->name) << "\"></a>\n## `" << m->name << "`\n\n";
    if (!m->description.empty()) md << join(m->description, "\n") << "\n\n";
    for (const Block* f : api.functions)
      if (ownerOf(f->name) == m->name) markdownFunction(md, *f);
  }
  std::vector<const Block*> data;
  for (const Block* c : api.classes) {
    bool hasMethods = std::any_of(api.functions.begin(), api.functions.end(),
                                  [&](const Block* f) { return ownerOf(f->name) == c->name; });
    if (!hasMethods) {
      if (c->name != "Scenario" && c->name != "Ctx") data.push_back(c);
      continue;
    }
    md << "<a id=\"" << anchor("type-" + c->name) << "\"></a>\n## `" << c->name << "`\n\n";
    if (!c->description.empty()) md << join(c->description, "\n") << "\n\n";
    markdownFields(md, *c);
    for (const Block* f : api.functions)
      if (ownerOf(f->name) == c->name) markdownFunction(md, *f);
  }
  md << "## Data types\n\nTables that functions take or return.\n\n";
  for (const Block* a : api.aliases)
    md << "- `" << a->name << "` = `" << a->returns[0].type << "`: " << a->returns[0].text << "\n";
  if (!api.aliases.empty()) md << "\n";
  for (const Block* c : data) {
    md << "### `" << c->name << "`" << (c->parent.empty() ? "" : " (and every field of `" + c->parent + "`)")
       << "\n\n";
    if (!c->description.empty()) md << join(c->description, "\n") << "\n\n";
    markdownFields(md, *c);
  }
  std::string s = md.str();
  while (s.size() > 1 && s[s.size() - 1] == '\n' && s[s.size() - 2] == '\n') s.pop_back();
  return s;
}

void luaComment(std::ostream& lua, const std::vector<std::string>& lines) {
  for (const auto& l : lines) lua << "---" << l << "\n";
}

void luaFunction(std::ostream& lua, const Block& f) {
  luaComment(lua, f.description);
  if (!f.examples.empty()) {
    lua << "---\n---```lua\n";
    for (const auto& e : f.examples) lua << "---" << e << "\n";
    lua << "---```\n";
  }
  std::string args;
  for (const Item& p : f.params) {
    lua << "---@param " << p.name << (p.optional && p.name != "..." ? "?" : "") << " " << p.type
        << (p.text.empty() ? "" : " " + p.text) << "\n";
    args += (args.empty() ? "" : ", ") + p.name;
  }
  for (const Item& r : f.returns) lua << "---@return " << r.type << (r.text.empty() ? "" : " # " + r.text) << "\n";
  lua << "function " << f.name << "(" << args << ") end\n\n";
}

std::string luaAnnotations(const Api& api) {
  std::ostringstream lua;
  lua << "---@meta\n"
         "-- Lua Language Server annotations for the Tumble mod API, generated by tools/luadoc from the\n"
         "-- doc blocks in runtime/script/*.cpp. Do not edit by hand and do not require it: editors read it.\n"
         "-- VS Code (sumneko.lua): add this folder to \"Lua.workspace.library\" in .vscode/settings.json.\n\n";
  for (const Block* a : api.aliases)
    lua << "---" << a->returns[0].text << "\n---@alias " << a->name << " " << a->returns[0].type << "\n\n";
  for (const Block* c : api.classes) {
    luaComment(lua, c->description);
    lua << "---@class " << c->name << (c->parent.empty() ? "" : ": " + c->parent) << "\n";
    for (const Item& f : c->fields)
      lua << "---@field " << f.name << (f.optional ? "?" : "") << " " << f.type
          << (f.text.empty() ? "" : " " + f.text) << "\n";
    bool hasMethods = std::any_of(api.functions.begin(), api.functions.end(),
                                  [&](const Block* f) { return ownerOf(f->name) == c->name; });
    if (hasMethods) lua << "local " << c->name << " = {}\n";
    lua << "\n";
    for (const Block* f : api.functions)
      if (ownerOf(f->name) == c->name) luaFunction(lua, *f);
  }
  for (const Block* m : api.modules) {
    luaComment(lua, m->description);
    lua << m->name << " = {}\n\n";
    for (const Block* f : api.functions)
      if (ownerOf(f->name) == m->name) luaFunction(lua, *f);
  }
  for (const Block* f : api.functions)
    if (ownerOf(f->name).empty()) luaFunction(lua, *f);
  std::string s = lua.str();
  while (s.size() > 1 && s[s.size() - 1] == '\n' && s[s.size() - 2] == '\n') s.pop_back();
  return s;
}

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool writeAll(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary);
  out << text;
  return bool(out);
}

}  // namespace

int main(int argc, char** argv) {
  fs::path source, out;
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--source" && i + 1 < argc) source = argv[++i];
    else if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--check") check = true;
    else {
      std::cerr << "usage: tumble_luadoc --source ROOT --out DIR [--check]\n";
      return 1;
    }
  }
  if (source.empty() || out.empty()) {
    std::cerr << "usage: tumble_luadoc --source ROOT --out DIR [--check]\n";
    return 1;
  }
  std::vector<fs::path> files;
  for (const char* dir : {"runtime/script", "runtime/script/internal"}) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(source / dir, ec))
      if (e.is_regular_file() && e.path().extension() == ".cpp") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::cerr << "tumble_luadoc: no .cpp files under " << (source / "runtime/script") << "\n";
    return 1;
  }
  Api api;
  bool ok = true;
  for (const fs::path& f : files) {
    std::ifstream in(f);
    ok &= parseStream(in, fs::relative(f, source).string(), api.blocks);
  }
  // Definition files' tables are documented by their field tables.
  std::istringstream vehicleTables(tumble::script::vehicleDefinitionDocBlocks());
  ok &= parseStream(vehicleTables, "runtime/script/vehicle_defs.cpp (field tables)", api.blocks);
  if (!ok) return 1;
  std::map<std::string, std::string> seen;
  for (const Block& b : api.blocks) {
    std::string key = b.kind + " " + b.name;
    if (seen.count(key)) {
      std::cerr << b.where << ": " << key << " is documented twice (also at " << seen[key] << ")\n";
      return 1;
    }
    seen[key] = b.where;
    (b.kind == "module"  ? api.modules
     : b.kind == "class" ? api.classes
     : b.kind == "alias" ? api.aliases
                         : api.functions)
        .push_back(&b);
  }
  const std::string md = markdown(api), lua = luaAnnotations(api);
  const fs::path mdPath = "docs/lua-api.md", luaPath = "scripts/tumble/api.lua";
  if (!writeAll(out / mdPath, md) || !writeAll(out / luaPath, lua)) {
    std::cerr << "tumble_luadoc: cannot write under " << out << "\n";
    return 1;
  }
  if (!check) return 0;
  bool current = true;
  for (const auto& [path, text] : {std::pair{mdPath, md}, std::pair{luaPath, lua}}) {
    if (readAll(source / path) != text) {
      std::cerr << "docs are out of date: " << (source / path).string() << " differs from what the doc blocks say ("
                << (out / path).string() << "); run `cmake --build <build dir> --target luadoc` and commit the result\n";
      current = false;
    }
  }
  if (current) std::cout << "docs are current: " << api.functions.size() << " functions, " << api.classes.size()
                         << " types, " << api.modules.size() << " tables\n";
  return current ? 0 : 1;
}
