// world.spring{...} and world.remove_spring(id): applied springs between
// centres of mass (physics/integrate.h). Their stiffness is what makes the
// world's integrator choice matter: a scenario with stiff springs sets
// integrator = "sdirk2" (or --integrator sdirk2).
//
//   local s = world.spring{a = ball, anchor = {0, 5, 0}, stiffness = 1e6, rest_length = 1}
#include "script/internal/bind_common.h"

namespace tumble::script {
namespace {

/// @class SpringDef
/// @field a Body the first end (its centre of mass)
/// @field b? Body the other end; without it the spring holds a to `anchor`
/// @field anchor? Vec3Arg fixed world point for the other end (m), when b is absent
/// @field stiffness number k > 0 (N/m)
/// @field damping? number along the spring, >= 0 (N s/m, default 0)
/// @field rest_length? number >= 0 (m); default: the distance now

/// @function world.spring
/// An applied spring-damper between centres of mass (no torque). Stiff
/// springs (k/m of 1e5 and more at 60 Hz) need an implicit integrator:
/// integrator = "sdirk2" in the scenario, or --integrator sdirk2; with the
/// default symplectic Euler they blow up (the body is frozen and counted
/// in the report's nan_events).
/// @param def SpringDef
/// @return integer the spring's id (for world.remove_spring)
/// @example world.spring{a = bob, anchor = {0, 5, 0}, stiffness = 400, damping = 2}
int worldSpring(lua_State* L) {
  const char* fn = "world.spring";
  if (!lua_istable(L, 1))
    throw LuaArgError("world.spring: expected a table, e.g. world.spring{a = body, anchor = {0, 5, 0}, stiffness = 100}");
  lua_settop(L, 1);
  checkFields(L, 1, fn, {"a", "b", "anchor", "stiffness", "damping", "rest_length"});
  physics::SpringDef def;
  rawGetField(L, 1, "a");
  if (!testBody(L, -1, &def.a)) throw LuaArgError("world.spring: field 'a' must be a Body");
  def.a = checkBody(L, -1);
  lua_pop(L, 1);
  rawGetField(L, 1, "b");
  if (!lua_isnil(L, -1)) {
    if (!testBody(L, -1, &def.b)) throw LuaArgError("world.spring: field 'b' must be a Body");
    def.b = checkBody(L, -1);
  }
  lua_pop(L, 1);
  try {
    const bool hasAnchor = optVec3Field(L, 1, "anchor", &def.anchor_m);
    if (def.b.isNull() && !hasAnchor) throw LuaArgError("give 'b' (a Body) or 'anchor' ({x, y, z}, m)");
    if (!def.b.isNull() && hasAnchor) throw LuaArgError("give 'b' or 'anchor', not both");
    rawGetField(L, 1, "stiffness");
    const bool hasK = !lua_isnil(L, -1);
    lua_pop(L, 1);
    if (!hasK) throw LuaArgError("field 'stiffness' is required (N/m)");
    def.stiffness_Npm = Real(optNumberField(L, 1, "stiffness", 0));
    def.damping_Nspm = Real(optNumberField(L, 1, "damping", 0));
    def.restLength_m = Real(optNumberField(L, 1, "rest_length", -1));
    rawGetField(L, 1, "rest_length");
    const bool hasRest = !lua_isnil(L, -1);
    lua_pop(L, 1);
    if (hasRest && def.restLength_m < 0) throw LuaArgError("field 'rest_length' must be >= 0 (m)");
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  auto id = ScenarioHost::from(L)->world().addSpring(def);
  if (!id) throw LuaArgError(std::string(fn) + ": " + id.error());
  // One integer: index and generation packed (both < 2^31 in practice).
  lua_pushinteger(L, (lua_Integer(id->generation) << 32) | lua_Integer(id->index));
  return 1;
}

/// @function world.remove_spring
/// @param id integer what world.spring returned
/// @return boolean true if the spring was still there
int worldRemoveSpring(lua_State* L) {
  // The id is an integer (a float with an integer value too); any other
  // number is no spring's, and converting one such as -1e308 to an
  // integer would be undefined (found by the scenario fuzzer).
  int isInteger = 0;
  const lua_Integer packed = lua_tointegerx(L, 1, &isInteger);
  if (!isInteger || lua_type(L, 1) != LUA_TNUMBER)
    throw LuaArgError(std::string("world.remove_spring: expected a spring id (the integer world.spring returned), got ") +
                      (lua_type(L, 1) == LUA_TNUMBER ? toDisplayString(L, 1) : std::string(luaL_typename(L, 1))));
  physics::SpringId id{std::uint32_t(packed & 0xffffffff), std::uint32_t(packed >> 32)};
  lua_pushboolean(L, ScenarioHost::from(L)->world().removeSpring(id));
  return 1;
}

}  // namespace

void openSpringBindings(lua_State* L, int envIndex) {
  if (rawGetField(L, envIndex, "world") != LUA_TTABLE) {
    lua_pop(L, 1);
    return;
  }
  lua_pushcfunction(L, guarded<worldSpring>);
  rawSetField(L, -2, "spring");
  lua_pushcfunction(L, guarded<worldRemoveSpring>);
  rawSetField(L, -2, "remove_spring");
  lua_pop(L, 1);
}

}  // namespace tumble::script
