// The scenario's global functions that are not a module: print, expect,
// param and hud_text (each documented at its binding).
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/log.h"
#include "script/internal/bindings.h"
#include "script/internal/lua_util.h"
#include "script/scenario_host.h"

namespace tumble::script {

namespace {

/// @function print
/// Writes its arguments, separated by tabs, to the log as "mod NAME: ...".
/// @param ... any values, converted with tostring
/// @example print("spawned", world.body_count(), "bodies")
int luaPrint(lua_State* L) {
  ScenarioHost* host = ScenarioHost::from(L);
  std::string line;
  int n = lua_gettop(L);
  for (int i = 1; i <= n; ++i) {
    if (i > 1) line += '\t';
    line += toDisplayString(L, i);
  }
  log::info("mod " + (host ? host->mod().name : std::string("?")) + ": " + line);
  return 0;
}

/// @function expect
/// Records an expectation that lands in the run report; a failed one makes
/// `tumble run` exit with status 2. A boolean without limits must be true; a
/// number needs limits.
/// @param name string what is checked, shown in the report
/// @param value number|boolean the measured value
/// @param limits? table {min = number, max = number}, inclusive
/// @return boolean whether the expectation held
/// @example expect("ball bounced back", ball:position().y, {min = 0.8, max = 1.2})
int luaExpect(lua_State* L) {
  ScenarioHost* host = ScenarioHost::from(L);
  Expectation e;
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError("expect: argument 1 must be the expectation's name (a string)");
  e.name = lua_tostring(L, 1);
  if (lua_isboolean(L, 2)) {
    e.isBool = true;
    e.value = lua_toboolean(L, 2) ? 1 : 0;
  } else if (lua_type(L, 2) == LUA_TNUMBER) {
    e.value = lua_tonumber(L, 2);
  } else {
    throw LuaArgError("expect(\"" + e.name + "\"): argument 2 must be a number or a boolean, got " +
                      luaL_typename(L, 2));
  }
  if (lua_istable(L, 3)) {
    rawGetField(L, 3, "min");
    if (lua_type(L, -1) == LUA_TNUMBER) e.min = lua_tonumber(L, -1);
    lua_pop(L, 1);
    rawGetField(L, 3, "max");
    if (lua_type(L, -1) == LUA_TNUMBER) e.max = lua_tonumber(L, -1);
    lua_pop(L, 1);
  } else if (!lua_isnoneornil(L, 3)) {
    throw LuaArgError("expect(\"" + e.name + "\"): argument 3 must be a table {min = ..., max = ...}");
  }
  if (e.isBool && !e.min && !e.max) {
    e.ok = e.value == 1;
  } else if (!e.min && !e.max) {
    throw LuaArgError("expect(\"" + e.name + "\"): a number needs limits, e.g. expect(name, v, {min = 0, max = 1})");
  } else {
    e.ok = std::isfinite(e.value) && (!e.min || e.value >= *e.min) && (!e.max || e.value <= *e.max);
  }
  lua_pushboolean(L, e.ok);
  host->addExpectation(std::move(e));
  return 1;
}

// Pushes the declared default of `name` as index 2 (replacing a nil), so
// param(name) converts to the declared type.
void pushDeclaredDefault(lua_State* L, const ScenarioHost& host, const std::string& name) {
  const ParamDecls& decls = host.declaredParams();
  if (!decls || !lua_isnoneornil(L, 2)) return;
  auto it = std::find_if(decls->begin(), decls->end(), [&](const ParamDecl& d) { return d.name == name; });
  if (it == decls->end()) {
    std::string known;
    for (const ParamDecl& d : *decls) known += (known.empty() ? "" : ", ") + d.name;
    throw LuaArgError("param(\"" + name + "\"): not in the scenario's params table (declared: " +
                      (known.empty() ? "none" : known) + "); declare it there or pass a default");
  }
  lua_settop(L, 1);
  switch (it->type) {
    case ParamDecl::Type::Number: lua_pushnumber(L, std::strtod(it->defaultText.c_str(), nullptr)); break;
    case ParamDecl::Type::Boolean: lua_pushboolean(L, it->defaultText == "true"); break;
    default: lua_pushstring(L, it->defaultText.c_str());
  }
}

/// @function param
/// A scenario parameter from the command line (`--set name=value`),
/// converted to the type of the default; the default when not given.
/// Without a default, the one the scenario's `params` table declares.
/// @param name string parameter name
/// @param default any? returned when absent; its type (number, boolean, string) decides the conversion; may be left out when the scenario declares the parameter in `params`
/// @return any the value
/// @example local count = param("count", 10)  -- tumble run mymod:rain --set count=50
int luaParam(lua_State* L) {
  ScenarioHost* host = ScenarioHost::from(L);
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError("param: argument 1 must be the parameter's name");
  const int nargs = lua_gettop(L);
  std::string name = lua_tostring(L, 1);
  pushDeclaredDefault(L, *host, name);  // the default is at index 2 from here on
  // Leaves exactly the arguments and one result (the value on top), as every
  // binding must (the debug stack check).
  auto result = [&]() {
    if (lua_gettop(L) > nargs + 1) {
      lua_replace(L, nargs + 1);
      lua_settop(L, nargs + 1);
    }
    return 1;
  };
  auto it = host->options().params.find(name);
  if (it == host->options().params.end()) {
    lua_pushvalue(L, 2);
    return result();
  }
  const std::string& text = it->second;
  switch (lua_type(L, 2)) {
    case LUA_TNUMBER: {
      char* end = nullptr;
      double v = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != 0 || !std::isfinite(v))
        throw LuaArgError("--set " + name + "=" + text + ": expected a number");
      lua_pushnumber(L, v);
      return result();
    }
    case LUA_TBOOLEAN:
      if (text != "true" && text != "false") throw LuaArgError("--set " + name + "=" + text + ": expected true or false");
      lua_pushboolean(L, text == "true");
      return result();
    default: lua_pushstring(L, text.c_str()); return result();
  }
}

/// @function hud_text
/// Replaces the scenario's lines on the HUD; they stay until the next call.
/// @param ... any one value per line, converted with tostring
/// @example hud_text(("height: %.2f m"):format(ball:position().y))
int luaHudText(lua_State* L) {
  std::vector<std::string> lines;
  for (int i = 1; i <= lua_gettop(L); ++i) {
    lines.push_back(toDisplayString(L, i));
  }
  ScenarioHost::from(L)->setHudText(std::move(lines));
  return 0;
}

const luaL_Reg kGlobals[] = {
    {"print", guarded<luaPrint>},
    {"expect", guarded<luaExpect>},
    {"param", guarded<luaParam>},
    {"hud_text", guarded<luaHudText>},
    {nullptr, nullptr},
};

}  // namespace

void openGlobalBindings(lua_State* L, int envIndex) { registerFunctions(L, envIndex, kGlobals); }

}  // namespace tumble::script
