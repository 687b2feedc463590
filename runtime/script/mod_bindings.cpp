#include "script/sandbox.h"
#include "script/mod_bindings.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>

#include "core/file_util.h"
#include "script/internal/lua_util.h"
#include "script/lua_vm.h"

namespace tumble::script {

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kTopFields{"contexts"};
const std::vector<std::string> kContextFields{"priority", "enabled", "actions"};
const std::vector<std::string> kActionFields{"type", "label", "bindings", "dead_zone", "curve", "invert", "scale"};
const std::vector<std::string> kBindingFields{"dead_zone", "curve", "invert", "scale"};

// Reads a bindings.lua table with the Lua state's stack as the cursor.
class Reader {
 public:
  Reader(lua_State* L, const ModInfo& mod, std::string file, std::string text, std::vector<ModProblem>& problems)
      : m_L(L), m_mod(mod), m_file(std::move(file)), m_text(std::move(text)), m_problems(problems) {}

  void top(input::BindingSet& out) {
    if (!lua_istable(m_L, -1)) {
      problem(0, "must return a table {contexts = {NAME = {priority = N, actions = {...}}}}");
      return;
    }
    checkFields(-1, kTopFields, "");
    rawGetField(m_L, -1, "contexts");
    if (!lua_istable(m_L, -1)) {
      problem(0, "contexts: expected a table of contexts, e.g. contexts = {vehicle = {priority = 10, actions = {...}}}");
    } else {
      for (const std::string& name : inFileOrder(sortedKeys(-1, "contexts"), 1)) {
        rawGetField(m_L, -1, name.c_str());
        context(name, out);
        lua_pop(m_L, 1);
      }
    }
    lua_pop(m_L, 1);
  }

 private:
  void problem(int line, std::string message) { m_problems.push_back({m_file, line, std::move(message), m_mod.name}); }

  // Line of the first "name =" (or ["name"] =) in the file, 0 if not found:
  // tables carry no line numbers, the text does.
  int lineOf(const std::string& name, int fromLine = 1) const {
    const std::string quoted = "[\"" + name + "\"]";
    int line = 1;
    std::size_t start = 0;
    while (start <= m_text.size()) {
      std::size_t end = m_text.find('\n', start);
      std::string l = m_text.substr(start, end == std::string::npos ? std::string::npos : end - start);
      std::size_t p = l.find(quoted);
      std::size_t after = p == std::string::npos ? std::string::npos : p + quoted.size();
      if (p == std::string::npos) {
        for (p = l.find(name); p != std::string::npos; p = l.find(name, p + 1)) {
          bool wordStart = p == 0 || !(std::isalnum(static_cast<unsigned char>(l[p - 1])) || l[p - 1] == '_');
          std::size_t q = p + name.size();
          bool wordEnd = q >= l.size() || !(std::isalnum(static_cast<unsigned char>(l[q])) || l[q] == '_');
          if (wordStart && wordEnd) {
            after = q;
            break;
          }
        }
      }
      if (after != std::string::npos && line >= fromLine) {
        std::size_t eq = l.find_first_not_of(" \t", after);
        if (eq != std::string::npos && l[eq] == '=') return line;
      }
      if (end == std::string::npos) break;
      start = end + 1;
      ++line;
    }
    return 0;
  }

  std::vector<std::string> sortedKeys(int idx, const std::string& where) {
    idx = lua_absindex(m_L, idx);
    std::vector<std::string> keys;
    lua_pushnil(m_L);
    while (lua_next(m_L, idx)) {
      if (lua_type(m_L, -2) == LUA_TSTRING) keys.emplace_back(lua_tostring(m_L, -2));
      else problem(0, where + ": keys must be names (strings), found a " + luaL_typename(m_L, -2) + " key");
      lua_pop(m_L, 1);
    }
    std::sort(keys.begin(), keys.end());
    return keys;
  }

  // Lua tables forget the order they were written in; the menu and `tumble
  // list` should not. Names sort by the line that declares them (from
  // fromLine on), then by name.
  std::vector<std::string> inFileOrder(std::vector<std::string> names, int fromLine) const {
    std::vector<std::pair<int, std::string>> keyed;
    for (auto& n : names) {
      int l = lineOf(n, fromLine);
      keyed.emplace_back(l == 0 ? INT32_MAX : l, std::move(n));
    }
    std::stable_sort(keyed.begin(), keyed.end());
    std::vector<std::string> out;
    for (auto& [l, n] : keyed) out.push_back(std::move(n));
    return out;
  }

  void checkFields(int idx, const std::vector<std::string>& known, const std::string& where, int skipArray = 0) {
    idx = lua_absindex(m_L, idx);
    lua_pushnil(m_L);
    while (lua_next(m_L, idx)) {
      if (lua_type(m_L, -2) == LUA_TSTRING) {
        std::string k = lua_tostring(m_L, -2);
        if (std::find(known.begin(), known.end(), k) == known.end())
          problem(lineOf(k), (where.empty() ? "" : where + ": ") +
                                 unknownFieldMessage(k, std::set<std::string>(known.begin(), known.end())));
      } else if (!(lua_isinteger(m_L, -2) && lua_tointeger(m_L, -2) >= 1 && lua_tointeger(m_L, -2) <= skipArray)) {
        problem(0, (where.empty() ? std::string("top level") : where) + ": unexpected list entry");
      }
      lua_pop(m_L, 1);
    }
  }

  // An identifier, or two joined by one dot ("vehicle.throttle"); checked
  // by hand, not with a regular expression over the mod's text.
  bool validName(const std::string& name) const {
    if (name.size() > 128) return false;
    int dots = 0;
    bool atStart = true;
    for (char c : name) {
      const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
      if (c == '.') {
        if (atStart || ++dots > 1) return false;
        atStart = true;
      } else if (letter || (!atStart && c >= '0' && c <= '9')) {
        atStart = false;
      } else {
        return false;
      }
    }
    return !atStart;
  }

  void context(const std::string& name, input::BindingSet& out) {
    const std::string where = "contexts." + name;
    const int line = lineOf(name);
    if (!validName(name) || name.find('.') != std::string::npos) {
      problem(line, where + ": a context name is a plain identifier like vehicle or menu_ui");
      return;
    }
    if (!lua_istable(m_L, -1)) {
      problem(line, where + ": expected a table {priority = N, enabled = true, actions = {...}}");
      return;
    }
    checkFields(-1, kContextFields, where);
    input::ContextDef c;
    c.name = name;
    rawGetField(m_L, -1, "priority");
    if (lua_isinteger(m_L, -1)) c.priority = int(lua_tointeger(m_L, -1));
    else if (!lua_isnil(m_L, -1))
      problem(lineOf("priority", line), where + ".priority: expected an integer (higher wins a shared key)");
    lua_pop(m_L, 1);
    rawGetField(m_L, -1, "enabled");
    if (lua_isboolean(m_L, -1)) c.enabled = lua_toboolean(m_L, -1);
    else if (!lua_isnil(m_L, -1)) problem(lineOf("enabled", line), where + ".enabled: expected true or false");
    lua_pop(m_L, 1);
    out.contexts.push_back(c);
    rawGetField(m_L, -1, "actions");
    if (!lua_istable(m_L, -1)) {
      problem(line, where + ".actions: expected a table of actions, e.g. actions = {jump = {type = \"button\", "
                            "bindings = {\"key:Space\", \"pad:a\"}}}");
    } else {
      for (const std::string& a : inFileOrder(sortedKeys(-1, where + ".actions"), line)) {
        rawGetField(m_L, -1, a.c_str());
        action(a, name, out);
        lua_pop(m_L, 1);
      }
    }
    lua_pop(m_L, 1);
  }

  // dead_zone, curve, invert, scale of the table on top into m; false on a problem.
  bool modifiers(input::Modifiers& m, const std::string& where, int line) {
    bool ok = true;
    auto number = [&](const char* key, double* out, double lo, double hi, const char* what) {
      rawGetField(m_L, -1, key);
      if (lua_type(m_L, -1) == LUA_TNUMBER) {
        double v = lua_tonumber(m_L, -1);
        if (v >= lo && v <= hi) *out = v;
        else ok = false, problem(line, where + "." + key + ": " + what);
      } else if (!lua_isnil(m_L, -1)) {
        ok = false, problem(line, where + "." + key + ": expected a number, " + what);
      }
      lua_pop(m_L, 1);
    };
    number("dead_zone", &m.deadZone, 0, 0.95, "a fraction of travel in 0..0.95");
    number("curve", &m.curve, 0.2, 5, "a response exponent in 0.2..5");
    number("scale", &m.scale, -1e6, 1e6, "a finite factor");
    rawGetField(m_L, -1, "invert");
    if (lua_isboolean(m_L, -1)) m.invert = lua_toboolean(m_L, -1);
    else if (!lua_isnil(m_L, -1)) ok = false, problem(line, where + ".invert: expected true or false");
    lua_pop(m_L, 1);
    return ok;
  }

  void action(const std::string& name, const std::string& ctx, input::BindingSet& out) {
    const std::string where = "action \"" + name + "\"";
    const int line = lineOf(name);
    if (!validName(name)) {
      problem(line, where + ": an action name is an identifier like throttle (other mods: \"" + m_mod.name +
                        ".throttle\")");
      return;
    }
    if (!lua_istable(m_L, -1)) {
      problem(line, where + ": expected a table {type = \"button\" or \"axis\", bindings = {...}}");
      return;
    }
    checkFields(-1, kActionFields, where);
    input::ActionDef a;
    a.name = name;
    a.context = ctx;
    a.mod = m_mod.name;
    rawGetField(m_L, -1, "type");
    std::string type = lua_type(m_L, -1) == LUA_TSTRING ? lua_tostring(m_L, -1) : "";
    lua_pop(m_L, 1);
    if (type == "axis") a.type = input::ActionType::Axis;
    else if (type != "button") {
      problem(line, where + ".type: expected \"button\" (0..1, down/pressed/released) or \"axis\" (-1..1)" +
                        (type.empty() ? std::string() : ", got \"" + type + "\""));
      return;
    }
    rawGetField(m_L, -1, "label");
    if (lua_type(m_L, -1) == LUA_TSTRING) a.label = lua_tostring(m_L, -1);
    else if (!lua_isnil(m_L, -1)) problem(line, where + ".label: expected a string");
    lua_pop(m_L, 1);
    modifiers(a.modifiers, where, line);
    rawGetField(m_L, -1, "bindings");
    if (!lua_istable(m_L, -1)) {
      if (!lua_isnil(m_L, -1)) problem(line, where + ".bindings: expected a list like {\"key:W\", \"pad:a\"}");
    } else {
      lua_Integer n = lua_Integer(lua_rawlen(m_L, -1));
      checkFields(-1, {}, where + ".bindings", int(n));
      for (lua_Integer i = 1; i <= n; ++i) {
        lua_rawgeti(m_L, -1, i);
        binding(a, where + ".bindings[" + std::to_string(i) + "]", line);
        lua_pop(m_L, 1);
      }
    }
    lua_pop(m_L, 1);
    out.actions.push_back(std::move(a));
  }

  void binding(input::ActionDef& a, const std::string& where, int line) {
    std::string text;
    input::Modifiers m = a.modifiers;
    if (lua_type(m_L, -1) == LUA_TSTRING) {
      text = lua_tostring(m_L, -1);
    } else if (lua_istable(m_L, -1)) {
      lua_rawgeti(m_L, -1, 1);
      if (lua_type(m_L, -1) == LUA_TSTRING) text = lua_tostring(m_L, -1);
      lua_pop(m_L, 1);
      checkFields(-1, kBindingFields, where, 1);
      if (!modifiers(m, where, line)) return;
    }
    if (text.empty()) {
      problem(line, where + ": expected a binding like \"key:W\" or {\"pad_axis:leftx\", dead_zone = 0.15}");
      return;
    }
    auto b = input::parseBinding(text);
    if (!b) {
      problem(line, where + ": " + b.error());
      return;
    }
    if (b->pair && a.type != input::ActionType::Axis) {
      problem(line, where + ": \"" + text + "\" is a key pair (-1 / +1), which only an axis takes; give a button one key");
      return;
    }
    // Modifiers written in the text win over the table's and the action's.
    if (b->modifiers == input::Modifiers{}) b->modifiers = m;
    a.bindings.push_back(*b);
  }

  lua_State* m_L;
  const ModInfo& m_mod;
  std::string m_file, m_text;
  std::vector<ModProblem>& m_problems;
};

}  // namespace

ModBindings loadModBindings(const ModInfo& mod) {
  ModBindings out;
  const fs::path path = fs::path(mod.dir) / "bindings.lua";
  std::error_code ec;
  if (!fs::exists(path, ec)) return out;
  out.present = true;
  auto text = readTextFile(path.string());
  if (!text) {
    out.problems.push_back({path.string(), 0, text.error(), mod.name});
    return out;
  }
  VmLimits limits;
  limits.memoryBytes = 8u << 20;
  limits.instructionsPerCall = 1'000'000;
  LuaVm vm(limits);
  lua_State* L = vm.state();
  if (luaL_loadbufferx(L, text->data(), text->size(), ("@" + path.string()).c_str(), "t") != LUA_OK) {
    ScriptError e = LuaVm::parseError(mod.name, lua_tostring(L, -1), "");
    out.problems.push_back({path.string(), e.line, e.message, mod.name});
    return out;
  }
  pushDataEnvironment(L);  // private math, string and table: data, no world
  lua_setupvalue(L, -2, 1);
  ScriptError err;
  if (!vm.call(0, 1, mod.name, "bindings.lua", "top level", &err)) {
    out.problems.push_back({path.string(), err.line, err.message, mod.name});
    return out;
  }
  Reader(L, mod, path.string(), *text, out.problems).top(out.set);
  lua_pop(L, 1);
  return out;
}

ModBindings loadBindings(const std::vector<ModInfo>& mods) {
  ModBindings out;
  for (const ModInfo& mod : mods) {
    ModBindings one = loadModBindings(mod);
    out.present = out.present || one.present;
    out.problems.insert(out.problems.end(), one.problems.begin(), one.problems.end());
    const std::string file = (fs::path(mod.dir) / "bindings.lua").string();
    input::BindingSet accepted;
    accepted.contexts = one.set.contexts;
    for (input::ActionDef& a : one.set.actions) {
      const bool known = out.set.findAction(a.name) != nullptr;
      if (!known && mod.name != "base" && a.name.rfind(mod.name + ".", 0) != 0) {
        out.problems.push_back({file, 0,
                                "action \"" + a.name + "\": a new action of mod " + mod.name + " must be named \"" +
                                    mod.name + "." + a.name.substr(a.name.rfind('.') + 1) +
                                    "\" (only base declares plain names; re-declaring an existing action changes "
                                    "its default bindings)",
                                mod.name});
        continue;
      }
      accepted.actions.push_back(std::move(a));
    }
    std::vector<std::string> merged;
    input::mergeBindings(out.set, accepted, merged);
    for (auto& m : merged) out.problems.push_back({file, 0, std::move(m), mod.name});
  }
  return out;
}

}  // namespace tumble::script
