// Lua table `trigger` and type Trigger: boxes (axis-aligned, or turned by a
// rotation) that report
// bodies entering and leaving (ScenarioHost::runTriggers does the work after
// each physics step).
#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module trigger
/// Trigger volumes: regions that call a function when a body's centre of mass
/// enters or leaves them. Checked after every physics step against every
/// dynamic and kinematic body (static bodies never trigger). Events come
/// after the whole step, enters and exits in body order; a body removed while
/// inside gets its on_exit (with a handle that is no longer valid).

namespace {

constexpr const char* kTriggerMeta = "tumble.Trigger";

struct TriggerRef {
  std::uint32_t id;
};

std::uint32_t checkTrigger(lua_State* L, int idx) {
  auto* ref = static_cast<TriggerRef*>(luaL_testudata(L, idx, kTriggerMeta));
  if (!ref) throw LuaArgError(std::string("expected a Trigger, got ") + luaL_typename(L, idx));
  return ref->id;
}

int optFunctionField(lua_State* L, int t, const char* key, const char* fn) {
  int type = rawGetField(L, t, key);
  if (type == LUA_TNIL) {
    lua_pop(L, 1);
    return 0;
  }
  if (type != LUA_TFUNCTION) {
    std::string got = luaL_typename(L, -1);
    lua_pop(L, 1);
    throw LuaArgError(std::string(fn) + ": field '" + key + "' must be a function, got " + got);
  }
  return lua_gettop(L);
}

/// @class TriggerBoxDef
/// @field center Vec3Arg centre of the box, m
/// @field size Vec3Arg full size along the box's x, y, z, m (each > 0)
/// @field rotation? Vec3Arg rotation vector of the box: axis times angle, rad (as world bodies'; default none: axis-aligned)
/// @field on_enter? fun(body: Body, trigger: Trigger) called when a body's centre enters
/// @field on_exit? fun(body: Body, trigger: Trigger) called when it leaves (or is removed inside)

/// @function trigger.box
/// A box trigger: axis-aligned, or turned by `rotation` (e.g. {0, yaw, 0} for a gate across a road).
/// @param def TriggerBoxDef centre, size and callbacks
/// @return Trigger the trigger
/// @example local goal = trigger.box{center = {0, 1, 20}, size = {4, 2, 1},
/// @example   on_enter = function(body) if body == ball then game.win("goal!") end end}
int triggerBox(lua_State* L) {
  const char* fn = "trigger.box";
  if (!lua_istable(L, 1))
    throw LuaArgError("trigger.box: expected a table, e.g. trigger.box{center = {0, 1, 0}, size = {2, 2, 2}, "
                      "on_enter = function(body) ... end}");
  lua_settop(L, 1);
  checkFields(L, 1, fn, {"center", "size", "rotation", "on_enter", "on_exit"});
  Vec3 center, size;
  Quat orientation = Quat::Identity();
  try {
    if (!optVec3Field(L, 1, "center", &center)) throw LuaArgError("field 'center' is required ({x, y, z}, m)");
    if (!optVec3Field(L, 1, "size", &size)) throw LuaArgError("field 'size' is required ({x, y, z}, m)");
    orientation = optRotationField(L, 1);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  if (size.minCoeff() <= 0) throw LuaArgError("trigger.box: every component of 'size' must be > 0 m");
  int onEnter = optFunctionField(L, 1, "on_enter", fn);
  int onExit = optFunctionField(L, 1, "on_exit", fn);
  std::uint32_t id = ScenarioHost::from(L)->triggers().add(center, size / 2, orientation, onEnter, onExit);
  lua_settop(L, 1);  // the functions are referenced now
  pushTrigger(L, id);
  return 1;
}

/// @class Trigger
/// A handle returned by trigger.box.

/// @function Trigger:remove
/// Removes the trigger; no more events. Bodies inside get no on_exit.
/// @return boolean true if it was still there
int triggerRemove(lua_State* L) {
  lua_pushboolean(L, ScenarioHost::from(L)->triggers().remove(checkTrigger(L, 1)));
  return 1;
}

/// @function Trigger:bodies
/// @return Body[] the bodies inside after the last step, in body order
int triggerBodies(lua_State* L) {
  const auto* inside = ScenarioHost::from(L)->triggers().bodiesIn(checkTrigger(L, 1));
  lua_createtable(L, inside ? int(inside->size()) : 0, 0);
  if (!inside) return 1;
  for (std::size_t i = 0; i < inside->size(); ++i) {
    pushBody(L, (*inside)[i]);
    lua_rawseti(L, -2, lua_Integer(i + 1));
  }
  return 1;
}

/// @function Trigger:contains
/// @param body Body
/// @return boolean whether the body was inside after the last step
int triggerContains(lua_State* L) {
  std::uint32_t id = checkTrigger(L, 1);
  physics::BodyId body;
  if (!testBody(L, 2, &body)) throw LuaArgError(std::string("Trigger:contains: expected a Body, got ") + luaL_typename(L, 2));
  const auto* inside = ScenarioHost::from(L)->triggers().bodiesIn(id);
  bool found = false;
  if (inside)
    for (physics::BodyId b : *inside) found |= b == body;
  lua_pushboolean(L, found);
  return 1;
}

/// @function Trigger:count
/// @return integer the number of bodies inside after the last step
int triggerCount(lua_State* L) {
  const auto* inside = ScenarioHost::from(L)->triggers().bodiesIn(checkTrigger(L, 1));
  lua_pushinteger(L, inside ? lua_Integer(inside->size()) : 0);
  return 1;
}

int triggerToString(lua_State* L) {
  auto* ref = static_cast<TriggerRef*>(luaL_checkudata(L, 1, kTriggerMeta));
  lua_pushfstring(L, "Trigger(%d)", int(ref->id));
  return 1;
}

int triggerEq(lua_State* L) {
  auto* a = static_cast<TriggerRef*>(luaL_testudata(L, 1, kTriggerMeta));
  auto* b = static_cast<TriggerRef*>(luaL_testudata(L, 2, kTriggerMeta));
  lua_pushboolean(L, a && b && a->id == b->id);
  return 1;
}

const luaL_Reg kTrigger[] = {
    {"box", guarded<triggerBox>},
    {nullptr, nullptr},
};
const luaL_Reg kMethods[] = {
    {"remove", guarded<triggerRemove>},
    {"bodies", guarded<triggerBodies>},
    {"contains", guarded<triggerContains>},
    {"count", guarded<triggerCount>},
    {nullptr, nullptr},
};

}  // namespace

void pushTrigger(lua_State* L, std::uint32_t id) {
  auto* ref = static_cast<TriggerRef*>(lua_newuserdatauv(L, sizeof(TriggerRef), 0));
  ref->id = id;
  luaL_setmetatable(L, kTriggerMeta);
}

void openTriggerBindings(lua_State* L, int envIndex) {
  registerType(L, {kTriggerMeta, kMethods, triggerToString, triggerEq});
  registerModule(L, envIndex, "trigger", kTrigger);
}

}  // namespace tumble::script
