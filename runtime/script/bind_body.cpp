// Lua type Body: a handle to a rigid body (index + generation). Methods
// refuse a removed body with a clear error instead of touching a reused slot.
//
// Vectors are tables {x=, y=, z=}; setters accept {x, y, z} or {x=, y=, z=}.
#include "script/internal/bind_common.h"

namespace tumble::script {

namespace {

struct BodyRef {
  std::uint32_t index, generation;
};

physics::World& worldOf(lua_State* L) { return ScenarioHost::from(L)->world(); }

/// @function Body:position
/// @return {x,y,z} centre of mass, m
int bodyPosition(lua_State* L) {
  pushVec3(L, worldOf(L).body(checkBody(L, 1)).position_m);
  return 1;
}
/// @function Body:velocity  @return {x,y,z} m/s
int bodyVelocity(lua_State* L) {
  pushVec3(L, worldOf(L).body(checkBody(L, 1)).linearVelocity_mps);
  return 1;
}
/// @function Body:angular_velocity  @return {x,y,z} rad/s, world frame
int bodyAngularVelocity(lua_State* L) {
  pushVec3(L, worldOf(L).body(checkBody(L, 1)).angularVelocity_radps);
  return 1;
}
/// @function Body:orientation  @return {w,x,y,z} unit quaternion
int bodyOrientation(lua_State* L) {
  const Quat& q = worldOf(L).body(checkBody(L, 1)).orientation;
  lua_createtable(L, 0, 4);
  lua_pushnumber(L, q.w());
  lua_setfield(L, -2, "w");
  lua_pushnumber(L, q.x());
  lua_setfield(L, -2, "x");
  lua_pushnumber(L, q.y());
  lua_setfield(L, -2, "y");
  lua_pushnumber(L, q.z());
  lua_setfield(L, -2, "z");
  return 1;
}
/// @function Body:up  @return {x,y,z} the body's local +Y axis in world space (unit)
int bodyUp(lua_State* L) {
  pushVec3(L, worldOf(L).body(checkBody(L, 1)).orientation * Vec3::UnitY());
  return 1;
}
/// @function Body:mass  @return kg (0 for static and kinematic bodies)
int bodyMass(lua_State* L) {
  lua_pushnumber(L, worldOf(L).body(checkBody(L, 1)).mass_kg);
  return 1;
}
/// @function Body:speed  @return |v| in m/s
int bodySpeed(lua_State* L) {
  lua_pushnumber(L, worldOf(L).body(checkBody(L, 1)).linearVelocity_mps.norm());
  return 1;
}
/// @function Body:kinetic_energy  @return J, translation + rotation
int bodyKineticEnergy(lua_State* L) {
  const physics::Body& b = worldOf(L).body(checkBody(L, 1));
  Vec3 wl = b.orientation.conjugate() * b.angularVelocity_radps;
  lua_pushnumber(L, 0.5 * b.mass_kg * b.linearVelocity_mps.squaredNorm() +
                        0.5 * wl.dot(b.inertiaLocal_kgm2.cwiseProduct(wl)));
  return 1;
}
/// @function Body:is_awake  @return boolean
int bodyIsAwake(lua_State* L) {
  lua_pushboolean(L, worldOf(L).body(checkBody(L, 1)).awake);
  return 1;
}
/// @function Body:is_valid  @return false once the body was removed
int bodyIsValid(lua_State* L) {
  auto* ref = static_cast<BodyRef*>(luaL_testudata(L, 1, kBodyMeta));
  lua_pushboolean(L, ref && worldOf(L).isValid(physics::BodyId{ref->index, ref->generation}));
  return 1;
}
/// @function Body:set_position  @param p {x,y,z} m
int bodySetPosition(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  worldOf(L).setPosition(id, checkVec3(L, 2, "Body:set_position"));
  return 0;
}
/// @function Body:set_velocity  @param v {x,y,z} m/s
int bodySetVelocity(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  worldOf(L).setLinearVelocity(id, checkVec3(L, 2, "Body:set_velocity"));
  return 0;
}
/// @function Body:set_angular_velocity  @param w {x,y,z} rad/s
int bodySetAngularVelocity(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  worldOf(L).setAngularVelocity(id, checkVec3(L, 2, "Body:set_angular_velocity"));
  return 0;
}
/// @function Body:apply_force  @param f {x,y,z} N  @param at? {x,y,z} world point, m (default: centre of mass)
int bodyApplyForce(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  Vec3 f = checkVec3(L, 2, "Body:apply_force force");
  Vec3 at = lua_isnoneornil(L, 3) ? worldOf(L).body(id).position_m : checkVec3(L, 3, "Body:apply_force point");
  worldOf(L).applyForce(id, f, at);
  return 0;
}
/// @function Body:apply_impulse  @param j {x,y,z} N s  @param at? {x,y,z} world point, m
int bodyApplyImpulse(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  Vec3 j = checkVec3(L, 2, "Body:apply_impulse impulse");
  Vec3 at = lua_isnoneornil(L, 3) ? worldOf(L).body(id).position_m : checkVec3(L, 3, "Body:apply_impulse point");
  worldOf(L).applyImpulse(id, j, at);
  return 0;
}
/// @function Body:apply_torque  @param t {x,y,z} N m
int bodyApplyTorque(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  worldOf(L).applyTorque(id, checkVec3(L, 2, "Body:apply_torque"));
  return 0;
}
/// @function Body:remove  Removes the body; the handle becomes invalid.
int bodyRemove(lua_State* L) {
  worldOf(L).destroyBody(checkBody(L, 1));
  return 0;
}
int bodyToString(lua_State* L) {
  auto* ref = static_cast<BodyRef*>(luaL_checkudata(L, 1, kBodyMeta));
  lua_pushfstring(L, "Body(%d#%d)", int(ref->index), int(ref->generation));
  return 1;
}
int bodyEq(lua_State* L) {
  auto* a = static_cast<BodyRef*>(luaL_testudata(L, 1, kBodyMeta));
  auto* b = static_cast<BodyRef*>(luaL_testudata(L, 2, kBodyMeta));
  lua_pushboolean(L, a && b && a->index == b->index && a->generation == b->generation);
  return 1;
}

const luaL_Reg kMethods[] = {
    {"position", guarded<bodyPosition>},
    {"velocity", guarded<bodyVelocity>},
    {"angular_velocity", guarded<bodyAngularVelocity>},
    {"orientation", guarded<bodyOrientation>},
    {"up", guarded<bodyUp>},
    {"mass", guarded<bodyMass>},
    {"speed", guarded<bodySpeed>},
    {"kinetic_energy", guarded<bodyKineticEnergy>},
    {"is_awake", guarded<bodyIsAwake>},
    {"is_valid", guarded<bodyIsValid>},
    {"set_position", guarded<bodySetPosition>},
    {"set_velocity", guarded<bodySetVelocity>},
    {"set_angular_velocity", guarded<bodySetAngularVelocity>},
    {"apply_force", guarded<bodyApplyForce>},
    {"apply_impulse", guarded<bodyApplyImpulse>},
    {"apply_torque", guarded<bodyApplyTorque>},
    {"remove", guarded<bodyRemove>},
    {nullptr, nullptr},
};

}  // namespace

physics::BodyId checkBody(lua_State* L, int idx) {
  auto* ref = static_cast<BodyRef*>(luaL_testudata(L, idx, kBodyMeta));
  if (!ref) throw LuaArgError(std::string("expected a Body, got ") + luaL_typename(L, idx));
  physics::BodyId id{ref->index, ref->generation};
  if (!ScenarioHost::from(L)->world().isValid(id))
    throw LuaArgError("this Body was removed; check body:is_valid() before using it");
  return id;
}

void pushBody(lua_State* L, physics::BodyId id) {
  auto* ref = static_cast<BodyRef*>(lua_newuserdatauv(L, sizeof(BodyRef), 0));
  ref->index = id.index;
  ref->generation = id.generation;
  luaL_setmetatable(L, kBodyMeta);
}

void openBodyType(lua_State* L) {
  luaL_newmetatable(L, kBodyMeta);
  luaL_newlib(L, kMethods);
  lua_setfield(L, -2, "__index");
  lua_pushcfunction(L, bodyToString);
  lua_setfield(L, -2, "__tostring");
  lua_pushcfunction(L, bodyEq);
  lua_setfield(L, -2, "__eq");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");  // scripts cannot swap the methods
  lua_pop(L, 1);
}

}  // namespace tumble::script
