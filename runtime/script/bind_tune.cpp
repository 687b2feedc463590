// Lua table `tune`: tunables a designer changes while playing (the tuning
// panel, F2), from the command line (--set tune.NAME=VALUE) or a saved
// overrides file. The values live in the host's Tunables (tunables.h).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module tune
/// Values a designer can change while the scenario runs, without a restart:
/// the tuning panel (F2, or the HUD's "Tune" button) shows every declared
/// tunable; `--set tune.NAME=VALUE` sets one for a headless run; the panel's
/// "Save" writes them to the mod's overrides file (in ~/.config/tumble/tune/,
/// or $TUMBLE_CONFIG_DIR/tune/), which is loaded the next time the mod runs.
/// Each call returns the *live* value, so read it where you use it (e.g. in
/// on_update) and a change applies at the next step. Calling it again with
/// the same arguments is cheap; a hot reload with a new default applies the
/// new default unless the user has set a value.

namespace {

// Throws for any key of the options table at idx that is not in `allowed`:
// a misspelt option must not silently do nothing.
// `fn` names the call for the message ("tune.number" and the name at stack
// index 1); it is only built when there is an error, keeping the common path
// free of allocations.
std::string callName(lua_State* L, const char* fn) { return std::string(fn) + "(\"" + lua_tostring(L, 1) + "\")"; }


std::string checkName(lua_State* L, const char* fn) {
  if (lua_type(L, 1) != LUA_TSTRING || lua_rawlen(L, 1) == 0)
    throw LuaArgError(std::string(fn) + ": argument 1 must be the tunable's name (a non-empty string)");
  return lua_tostring(L, 1);
}

// Declares, reports any pending problems, and pushes the live value.
int declareAndPush(lua_State* L, Tunable spec) {
  ScenarioHost* host = ScenarioHost::from(L);
  auto declared = host->tunables().declare(std::move(spec));
  if (!declared) throw LuaArgError(declared.error());
  host->reportTuneProblems();
  const Tunable& t = host->tunables()[*declared];
  switch (t.kind) {
    case Tunable::Kind::Number: lua_pushnumber(L, t.value()); break;
    case Tunable::Kind::Bool: lua_pushboolean(L, t.value() != 0); break;
    case Tunable::Kind::Choice: lua_pushstring(L, t.valueText().c_str()); break;
  }
  return 1;
}

int optionsIndex(lua_State* L, const char* fn, int idx) {
  if (lua_isnoneornil(L, idx)) return 0;
  if (!lua_istable(L, idx))
    throw LuaArgError(callName(L, fn) + ": argument " + std::to_string(idx) + " must be an options table");
  return idx;
}

/// @function tune.number
/// Declares a number tunable (first call) and returns its live value.
/// @param name string unique within the mod; also the key for --set tune.NAME
/// @param default number the value until someone changes it
/// @param opts? table {min = number, max = number, step = number, unit = string, description = string}; the panel's slider spans min..max
/// @return number the live value
/// @example local g = tune.number("gravity", 9.81, {min = 0, max = 20, unit = "m/s^2"})
int tuneNumber(lua_State* L) {
  const char* fn = "tune.number";
  Tunable t;
  t.name = checkName(L, fn);
  t.kind = Tunable::Kind::Number;
  if (lua_type(L, 2) != LUA_TNUMBER || !std::isfinite(lua_tonumber(L, 2)))
    throw LuaArgError(callName(L, fn) + ": argument 2 (the default) must be a finite number");
  t.defaultValue = lua_tonumber(L, 2);
  if (int o = optionsIndex(L, fn, 3)) {
    checkFields(L, o, callName(L, fn), {"min", "max", "step", "unit", "description"});
    t.min = optNumberField(L, o, "min", t.min);
    t.max = optNumberField(L, o, "max", t.max);
    t.step = optNumberField(L, o, "step", 0);
    t.unit = optStringField(L, o, "unit", "");
    t.description = optStringField(L, o, "description", "");
  }
  return declareAndPush(L, std::move(t));
}

/// @function tune.bool
/// Declares an on/off tunable (first call) and returns its live value.
/// @param name string unique within the mod
/// @param default boolean
/// @param opts? table {description = string}
/// @return boolean the live value
/// @example if tune.bool("wind", false) then body:apply_force({5, 0, 0}) end
int tuneBool(lua_State* L) {
  const char* fn = "tune.bool";
  Tunable t;
  t.name = checkName(L, fn);
  if (!lua_isboolean(L, 2)) throw LuaArgError(callName(L, fn) + ": argument 2 (the default) must be true or false");
  t.kind = Tunable::Kind::Bool;
  t.defaultValue = lua_toboolean(L, 2) ? 1 : 0;
  if (int o = optionsIndex(L, fn, 3)) {
    checkFields(L, o, callName(L, fn), {"description"});
    t.description = optStringField(L, o, "description", "");
  }
  return declareAndPush(L, std::move(t));
}

/// @function tune.choice
/// Declares a tunable that is one of a few strings (first call) and returns
/// the chosen one.
/// @param name string unique within the mod
/// @param default string one of the choices
/// @param opts table {choices = {string, ...}, description = string}
/// @return string the live choice
/// @example local mode = tune.choice("difficulty", "normal", {choices = {"easy", "normal", "hard"}})
int tuneChoice(lua_State* L) {
  const char* fn = "tune.choice";
  std::string name = checkName(L, fn);
  if (lua_type(L, 2) != LUA_TSTRING)
    throw LuaArgError(callName(L, fn) + ": argument 2 (the default) must be a string");
  std::string def = lua_tostring(L, 2);
  int o = optionsIndex(L, fn, 3);
  if (!o) throw LuaArgError(callName(L, fn) + ": argument 3 must be {choices = {\"a\", \"b\", ...}}");
  checkFields(L, o, callName(L, fn), {"choices", "description"});
  Tunable t;
  t.name = name;
  t.kind = Tunable::Kind::Choice;
  t.description = optStringField(L, o, "description", "");
  rawGetField(L, o, "choices");
  if (!lua_istable(L, -1)) throw LuaArgError(callName(L, fn) + ": choices must be a list of strings");
  for (lua_Integer i = 1, n = rawLength(L, -1); i <= n; ++i) {
    lua_rawgeti(L, -1, i);
    if (lua_type(L, -1) != LUA_TSTRING)
      throw LuaArgError(callName(L, fn) + ": choices[" + std::to_string(i) + "] must be a string");
    t.choices.emplace_back(lua_tostring(L, -1));
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  auto it = std::find(t.choices.begin(), t.choices.end(), def);
  if (it == t.choices.end())
    throw LuaArgError(callName(L, fn) + ": the default \"" + def + "\" is not one of the choices");
  t.defaultValue = double(it - t.choices.begin());
  return declareAndPush(L, std::move(t));
}

/// @function tune.get
/// The live value of a tunable declared earlier (by any scenario code).
/// @param name string
/// @return number|boolean|string the live value
/// @example local g = tune.get("gravity")
int tuneGet(lua_State* L) {
  std::string name = checkName(L, "tune.get");
  ScenarioHost* host = ScenarioHost::from(L);
  int i = host->tunables().find(name);
  if (i < 0)
    throw LuaArgError("tune.get(\"" + name + "\"): not declared; declare it first with tune.number/bool/choice");
  const Tunable& t = host->tunables()[i];
  switch (t.kind) {
    case Tunable::Kind::Number: lua_pushnumber(L, t.value()); break;
    case Tunable::Kind::Bool: lua_pushboolean(L, t.value() != 0); break;
    case Tunable::Kind::Choice: lua_pushstring(L, t.valueText().c_str()); break;
  }
  return 1;
}

const luaL_Reg kTune[] = {
    {"number", guarded<tuneNumber>},
    {"bool", guarded<tuneBool>},
    {"choice", guarded<tuneChoice>},
    {"get", guarded<tuneGet>},
    {nullptr, nullptr},
};

}  // namespace

void openTuneBindings(lua_State* L, int envIndex) {
  registerModule(L, envIndex, "tune", kTune);
}

}  // namespace tumble::script
