// Lua table `input`: the mods' named actions (bindings.lua), never raw keys.
// The state is the fixed step's snapshot (input/input_system.h), so every
// callback in a step reads the same values, headless or with a window.
#include <algorithm>
#include <string_view>

#include "input/input_system.h"
#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module input
/// Named actions declared in the mods' bindings.lua files (mods/base/bindings.lua:
/// throttle, brake, steer, handbrake, gear_up, gear_down, reset, camera in context
/// "vehicle"; grab, impulse, more_links, fewer_links, dt_up, dt_down in "interact";
/// pause, screenshot, menu in "game"). Scripts read actions, never keys: the player
/// rebinds them in the bindings menu (F1). Values are sampled once at the start of
/// each fixed step. A button's value is 0..1 and it is down at >= 0.5; an axis is
/// -1..1 (mouse motion: pixels during the step). An unknown action name is an
/// error that suggests close names.

namespace {

int checkAction(lua_State* L, const char* fn) {
  std::size_t len = 0;
  const char* s = lua_type(L, 1) == LUA_TSTRING ? lua_tolstring(L, 1, &len) : nullptr;
  if (!s) throw LuaArgError(std::string("input.") + fn + ": expected an action name (a string), got " + luaL_typename(L, 1));
  const input::InputSystem& in = ScenarioHost::from(L)->input();
  int a = in.find(std::string_view(s, len));
  if (a < 0) throw LuaArgError(std::string("input.") + fn + ": " + in.unknownActionMessage(std::string_view(s, len)));
  return a;
}

/// @function input.value
/// The action's value in this step.
/// @param action string an action name from bindings.lua
/// @return number button 0..1; axis -1..1 (mouse_axis: pixels, wheel: notches)
/// @example local steer = input.value("steer")
int inputValue(lua_State* L) {
  int a = checkAction(L, "value");
  lua_pushnumber(L, ScenarioHost::from(L)->input().value(a));
  return 1;
}

/// @function input.down
/// Whether the action is held in this step (|value| >= 0.5).
/// @param action string an action name
/// @return boolean
/// @example if input.down("handbrake") then car:brake(1) end
int inputDown(lua_State* L) {
  int a = checkAction(L, "down");
  lua_pushboolean(L, ScenarioHost::from(L)->input().down(a));
  return 1;
}

/// @function input.pressed
/// True in the one step the action went down. A tap shorter than a frame
/// still counts once.
/// @param action string an action name
/// @return boolean
/// @example if input.pressed("reset") then reset_car() end
int inputPressed(lua_State* L) {
  int a = checkAction(L, "pressed");
  lua_pushboolean(L, ScenarioHost::from(L)->input().pressed(a));
  return 1;
}

/// @function input.released
/// True in the one step the action came up.
/// @param action string an action name
/// @return boolean
/// @example if input.released("grab") then drop_part() end
int inputReleased(lua_State* L) {
  int a = checkAction(L, "released");
  lua_pushboolean(L, ScenarioHost::from(L)->input().released(a));
  return 1;
}

/// @function input.set_context
/// Switches a context (a group of actions) on or off. Off, its actions read
/// 0 and its keys go to lower-priority contexts. "vehicle" and "interact"
/// start off; a scenario switches on what it uses.
/// @param name string a context from bindings.lua ("vehicle", "interact", "game")
/// @param enabled boolean
/// @example input.set_context("vehicle", true)
int inputSetContext(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError("input.set_context: expected a context name (a string)");
  if (!lua_isboolean(L, 2)) throw LuaArgError("input.set_context: argument 2 must be true or false");
  Status st = ScenarioHost::from(L)->input().setContextEnabled(lua_tostring(L, 1), lua_toboolean(L, 2));
  if (!st) throw LuaArgError("input.set_context: " + st.error());
  return 0;
}

/// @function input.context_enabled
/// @param name string a context name
/// @return boolean whether it is on
int inputContextEnabled(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError("input.context_enabled: expected a context name (a string)");
  const input::InputSystem& in = ScenarioHost::from(L)->input();
  auto names = in.contextNames();
  std::string name = lua_tostring(L, 1);
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw LuaArgError("input.context_enabled: unknown input context \"" + name + "\"" + input::didYouMean(name, names));
  lua_pushboolean(L, in.contextEnabled(name));
  return 1;
}

/// @function input.inject
/// Drives an action from the script (autopilots, tests, replays): from the
/// next step on it reads this value whatever the player does; nil gives it
/// back to the devices. Headless runs have no devices, so this is how they
/// press buttons; the same injections give the same run.
/// @param action string an action name
/// @param value number|boolean|nil the value (true = 1, false = 0), nil to stop
/// @example input.inject("throttle", 1)  -- full throttle from the next step
int inputInject(lua_State* L) {
  int a = checkAction(L, "inject");
  input::InputSystem& in = ScenarioHost::from(L)->input();
  if (lua_isnoneornil(L, 2)) in.clearInjection(a);
  else if (lua_isboolean(L, 2)) in.inject(a, lua_toboolean(L, 2) ? 1.0 : 0.0);
  else in.inject(a, checkNumber(L, 2, "input.inject value"));
  return 0;
}

/// @function input.actions
/// Every action this run knows, in declaration order.
/// @return table[] {name = string, type = "button"|"axis", context = string, label = string}
/// @example for _, a in ipairs(input.actions()) do print(a.name, a.context) end
int inputActions(lua_State* L) {
  const input::InputSystem& in = ScenarioHost::from(L)->input();
  lua_createtable(L, in.actionCount(), 0);
  for (int i = 0; i < in.actionCount(); ++i) {
    const input::ActionDef& a = in.action(i);
    lua_createtable(L, 0, 4);
    lua_pushstring(L, a.name.c_str());
    rawSetField(L, -2, "name");
    lua_pushstring(L, a.type == input::ActionType::Axis ? "axis" : "button");
    rawSetField(L, -2, "type");
    lua_pushstring(L, a.context.c_str());
    rawSetField(L, -2, "context");
    lua_pushstring(L, (a.label.empty() ? a.name : a.label).c_str());
    rawSetField(L, -2, "label");
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

/// @function input.pointer
/// Where the mouse pointer is in the window, for picking (grab): x and y in
/// -1..1 (x right, y up), nil without a window or before the mouse moved.
/// @return number? x, -1 (left) .. 1 (right)
/// @return number? y, -1 (bottom) .. 1 (top)
int inputPointer(lua_State* L) {
  auto p = ScenarioHost::from(L)->input().pointer();
  if (!p) {
    lua_pushnil(L);
    return 1;
  }
  lua_pushnumber(L, (*p)[0]);
  lua_pushnumber(L, (*p)[1]);
  return 2;
}

/// @function input.pointer_ray
/// The ray from the camera through the mouse pointer, for grabbing what is
/// under it: cast it with world.raycast. nil without a window.
/// @return Vec3? origin, m (the camera's eye)
/// @return Vec3? unit direction
/// @example local o, d = input.pointer_ray()
/// @example if o and input.pressed("grab") then local hit = world.raycast(o, d, 100) end
int inputPointerRay(lua_State* L) {
  auto ray = ScenarioHost::from(L)->input().pointerRay();
  if (!ray) {
    lua_pushnil(L);
    return 1;
  }
  pushVec3(L, ray->origin_m);
  pushVec3(L, ray->direction);
  return 2;
}

const luaL_Reg kInput[] = {
    {"value", guarded<inputValue>},
    {"down", guarded<inputDown>},
    {"pressed", guarded<inputPressed>},
    {"released", guarded<inputReleased>},
    {"set_context", guarded<inputSetContext>},
    {"context_enabled", guarded<inputContextEnabled>},
    {"inject", guarded<inputInject>},
    {"actions", guarded<inputActions>},
    {"pointer", guarded<inputPointer>},
    {"pointer_ray", guarded<inputPointerRay>},
    {nullptr, nullptr},
};

}  // namespace

void openInputBindings(lua_State* L, int envIndex) {
  registerModule(L, envIndex, "input", kInput);
}

}  // namespace tumble::script
