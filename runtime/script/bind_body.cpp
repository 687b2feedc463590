// Lua type Body: a handle to a rigid body (index + generation). Methods
// refuse a removed body with a clear error instead of touching a reused slot.
//
// Vectors are tables {x=, y=, z=}; setters accept {x, y, z} or {x=, y=, z=}.
#include "audio/synth.h"
#include "script/internal/bind_common.h"

namespace tumble::script {

namespace {

struct BodyRef {
  std::uint32_t index, generation;
};

physics::World& worldOf(lua_State* L) { return ScenarioHost::from(L)->world(); }

/// @class Body
/// A handle to a rigid body (slot index plus generation). Methods refuse a
/// removed body with a clear error; check body:is_valid() when unsure. Bodies
/// compare equal with == when they are the same body. Its metatable is
/// protected: scripts cannot change or replace its methods.

/// @function Body:position
/// @return Vec3 centre of mass, m
/// @example local p = ball:position()  print(p.x, p.y, p.z)
int bodyPosition(lua_State* L) {
  pushVec3(L, worldOf(L).body(checkBody(L, 1)).position_m);
  return 1;
}
/// @function Body:velocity
/// @return Vec3 velocity of the centre of mass, m/s
int bodyVelocity(lua_State* L) {
  pushVec3(L, worldOf(L).body(checkBody(L, 1)).linearVelocity_mps);
  return 1;
}
/// @function Body:angular_velocity
/// @return Vec3 angular velocity, rad/s, world frame
int bodyAngularVelocity(lua_State* L) {
  pushVec3(L, worldOf(L).body(checkBody(L, 1)).angularVelocity_radps);
  return 1;
}
/// @function Body:orientation
/// @return Quat unit quaternion {w=, x=, y=, z=}, body to world
int bodyOrientation(lua_State* L) {
  const Quat& q = worldOf(L).body(checkBody(L, 1)).orientation;
  lua_createtable(L, 0, 4);
  lua_pushnumber(L, q.w());
  rawSetField(L, -2, "w");
  lua_pushnumber(L, q.x());
  rawSetField(L, -2, "x");
  lua_pushnumber(L, q.y());
  rawSetField(L, -2, "y");
  lua_pushnumber(L, q.z());
  rawSetField(L, -2, "z");
  return 1;
}
/// @function Body:up
/// @return Vec3 the body's local +Y axis in world space (unit)
/// @example if crate:up().y < 0.5 then game.lose("the crate tipped over") end
int bodyUp(lua_State* L) {
  pushVec3(L, worldOf(L).body(checkBody(L, 1)).orientation * Vec3::UnitY());
  return 1;
}
/// @function Body:mass
/// @return number kg (0 for static and kinematic bodies)
int bodyMass(lua_State* L) {
  lua_pushnumber(L, worldOf(L).body(checkBody(L, 1)).mass_kg);
  return 1;
}
/// @function Body:speed
/// @return number |v|, m/s
int bodySpeed(lua_State* L) {
  lua_pushnumber(L, worldOf(L).body(checkBody(L, 1)).linearVelocity_mps.norm());
  return 1;
}
/// @function Body:kinetic_energy
/// @return number translational plus rotational kinetic energy, J
int bodyKineticEnergy(lua_State* L) {
  const physics::Body& b = worldOf(L).body(checkBody(L, 1));
  Vec3 wl = b.orientation.conjugate() * b.angularVelocity_radps;
  lua_pushnumber(L, 0.5 * b.mass_kg * b.linearVelocity_mps.squaredNorm() +
                        0.5 * wl.dot(b.inertiaLocal_kgm2.cwiseProduct(wl)));
  return 1;
}
/// @function Body:angular_momentum
/// Angular momentum about the centre of mass, world frame (R I R^T w).
/// @return Vec3 kg m^2/s
int bodyAngularMomentum(lua_State* L) {
  const physics::Body& b = worldOf(L).body(checkBody(L, 1));
  const Vec3 wl = b.orientation.conjugate() * b.angularVelocity_radps;
  pushVec3(L, b.orientation * b.inertiaLocal_kgm2.cwiseProduct(wl));
  return 1;
}
/// @function Body:inertia
/// Principal moments of inertia about the body's own x, y and z axes
/// (through the centre of mass; 0 for static and kinematic bodies).
/// @return Vec3 kg m^2
int bodyInertia(lua_State* L) {
  pushVec3(L, worldOf(L).body(checkBody(L, 1)).inertiaLocal_kgm2);
  return 1;
}
/// @function Body:axis
/// One of the body's own axes in the world (unit).
/// @param which string "x", "y" or "z"
/// @return Vec3 the axis, world frame
/// @example local spin_axis = top:axis("y")
int bodyAxis(lua_State* L) {
  const physics::Body& b = worldOf(L).body(checkBody(L, 1));
  const std::string w = lua_isnoneornil(L, 2) ? "y" : lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "?";
  if (w != "x" && w != "y" && w != "z")
    throw LuaArgError("Body:axis: expected \"x\", \"y\" or \"z\", got \"" + w + "\"");
  pushVec3(L, b.orientation * Vec3::Unit(w[0] - 'x'));
  return 1;
}
/// @function Body:is_awake
/// @return boolean false while the body sleeps (at rest, not simulated)
int bodyIsAwake(lua_State* L) {
  lua_pushboolean(L, worldOf(L).body(checkBody(L, 1)).awake);
  return 1;
}
/// @function Body:is_valid
/// The one method that accepts a removed body.
/// @return boolean false once the body was removed
int bodyIsValid(lua_State* L) {
  auto* ref = static_cast<BodyRef*>(luaL_testudata(L, 1, kBodyMeta));
  lua_pushboolean(L, ref && worldOf(L).isValid(physics::BodyId{ref->index, ref->generation}));
  return 1;
}
/// @function Body:set_position
/// Teleports the body (wakes it).
/// @param p Vec3Arg new centre of mass, m
int bodySetPosition(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  worldOf(L).setPosition(id, checkVec3(L, 2, "Body:set_position"));
  return 0;
}
/// @function Body:set_velocity
/// @param v Vec3Arg m/s
/// @example ball:set_velocity{5, 0, 0}
int bodySetVelocity(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  worldOf(L).setLinearVelocity(id, checkVec3(L, 2, "Body:set_velocity"));
  return 0;
}
/// @function Body:set_angular_velocity
/// @param w Vec3Arg rad/s, world frame
int bodySetAngularVelocity(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  worldOf(L).setAngularVelocity(id, checkVec3(L, 2, "Body:set_angular_velocity"));
  return 0;
}
/// @function Body:apply_force
/// Applies a force over the next step (call it every on_update for a steady force).
/// @param f Vec3Arg force, N
/// @param at? Vec3Arg world point, m (default: the centre of mass)
/// @example rocket:apply_force({0, 200, 0})
int bodyApplyForce(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  Vec3 f = checkVec3(L, 2, "Body:apply_force force");
  Vec3 at = lua_isnoneornil(L, 3) ? worldOf(L).body(id).position_m : checkVec3(L, 3, "Body:apply_force point");
  worldOf(L).applyForce(id, f, at);
  return 0;
}
/// @function Body:apply_impulse
/// Changes the momentum at once.
/// @param j Vec3Arg impulse, N s
/// @param at? Vec3Arg world point, m (default: the centre of mass)
/// @example ball:apply_impulse({0, 5, 0})
int bodyApplyImpulse(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  Vec3 j = checkVec3(L, 2, "Body:apply_impulse impulse");
  Vec3 at = lua_isnoneornil(L, 3) ? worldOf(L).body(id).position_m : checkVec3(L, 3, "Body:apply_impulse point");
  worldOf(L).applyImpulse(id, j, at);
  return 0;
}
/// @function Body:apply_torque
/// Applies a torque over the next step.
/// @param t Vec3Arg torque, N m, world frame
int bodyApplyTorque(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  worldOf(L).applyTorque(id, checkVec3(L, 2, "Body:apply_torque"));
  return 0;
}
/// @function Body:remove
/// Removes the body from the world (as world.remove); the handle becomes invalid.
int bodyRemove(lua_State* L) {
  worldOf(L).destroyBody(checkBody(L, 1));
  return 0;
}
/// @class Material
/// @field friction? number Coulomb coefficient >= 0; a pair uses sqrt(fa*fb)
/// @field restitution? number 0..1; a pair uses the larger
/// @field sound? string what it sounds like when struck: "metal", "wood", "rubber", "rock", "gravel", "soil", "mud" or "thud" (a dull knock; the default, but a vehicle's chassis sounds as metal and a plane as rock). Heard only: physics ignores it

/// @function Body:set_material
/// Changes friction, restitution and the sound of impacts; a field left out keeps its value.
/// @param m Material {friction=, restitution=, sound=}
/// @example ice:set_material{friction = 0.02}
/// @example crate:set_material{sound = "wood"}
int bodySetMaterial(lua_State* L) {
  physics::BodyId id = checkBody(L, 1);
  if (!lua_istable(L, 2))
    throw LuaArgError(std::string("Body:set_material: expected a table {friction = ..., restitution = ...}, got ") +
                      luaL_typename(L, 2));
  checkFields(L, 2, "Body:set_material", {"friction", "restitution", "sound"});
  const physics::Body& b = worldOf(L).body(id);
  double friction = 0, restitution = 0;
  std::string sound;
  try {
    friction = optNumberField(L, 2, "friction", b.friction);
    restitution = optNumberField(L, 2, "restitution", b.restitution);
    sound = optStringField(L, 2, "sound", audio::impactMaterialName(audio::ImpactMaterial(b.soundMaterial)));
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string("Body:set_material: ") + e.what());
  }
  const std::optional<audio::ImpactMaterial> soundMaterial = audio::parseImpactMaterial(sound);
  if (!soundMaterial)
    throw LuaArgError("Body:set_material: field 'sound' must be one of \"metal\", \"wood\", \"rubber\", \"rock\", "
                      "\"gravel\", \"soil\", \"mud\", \"thud\", got \"" + sound + "\"");
  if (friction < 0) throw LuaArgError("Body:set_material: field 'friction' must be >= 0, got " + std::to_string(friction));
  if (restitution < 0 || restitution > 1)
    throw LuaArgError("Body:set_material: field 'restitution' must be in 0..1, got " + std::to_string(restitution));
  worldOf(L).setMaterial(id, Real(friction), Real(restitution));
  worldOf(L).setSoundMaterial(id, std::uint8_t(*soundMaterial));
  return 0;
}

/// @function Body:material
/// @return Material the body's {friction=, restitution=, sound=} (sound: what it was set to, "thud" when never set)
int bodyMaterial(lua_State* L) {
  const physics::Body& b = worldOf(L).body(checkBody(L, 1));
  lua_createtable(L, 0, 3);
  lua_pushstring(L, audio::impactMaterialName(audio::ImpactMaterial(b.soundMaterial)));
  rawSetField(L, -2, "sound");
  lua_pushnumber(L, b.friction);
  rawSetField(L, -2, "friction");
  lua_pushnumber(L, b.restitution);
  rawSetField(L, -2, "restitution");
  return 1;
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
    {"angular_momentum", guarded<bodyAngularMomentum>},
    {"inertia", guarded<bodyInertia>},
    {"axis", guarded<bodyAxis>},
    {"is_awake", guarded<bodyIsAwake>},
    {"is_valid", guarded<bodyIsValid>},
    {"set_position", guarded<bodySetPosition>},
    {"set_velocity", guarded<bodySetVelocity>},
    {"set_angular_velocity", guarded<bodySetAngularVelocity>},
    {"apply_force", guarded<bodyApplyForce>},
    {"apply_impulse", guarded<bodyApplyImpulse>},
    {"apply_torque", guarded<bodyApplyTorque>},
    {"set_material", guarded<bodySetMaterial>},
    {"material", guarded<bodyMaterial>},
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

bool testBody(lua_State* L, int idx, physics::BodyId* out) {
  auto* ref = static_cast<BodyRef*>(luaL_testudata(L, idx, kBodyMeta));
  if (!ref) return false;
  *out = physics::BodyId{ref->index, ref->generation};
  return true;
}

void pushBody(lua_State* L, physics::BodyId id) {
  auto* ref = static_cast<BodyRef*>(lua_newuserdatauv(L, sizeof(BodyRef), 0));
  ref->index = id.index;
  ref->generation = id.generation;
  luaL_setmetatable(L, kBodyMeta);
}

void openBodyType(lua_State* L) {
  registerType(L, {kBodyMeta, kMethods, bodyToString, bodyEq});
}

}  // namespace tumble::script
