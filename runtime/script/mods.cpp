#include "script/mods.h"
#include "script/internal/raw_access.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <cstring>

#include "core/text.h"
#include "script/emitter_files.h"
#include "script/lua_vm.h"
#include "script/mod_bindings.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace fs = std::filesystem;

namespace tumble::script {

std::string ModProblem::text() const {
  return file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + message;
}

namespace {

// Versions, dependencies and references are parsed by hand, never with a
// regular expression: std::regex recurses per character, and a manifest's
// text can be any length.
bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isAlnum(char c) { return isDigit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool isIdentifierChar(char c) { return isAlnum(c) || c == '.' || c == '-'; }  // semver's [0-9A-Za-z.-]
bool isNameChar(char c) { return isAlnum(c) || c == '_' || c == '-'; }         // mod and scenario names
bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

struct Semver {
  long long part[3] = {0, 0, 0};
  int parts = 0;                 ///< how many numbers were written (1..3)
  std::vector<std::string> pre;  ///< pre-release identifiers
};

// Reads "1", "1.2" or "1.2.3" from text at *i (each number at most 9
// digits); returns false when no number starts there.
bool readVersionNumbers(const std::string& text, std::size_t* i, Semver* v) {
  for (int p = 0; p < 3; ++p) {
    if (p > 0) {
      if (*i + 1 >= text.size() || text[*i] != '.' || !isDigit(text[*i + 1])) break;
      ++*i;
    }
    const std::size_t start = *i;
    while (*i < text.size() && isDigit(text[*i])) ++*i;
    if (*i == start || *i - start > 9) return false;
    v->part[p] = std::stoll(text.substr(start, *i - start));
    v->parts = p + 1;
  }
  return true;
}

// A run of semver identifier characters at *i, at least one.
bool readIdentifiers(const std::string& text, std::size_t* i, std::string* out) {
  const std::size_t start = *i;
  while (*i < text.size() && isIdentifierChar(text[*i])) ++*i;
  if (out) *out = text.substr(start, *i - start);
  return *i > start;
}

// A manifest's version: "1.2", "1.2.3", optionally "-pre" or "+build".
bool isSemver(const std::string& v) {
  Semver parsed;
  std::size_t i = 0;
  if (!readVersionNumbers(v, &i, &parsed) || parsed.parts < 2) return false;
  if (i == v.size()) return true;
  if (v[i] != '-' && v[i] != '+') return false;
  ++i;
  return readIdentifiers(v, &i, nullptr) && i == v.size();
}

// "1", "1.2", "1.2.3", with optional "-pre.release" and "+build".
bool parseSemver(const std::string& text, Semver* out) {
  Semver v;
  std::size_t i = 0;
  if (!readVersionNumbers(text, &i, &v)) return false;
  if (i < text.size() && text[i] == '-') {
    ++i;
    std::string pre;
    if (!readIdentifiers(text, &i, &pre)) return false;
    std::size_t start = 0;
    while (start <= pre.size()) {
      std::size_t dot = pre.find('.', start);
      v.pre.push_back(pre.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
  }
  if (i < text.size() && text[i] == '+') {
    ++i;
    if (!readIdentifiers(text, &i, nullptr)) return false;
  }
  if (i != text.size()) return false;
  *out = v;
  return true;
}

std::string trimmed(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && isSpace(s[b])) ++b;
  while (e > b && isSpace(s[e - 1])) --e;
  return s.substr(b, e - b);
}

bool isNumber(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Semver 2.0 precedence: numbers, then a pre-release sorts before the
// release; pre-release identifiers compare numerically or as text.
int compare(const Semver& a, const Semver& b) {
  for (int i = 0; i < 3; ++i)
    if (a.part[i] != b.part[i]) return a.part[i] < b.part[i] ? -1 : 1;
  if (a.pre.empty() || b.pre.empty()) return a.pre.empty() == b.pre.empty() ? 0 : (a.pre.empty() ? 1 : -1);
  for (std::size_t i = 0; i < std::min(a.pre.size(), b.pre.size()); ++i) {
    const std::string &x = a.pre[i], &y = b.pre[i];
    if (x == y) continue;
    bool nx = isNumber(x), ny = isNumber(y);
    if (nx && ny) return x.size() != y.size() ? (x.size() < y.size() ? -1 : 1) : (x < y ? -1 : 1);
    if (nx != ny) return nx ? -1 : 1;
    return x < y ? -1 : 1;
  }
  return a.pre.size() == b.pre.size() ? 0 : (a.pre.size() < b.pre.size() ? -1 : 1);
}

bool satisfiesOne(const Semver& v, const VersionConstraint& c) {
  Semver want;
  if (!parseSemver(c.version, &want)) return false;
  int cmp = compare(v, want);
  if (c.op == ">=") return cmp >= 0;
  if (c.op == ">") return cmp > 0;
  if (c.op == "<=") return cmp <= 0;
  if (c.op == "<") return cmp < 0;
  if (c.op == "=" || c.op == "==") return cmp == 0;
  // ^ and ~: at least `want`, below the next "breaking" version.
  Semver upper;
  upper.parts = 3;
  if (c.op == "~") {
    if (want.parts == 1) upper.part[0] = want.part[0] + 1;
    else upper.part[0] = want.part[0], upper.part[1] = want.part[1] + 1;
  } else {  // ^: the left-most non-zero part written may not change
    if (want.part[0] > 0 || want.parts == 1) upper.part[0] = want.part[0] + 1;
    else if (want.part[1] > 0 || want.parts == 2) upper.part[1] = want.part[1] + 1;
    else upper.part[2] = want.part[2] + 1;
  }
  upper.pre = {"0"};  // below every pre-release of the upper bound too
  return cmp >= 0 && compare(v, upper) < 0;
}

}  // namespace

int compareVersions(const std::string& a, const std::string& b) {
  Semver x, y;
  if (!parseSemver(a, &x) || !parseSemver(b, &y)) return 0;
  return compare(x, y);
}

bool satisfies(const std::string& version, const std::vector<VersionConstraint>& constraints) {
  Semver v;
  if (!parseSemver(version, &v)) return constraints.empty();
  for (const VersionConstraint& c : constraints)
    if (!satisfiesOne(v, c)) return false;
  return true;
}

namespace {

// One constraint: an operator and a version, "  >= 1.2 ".
bool parseConstraint(const std::string& piece, VersionConstraint* out) {
  const std::string p = trimmed(piece);
  std::size_t i = 0;
  for (const char* op : {">=", "<=", "==", "=", ">", "<", "^", "~"}) {
    if (p.compare(0, std::strlen(op), op) == 0) {
      out->op = op;
      i = std::strlen(op);
      break;
    }
  }
  if (i == 0) return false;
  while (i < p.size() && isSpace(p[i])) ++i;
  if (i >= p.size() || !isDigit(p[i])) return false;
  for (std::size_t j = i; j < p.size(); ++j)
    if (!isIdentifierChar(p[j]) && p[j] != '+') return false;
  out->version = p.substr(i);
  return true;
}

}  // namespace

Result<ModDependency> parseDependency(const std::string& text) {
  const std::string form = "dependency \"" + clipped(text) +
                           "\" is not of the form \"name\", \"name >= 1.0\" or \"name?\" (optional); operators: "
                           ">=, >, <=, <, =, ^, ~; several constraints are separated by commas";
  if (text.size() > kMaxDependencyChars)
    return makeError("dependency \"" + clipped(text) + "\" is longer than " + std::to_string(kMaxDependencyChars) +
                     " characters");
  // name, an optional '?', the constraints, an optional '?' at the end.
  std::string rest = trimmed(text);
  std::size_t i = 0;
  while (i < rest.size() && isNameChar(rest[i])) ++i;
  if (i == 0) return makeError(form);
  ModDependency dep;
  dep.name = rest.substr(0, i);
  dep.text = text;
  while (i < rest.size() && isSpace(rest[i])) ++i;
  if (i < rest.size() && rest[i] == '?') dep.optional = true, ++i;
  rest = trimmed(rest.substr(i));
  if (!rest.empty() && rest.back() == '?') dep.optional = true, rest = trimmed(rest.substr(0, rest.size() - 1));
  std::size_t start = 0;
  while (!rest.empty() && start <= rest.size()) {
    std::size_t comma = rest.find(',', start);
    std::string piece = rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    VersionConstraint c;
    if (!parseConstraint(piece, &c)) return makeError(form);
    Semver v;
    if (!parseSemver(c.version, &v))
      return makeError("dependency \"" + clipped(text) + "\": \"" + clipped(c.version) +
                       "\" is not a version like 1, 1.2 or 1.2.3");
    if (c.op == "==") c.op = "=";
    dep.constraints.push_back(c);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return dep;
}

namespace {

// 1-based line of the first line in `file` that contains `needle` (0: none).
int lineOf(const std::string& file, const std::string& needle) {
  std::ifstream in(file);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (line.find(needle) != std::string::npos) return n;
  return 0;
}

std::string constraintText(const ModDependency& d) {
  std::string s;
  for (const auto& c : d.constraints) s += (s.empty() ? "" : ", ") + c.op + " " + c.version;
  return s;
}

// Runs mod.lua in an empty environment under a small budget and reads the
// returned table. Problems are appended; returns true if a table came back.
bool readManifest(const std::string& dir, ModInfo& info, std::vector<ModProblem>& problems) {
  std::string path = (fs::path(dir) / "mod.lua").string();
  // "mods/mymod/" (a shell's completion) names the folder "mymod" too.
  fs::path folderPath = fs::path(dir).lexically_normal();
  if (!folderPath.has_filename()) folderPath = folderPath.parent_path();
  std::string folder = folderPath.filename().string();
  auto problem = [&](int line, std::string msg) { problems.push_back({path, line, std::move(msg), folder}); };
  if (!fs::exists(path)) {
    problem(0, "missing: every mod folder needs a mod.lua manifest returning {name, version, title, api}");
    return false;
  }
  VmLimits limits;
  limits.memoryBytes = 8u << 20;
  limits.instructionsPerCall = 1'000'000;
  LuaVm vm(limits);
  lua_State* L = vm.state();
  if (LuaVm::loadFile(L, std::string(path.c_str())) != LUA_OK) {
    ScriptError e = LuaVm::parseError(fs::path(dir).filename().string(), lua_tostring(L, -1), "");
    problem(e.line, e.message);
    return false;
  }
  lua_newtable(L);  // empty _ENV: a manifest is data
  lua_setupvalue(L, -2, 1);
  ScriptError err;
  if (!vm.call(0, 1, fs::path(dir).filename().string(), "mod.lua", "top level", &err)) {
    problem(err.line, err.message);
    return false;
  }
  if (!lua_istable(L, -1)) {
    problem(0, "must return a table {name = ..., version = ..., title = ..., api = ...}");
    return false;
  }
  auto str = [&](const char* key, bool required, std::size_t maxChars) -> std::string {
    rawGetField(L, -1, key);
    std::string v;
    if (lua_type(L, -1) == LUA_TSTRING) v = lua_tostring(L, -1);
    else if (!lua_isnil(L, -1) || required)
      problem(0, std::string("field '") + key + "' must be a string" + (required ? " (required)" : ""));
    lua_pop(L, 1);
    if (v.size() > maxChars) {
      problem(0, std::string("field '") + key + "' is " + std::to_string(v.size()) + " characters long; at most " +
                     std::to_string(maxChars) + " are allowed (\"" + clipped(v) + "\")");
      v.clear();
    }
    return v;
  };
  info.name = str("name", true, kMaxModNameChars);
  info.version = str("version", true, kMaxVersionChars);
  info.title = str("title", false, kMaxTitleChars);
  rawGetField(L, -1, "api");
  if (lua_isinteger(L, -1)) info.api = int(lua_tointeger(L, -1));
  else problem(0, "field 'api' must be an integer (the Lua API version, now " + std::to_string(kApiVersion) + ")");
  lua_pop(L, 1);
  if (!info.version.empty() && !isSemver(info.version))
    problem(0, "field 'version' must be semver like \"1.2.0\", got \"" + clipped(info.version) + "\"");
  if (info.api > kApiVersion)
    problem(lineOf(path, "api"), "field 'api' is " + std::to_string(info.api) + " but this Tumble provides API " +
                                     std::to_string(kApiVersion) + "; update Tumble or lower 'api'");
  else if (info.api < 1)
    problem(lineOf(path, "api"), "field 'api' is " + std::to_string(info.api) + "; API versions start at 1 (now " +
                                     std::to_string(kApiVersion) + ")");
  if (!info.name.empty() && info.name != folder)
    problem(0, "field 'name' is \"" + clipped(info.name) + "\" but the folder is \"" + clipped(folder) + "\"; they must match");
  rawGetField(L, -1, "depends");
  if (lua_istable(L, -1)) {
    lua_Integer n = rawLength(L, -1);
    if (n > 64) {
      problem(lineOf(path, "depends"), "field 'depends' lists " + std::to_string(n) + " mods; at most 64 are allowed");
      n = 0;
    }
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_rawgeti(L, -1, i);
      if (lua_type(L, -1) == LUA_TSTRING) {
        std::string text = lua_tostring(L, -1);
        auto dep = parseDependency(text);
        if (dep) info.depends.push_back(*dep);
        else problem(text.size() <= kMaxDependencyChars ? lineOf(path, text) : 0, "field 'depends': " + dep.error());
      } else {
        problem(0, "field 'depends' must be a list of strings like \"base >= 1.0\"");
      }
      lua_pop(L, 1);
    }
  } else if (!lua_isnil(L, -1)) {
    problem(0, "field 'depends' must be a list of strings like \"base >= 1.0\"");
  }
  lua_pop(L, 2);
  info.dir = fs::absolute(dir).lexically_normal().string();
  return true;
}

}  // namespace

Result<ModInfo> loadManifest(const std::string& dir) {
  ModInfo info;
  std::vector<ModProblem> problems;
  readManifest(dir, info, problems);
  if (!problems.empty()) {
    std::string msg;
    for (auto& p : problems) msg += (msg.empty() ? "" : "\n") + p.text();
    return makeError(msg);
  }
  return info;
}

namespace {

// Every mod with a valid manifest in the search folders; later folders
// override earlier ones with the same name. Manifest problems are appended.
std::vector<ModInfo> collect(const std::vector<std::string>& searchDirs, std::vector<ModProblem>& problems) {
  std::vector<ModInfo> mods;
  for (const std::string& root : searchDirs) {
    std::error_code ec;
    if (!fs::is_directory(root, ec)) continue;
    std::vector<fs::path> dirs;
    for (auto& entry : fs::directory_iterator(root, ec))
      if (entry.is_directory() && fs::exists(entry.path() / "mod.lua")) dirs.push_back(entry.path());
    std::sort(dirs.begin(), dirs.end());
    for (const fs::path& d : dirs) {
      ModInfo info;
      std::size_t before = problems.size();
      bool ok = readManifest(d.string(), info, problems);
      if (!ok || problems.size() != before) continue;
      auto it = std::find_if(mods.begin(), mods.end(), [&](const ModInfo& m) { return m.name == info.name; });
      if (it != mods.end()) *it = info;
      else mods.push_back(info);
    }
  }
  return mods;
}

struct Edge {
  std::size_t to;
  bool optional;
};

// Depth-first search for cycles; each mod on a cycle is marked and gets a
// problem that spells the cycle out ("a -> b -> a").
void findCycles(const std::vector<ModInfo>& mods, const std::vector<std::vector<Edge>>& edges,
                const std::vector<std::size_t>& byNameOrder, std::vector<bool>& broken,
                std::vector<ModProblem>& problems) {
  std::vector<int> color(mods.size(), 0);  // 0 new, 1 on the stack, 2 done
  std::vector<std::size_t> stack;
  std::function<void(std::size_t)> visit = [&](std::size_t i) {
    color[i] = 1;
    stack.push_back(i);
    for (const Edge& e : edges[i]) {
      if (color[e.to] == 0) {
        visit(e.to);
      } else if (color[e.to] == 1) {
        auto from = std::find(stack.begin(), stack.end(), e.to);
        std::string cycle;
        for (auto it = from; it != stack.end(); ++it) cycle += mods[*it].name + " -> ";
        cycle += mods[e.to].name;
        for (auto it = from; it != stack.end(); ++it) {
          std::string manifest = (fs::path(mods[*it].dir) / "mod.lua").string();
          problems.push_back({manifest, lineOf(manifest, "depends"),
                              "dependency cycle: " + cycle + "; none of these mods can load first, so none is loaded",
                              mods[*it].name});
          broken[*it] = true;
        }
      }
    }
    stack.pop_back();
    color[i] = 2;
  };
  for (std::size_t i : byNameOrder)
    if (color[i] == 0) visit(i);
}

// Loadable mods in load order (dependencies first, ties by name); every
// reason a mod cannot load is appended to problems.
std::vector<ModInfo> resolve(const std::vector<ModInfo>& mods, std::vector<ModProblem>& problems) {
  const std::size_t n = mods.size();
  std::map<std::string, std::size_t> byName;
  for (std::size_t i = 0; i < n; ++i) byName[mods[i].name] = i;
  std::vector<std::size_t> byNameOrder;
  for (const auto& [name, i] : byName) byNameOrder.push_back(i);
  std::vector<bool> broken(n, false);
  std::vector<std::vector<Edge>> edges(n);
  for (std::size_t i : byNameOrder) {
    const ModInfo& m = mods[i];
    std::string manifest = (fs::path(m.dir) / "mod.lua").string();
    auto report = [&](const ModDependency& d, std::string msg) {
      problems.push_back({manifest, lineOf(manifest, d.text), std::move(msg), m.name});
    };
    for (const ModDependency& d : m.depends) {
      if (d.name == m.name) {
        report(d, "mod \"" + m.name + "\" depends on itself (\"" + d.text + "\"); remove that entry");
        broken[i] = true;
        continue;
      }
      auto it = byName.find(d.name);
      if (it == byName.end()) {
        if (d.optional) continue;
        report(d, "missing dependency: mod \"" + m.name + "\" needs \"" + d.text + "\" but no mod named \"" + d.name +
                      "\" was found; install it, or write \"" + d.name + "?\" if the mod works without it");
        broken[i] = true;
        continue;
      }
      const ModInfo& dep = mods[it->second];
      if (!satisfies(dep.version, d.constraints)) {
        report(d, "version mismatch: mod \"" + m.name + "\" needs " + d.name + " " + constraintText(d) + " but " +
                      d.name + " is " + dep.version + " (" + dep.dir + ")");
        broken[i] = true;
        continue;
      }
      edges[i].push_back({it->second, d.optional});
    }
  }
  findCycles(mods, edges, byNameOrder, broken, problems);
  // A mod whose required dependency cannot load cannot load either; an
  // optional one that cannot load is treated as absent.
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t i : byNameOrder) {
      if (broken[i]) continue;
      for (const Edge& e : edges[i]) {
        if (!broken[e.to] || e.optional) continue;
        std::string manifest = (fs::path(mods[i].dir) / "mod.lua").string();
        problems.push_back({manifest, lineOf(manifest, "\"" + mods[e.to].name),
                            "mod \"" + mods[i].name + "\" needs \"" + mods[e.to].name +
                                "\", which cannot be loaded (see its problems)",
                            mods[i].name});
        broken[i] = changed = true;
        break;
      }
    }
  }
  // Kahn's algorithm; the ready set is ordered by name, so the order is
  // deterministic whatever the folders' listing order.
  std::vector<int> pending(n, 0);
  std::vector<std::vector<std::size_t>> dependents(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (broken[i]) continue;
    for (const Edge& e : edges[i]) {
      if (broken[e.to]) continue;
      ++pending[i];
      dependents[e.to].push_back(i);
    }
  }
  std::set<std::pair<std::string, std::size_t>> ready;
  for (std::size_t i = 0; i < n; ++i)
    if (!broken[i] && pending[i] == 0) ready.insert({mods[i].name, i});
  std::vector<ModInfo> order;
  while (!ready.empty()) {
    std::size_t i = ready.begin()->second;
    ready.erase(ready.begin());
    order.push_back(mods[i]);
    for (std::size_t d : dependents[i])
      if (--pending[d] == 0) ready.insert({mods[d].name, d});
  }
  return order;
}

}  // namespace

namespace {

// A call or field with a literal string argument found in a line of Lua:
// `particles.spawn ( "fire"`, `mesh = "x.obj"`. Found by a plain scan (no
// regular expression over a mod's text).
struct LiteralCallForm {
  const char* prefix;                    ///< "particles."
  std::vector<const char*> names;        ///< "spawn", "burst"
  char separator;                        ///< '(' for a call, '=' for a field
  bool wordStart;                        ///< the name may not follow a letter, digit or '_'
};
struct LiteralCall {
  std::size_t at;
  std::string what, argument;
};

std::vector<LiteralCall> findLiteralCalls(const std::string& line, const LiteralCallForm& form) {
  std::vector<LiteralCall> calls;
  auto skipSpace = [&](std::size_t i) {
    while (i < line.size() && isSpace(line[i])) ++i;
    return i;
  };
  for (const char* name : form.names) {
    const std::string needle = std::string(form.prefix) + name;
    for (std::size_t pos = line.find(needle); pos != std::string::npos; pos = line.find(needle, pos + 1)) {
      if (form.wordStart && pos > 0 && (isAlnum(line[pos - 1]) || line[pos - 1] == '_')) continue;
      std::size_t i = skipSpace(pos + needle.size());
      if (i >= line.size() || line[i] != form.separator) continue;
      i = skipSpace(i + 1);
      if (i >= line.size() || line[i] != '"') continue;
      const std::size_t end = line.find('"', i + 1);
      if (end == std::string::npos || end == i + 1) continue;
      calls.push_back({pos, name, line.substr(i + 1, end - i - 1)});
    }
  }
  std::sort(calls.begin(), calls.end(), [](const LiteralCall& a, const LiteralCall& b) { return a.at < b.at; });
  return calls;
}

const LiteralCallForm kEmitterCalls{"particles.", {"spawn", "burst"}, '(', false};
const LiteralCallForm kVehicleCalls{"vehicle.", {"spawn", "definition"}, '(', false};
const LiteralCallForm kActionCalls{"input.", {"value", "pressed", "released", "down", "inject"}, '(', false};
const LiteralCallForm kAssetCalls{"", {"set_model", "add_static_model", "model_mass_properties", "import"}, '(', false};
const LiteralCallForm kAssetFields{"", {"interior", "mesh", "display_mesh", "heightmap"}, '=', true};

// References by literal name in a mod's Lua files, checked statically: the
// emitter, vehicle, input action or asset file must exist. Names built at
// run time are not seen (the run then reports them). Comment lines are
// skipped.
void checkReferences(const ModInfo& self, const std::vector<fs::path>& files, const std::vector<ModInfo>& mods,
                     const input::BindingSet& actions, std::vector<ModProblem>& problems) {
  auto findMod = [&](const std::string& name) -> const ModInfo* {
    if (name == self.name) return &self;
    for (const ModInfo& m : mods)
      if (m.name == name) return &m;
    return nullptr;
  };
  // "mod:name" or "name" (this mod, then base) -> the file <mod>/<folder>/<name>.lua.
  auto definitionExists = [&](const std::string& ref, const char* folder, std::string* why) {
    std::vector<const ModInfo*> where;
    std::string name = ref;
    if (auto colon = ref.find(':'); colon != std::string::npos) {
      name = ref.substr(colon + 1);
      const ModInfo* m = findMod(ref.substr(0, colon));
      if (!m) {
        *why = "no mod named \"" + ref.substr(0, colon) + "\" is installed";
        return false;
      }
      where.push_back(m);
    } else {
      where.push_back(&self);
      if (const ModInfo* base = findMod("base"); base && base != &self) where.push_back(base);
    }
    std::string known;
    for (const ModInfo* m : where) {
      if (fs::exists(fs::path(m->dir) / folder / (name + ".lua"))) return true;
      for (const std::string& n : ModRegistry::listLua(*m, folder)) known += (known.empty() ? "" : ", ") + m->name + ":" + n;
    }
    *why = std::string(folder) + "/" + name + ".lua not found" + (known.empty() ? "" : " (known: " + known + ")");
    return false;
  };
  // "MOD:path" or a path inside this mod -> an existing file inside that mod.
  auto assetExists = [&](const std::string& ref, std::string* why) {
    const ModInfo* m = &self;
    std::string rel = ref;
    if (auto colon = ref.find(':'); colon != std::string::npos && colon > 1) {
      m = findMod(ref.substr(0, colon));
      rel = ref.substr(colon + 1);
      if (!m) {
        *why = "no mod named \"" + ref.substr(0, colon) + "\" is installed";
        return false;
      }
    }
    const fs::path root = fs::weakly_canonical(fs::path(m->dir));
    const fs::path path = fs::weakly_canonical(root / rel);
    const fs::path inside = path.lexically_relative(root);
    if (inside.empty() || *inside.begin() == "..") {
      *why = "leaves the mod's folder; paths stay inside it";
      return false;
    }
    if (!fs::is_regular_file(path)) {
      *why = "no such file in mod " + m->name + " (" + path.string() + ")";
      return false;
    }
    return true;
  };
  for (const fs::path& file : files) {
    std::ifstream in(file);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      const auto first = line.find_first_not_of(" \t");
      if (first == std::string::npos || line.compare(first, 2, "--") == 0) continue;
      auto scan = [&](const LiteralCallForm& form, auto&& check) {
        for (const LiteralCall& call : findLiteralCalls(line, form)) {
          std::string why;
          if (!check(call.what, call.argument, &why)) problems.push_back({file.string(), n, why, self.name});
        }
      };
      scan(kEmitterCalls, [&](const std::string& fn, const std::string& ref, std::string* why) {
        if (definitionExists(ref, "emitters", why)) return true;
        *why = "particles." + fn + "(\"" + ref + "\"): no such emitter: " + *why;
        return false;
      });
      scan(kVehicleCalls, [&](const std::string& fn, const std::string& ref, std::string* why) {
        if (definitionExists(ref, "vehicles", why)) return true;
        *why = "vehicle." + fn + "(\"" + ref + "\"): no such vehicle: " + *why;
        return false;
      });
      scan(kActionCalls, [&](const std::string& fn, const std::string& name, std::string* why) {
        if (actions.findAction(name)) return true;
        std::string known;
        for (const input::ActionDef& a : actions.actions) known += (known.empty() ? "" : ", ") + a.name;
        *why = "input." + fn + "(\"" + name + "\"): no such action in bindings.lua of this mod, its dependencies "
               "or base (known: " + (known.empty() ? std::string("none") : known) + ")";
        return false;
      });
      auto asset = [&](const std::string& fn, const std::string& ref, std::string* why) {
        if (assetExists(ref, why)) return true;
        *why = fn + " \"" + ref + "\": " + *why;
        return false;
      };
      scan(kAssetCalls, asset);
      scan(kAssetFields, asset);
    }
  }
}

}  // namespace

std::vector<ModProblem> checkMod(const std::string& dir) {
  fs::path parent = fs::absolute(fs::path(dir)).lexically_normal();
  if (!parent.has_filename()) parent = parent.parent_path();  // "mods/x/"
  return checkMod(dir, {parent.parent_path().string()});
}

std::vector<ModProblem> checkMod(const std::string& dir, const std::vector<std::string>& searchDirs) {
  std::vector<ModProblem> problems;
  if (!fs::is_directory(dir)) {
    problems.push_back({dir, 0, "not a folder", ""});
    return problems;
  }
  ModInfo info;
  std::size_t before = problems.size();
  bool manifestOk = readManifest(dir, info, problems) && problems.size() == before;
  // Dependencies: this mod among the others in the search folders.
  std::vector<ModInfo> bindingMods;  // base and this mod's dependencies, in load order, then this mod
  std::vector<ModInfo> allMods;      // every loadable mod (emitters, vehicles, assets by "mod:name")
  if (manifestOk) {
    std::vector<ModProblem> ignored, resolved;
    std::vector<ModInfo> mods = collect(searchDirs, ignored);
    info.dir = dir;
    auto it = std::find_if(mods.begin(), mods.end(), [&](const ModInfo& m) { return m.name == info.name; });
    if (it != mods.end()) *it = info;
    else mods.push_back(info);
    std::vector<ModInfo> ordered = resolve(mods, resolved);
    allMods = ordered;
    std::set<std::string> wanted{"base"};
    for (const ModDependency& d : info.depends) wanted.insert(d.name);
    for (auto m = ordered.rbegin(); m != ordered.rend(); ++m)  // dependents come after their dependencies
      if (wanted.count(m->name))
        for (const ModDependency& d : m->depends) wanted.insert(d.name);
    for (const ModInfo& m : ordered)
      if (wanted.count(m.name) && m.name != info.name) bindingMods.push_back(m);
    bindingMods.push_back(info);
    for (ModProblem& p : resolved) {
      if (p.mod != info.name) continue;
      p.file = (fs::path(dir) / "mod.lua").string();
      problems.push_back(std::move(p));
    }
  }
  // Every Lua file must compile (syntax); emitter files must also be valid.
  std::vector<fs::path> files;
  for (auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".lua") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    if (file.filename() == "mod.lua" && file.parent_path() == fs::path(dir)) continue;
    LuaVm vm(VmLimits{8u << 20, 1'000'000});
    lua_State* L = vm.state();
    if (LuaVm::loadFile(L, std::string(file.c_str())) != LUA_OK) {
      ScriptError e = LuaVm::parseError(info.name, lua_tostring(L, -1), "");
      problems.push_back({file.string(), e.line, e.message, info.name});
    } else if (file.parent_path().lexically_normal() == (fs::path(dir) / "emitters").lexically_normal()) {
      // Emitter definitions are data: run them and check every field.
      for (ModProblem& p : checkEmitterFile(file.string(), info.name)) problems.push_back(std::move(p));
    }
  }
  // bindings.lua: every action, context and binding (a syntax error there
  // was reported above already).
  if (manifestOk) {
    ModBindings bindings = loadBindings(bindingMods);
    const fs::path own = fs::path(dir) / "bindings.lua";
    for (ModProblem& p : bindings.problems) {
      if (fs::path(p.file) != own) continue;  // a dependency's problems are its own check's
      bool seen = std::any_of(problems.begin(), problems.end(), [&](const ModProblem& q) {
        return q.line == p.line && q.message == p.message && fs::path(q.file) == fs::path(p.file);
      });
      if (!seen) problems.push_back(std::move(p));
    }
    checkReferences(info, files, allMods, bindings.set, problems);
  }
  return problems;
}

ModRegistry ModRegistry::discover(const std::vector<std::string>& searchDirs) {
  ModRegistry reg;
  std::vector<ModInfo> mods = collect(searchDirs, reg.m_problems);
  reg.m_mods = resolve(mods, reg.m_problems);
  return reg;
}

const ModInfo* ModRegistry::find(const std::string& name) const {
  for (const ModInfo& m : m_mods)
    if (m.name == name) return &m;
  return nullptr;
}

std::vector<std::string> ModRegistry::listLua(const ModInfo& mod, const std::string& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (auto& entry : fs::directory_iterator(fs::path(mod.dir) / folder, ec))
    if (entry.is_regular_file() && entry.path().extension() == ".lua") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

Result<std::pair<std::string, std::string>> parseScenarioRef(const std::string& ref) {
  // [MOD:]SCENARIO, each a run of letters, digits, '_' and '-'.
  const std::size_t colon = ref.find(':');
  const std::string mod = colon == std::string::npos ? std::string("base") : ref.substr(0, colon);
  const std::string name = colon == std::string::npos ? ref : ref.substr(colon + 1);
  // Both become file names: bounded, so no path is too long for the system.
  auto valid = [](const std::string& s) {
    return !s.empty() && s.size() <= kMaxModNameChars && std::all_of(s.begin(), s.end(), isNameChar);
  };
  if (!valid(mod) || !valid(name))
    return makeError("scenario \"" + clipped(ref) + "\" is not of the form MOD:SCENARIO (for example base:drop; each name at most " +
                     std::to_string(kMaxModNameChars) + " letters, digits, '_' or '-')");
  return std::make_pair(mod, name);
}

}  // namespace tumble::script
