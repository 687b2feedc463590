// Joints for scripts: world.joint{...} (the JointDef of physics/joints/joint.h
// as a table), world.grab (a spring from a body point to a target, for
// dragging with the mouse), the Joint handle type, the joint solver and
// the step length while running.
//
//   local j = world.joint{type = "hinge", a = door, b = frame, anchor = {1, 1, 0}, axis = {0, 1, 0},
//                         lower_angle = -1.5, upper_angle = 0}
//   local g = world.grab(crate, {0, 0.5, 0}, {0, 3, 0});  g:set_target({1, 3, 0}); g:release()
#include <cmath>

#include "physics/joints/joint_system.h"
#include "script/internal/bind_common.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace tumble::script {
namespace {

constexpr const char* kJointMeta = "tumble.Joint";

struct JointRef {
  physics::JointId id;
};

physics::JointId checkJoint(lua_State* L, int idx, bool mustBeValid = true) {
  auto* ref = static_cast<JointRef*>(luaL_testudata(L, idx, kJointMeta));
  if (!ref) throw LuaArgError(std::string("expected a Joint, got ") + luaL_typename(L, idx));
  if (mustBeValid) {
    physics::JointSystem* js = ScenarioHost::from(L)->scene().jointsIfAny();
    if (!js || !js->isValid(ref->id))
      throw LuaArgError("this Joint was removed or broke (check joint:is_valid() first)");
  }
  return ref->id;
}

void pushJoint(lua_State* L, physics::JointId id) {
  auto* ref = static_cast<JointRef*>(lua_newuserdatauv(L, sizeof(JointRef), 0));
  ref->id = id;
  luaL_setmetatable(L, kJointMeta);
}

physics::BodyId bodyField(lua_State* L, int t, const char* key, bool required) {
  rawGetField(L, t, key);
  physics::BodyId id;
  if (lua_isnil(L, -1)) {
    lua_pop(L, 1);
    if (required) throw LuaArgError(std::string("field '") + key + "' is required (a Body)");
    return id;
  }
  id = checkBody(L, lua_gettop(L));
  lua_pop(L, 1);
  return id;
}

/// @class JointDef
/// What world.joint takes. Angles in rad, lengths in m.
/// @field type string "ball", "hinge", "cone_twist" or "fixed"
/// @field a Body the first body (must not be static unless b is dynamic)
/// @field b? Body the second body; nil joins a to the world
/// @field anchor Vec3Arg the joint point in the world, m (the bodies are held as they are now)
/// @field axis? Vec3Arg hinge axis (hinge) or twist axis (cone_twist), world; default {1, 0, 0}
/// @field lower_angle? number hinge: lower limit, rad (with upper_angle: turns the limit on)
/// @field upper_angle? number hinge: upper limit, rad
/// @field motor_speed? number hinge: motor target rate of b relative to a about the axis, rad/s
/// @field max_motor_torque? number hinge: motor torque bound, N m (> 0 turns the motor on)
/// @field swing_limit? number cone_twist: largest angle between the twist axes, rad (default pi/4)
/// @field twist_lower? number cone_twist: twist limit, rad in (-pi, 0] (default -pi/4)
/// @field twist_upper? number cone_twist: twist limit, rad in [0, pi) (default pi/4)
/// @field stiffness? number > 0 makes the joint a spring: N/m on the anchors
/// @field damping? number spring damping, N s/m
/// @field angular_stiffness? number spring on the angular rows (hinge, fixed), N m/rad
/// @field angular_damping? number N m s/rad
/// @field break_force? number the joint breaks above this anchor force, N (0: never)
/// @field break_torque? number likewise for the angular torque, N m
/// @field collide? boolean whether a and b still collide with each other (default false)

const std::set<std::string> kJointFields = {"type", "a", "b", "anchor", "axis", "lower_angle", "upper_angle",
                                    "motor_speed", "max_motor_torque", "swing_limit", "twist_lower",
                                    "twist_upper", "stiffness", "damping", "angular_stiffness",
                                    "angular_damping", "break_force", "break_torque", "collide"};


/// @function world.joint
/// Joins two bodies (or a body and the world) where they are now. Solved by
/// the scene's joint solver (Scenario.joint_solver). The two bodies stop
/// colliding with each other unless `collide = true`.
/// @param def JointDef type, bodies, anchor, limits, motor, spring, breaking
/// @return Joint the joint
/// @example local hinge = world.joint{type = "hinge", a = lid, b = box, anchor = {0, 1, -0.5}, axis = {1, 0, 0},
/// @example   lower_angle = 0, upper_angle = 2}
int worldJoint(lua_State* L) {
  const char* fn = "world.joint";
  if (!lua_istable(L, 1))
    throw LuaArgError("world.joint: expected a table, e.g. world.joint{type = \"ball\", a = body, anchor = {0, 2, 0}}");
  lua_settop(L, 1);
  checkFields(L, 1, fn, kJointFields);
  ScenarioHost& host = *ScenarioHost::from(L);
  physics::JointDef d;
  bool collide = false;
  try {
    const std::string type = optStringField(L, 1, "type", "ball");
    physics::JointType jt;
    if (type == "ball") jt = physics::JointType::Ball;
    else if (type == "hinge") jt = physics::JointType::Hinge;
    else if (type == "cone_twist") jt = physics::JointType::ConeTwist;
    else if (type == "fixed") jt = physics::JointType::Fixed;
    else throw LuaArgError("field 'type' must be \"ball\", \"hinge\", \"cone_twist\" or \"fixed\", got \"" + type + "\"");
    const physics::BodyId a = bodyField(L, 1, "a", true);
    const physics::BodyId b = bodyField(L, 1, "b", false);
    Vec3 anchor, axis = Vec3::UnitX();
    if (!optVec3Field(L, 1, "anchor", &anchor)) throw LuaArgError("field 'anchor' is required ({x, y, z}, m)");
    optVec3Field(L, 1, "axis", &axis);
    if (!(axis.norm() > 0)) throw LuaArgError("field 'axis' must not be zero");
    if (a == b) throw LuaArgError("fields 'a' and 'b' must be different bodies");
    d = physics::makeJointDef(host.world(), jt, a, b, anchor, axis);
    rawGetField(L, 1, "lower_angle");
    rawGetField(L, 1, "upper_angle");
    d.enableLimit = !lua_isnil(L, -1) || !lua_isnil(L, -2);
    lua_pop(L, 2);
    d.lowerAngle_rad = Real(optNumberField(L, 1, "lower_angle", -M_PI / 2));
    d.upperAngle_rad = Real(optNumberField(L, 1, "upper_angle", M_PI / 2));
    d.motorSpeed_radps = Real(optNumberField(L, 1, "motor_speed", 0));
    d.maxMotorTorque_Nm = Real(optNumberField(L, 1, "max_motor_torque", 0));
    d.enableMotor = d.maxMotorTorque_Nm > 0;
    d.swingLimit_rad = Real(optNumberField(L, 1, "swing_limit", d.swingLimit_rad));
    d.twistLower_rad = Real(optNumberField(L, 1, "twist_lower", d.twistLower_rad));
    d.twistUpper_rad = Real(optNumberField(L, 1, "twist_upper", d.twistUpper_rad));
    d.linearStiffness_Npm = Real(optNumberField(L, 1, "stiffness", 0));
    d.linearDamping_Nspm = Real(optNumberField(L, 1, "damping", 0));
    d.angularStiffness_Nmprad = Real(optNumberField(L, 1, "angular_stiffness", 0));
    d.angularDamping_Nmsprad = Real(optNumberField(L, 1, "angular_damping", 0));
    d.breakForce_N = Real(optNumberField(L, 1, "break_force", 0));
    d.breakTorque_Nm = Real(optNumberField(L, 1, "break_torque", 0));
    collide = optBoolField(L, 1, "collide", false);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  auto id = host.scene().joints().createJoint(d);
  if (!id) throw LuaArgError(std::string(fn) + ": " + id.error());
  if (!collide && !d.bodyB.isNull()) host.world().disableCollision(d.bodyA, d.bodyB);
  host.world().wake(d.bodyA);
  pushJoint(L, id.value());
  return 1;
}

/// @function world.grab
/// Grabs a body at a point with a spring towards a target (what dragging
/// with the mouse does): a soft ball joint to the world whose stiffness
/// follows the body's mass, so every body follows at the same rate. Move the
/// target with grab:set_target(p), let go with grab:release().
/// @param body Body a dynamic body
/// @param local_point Vec3Arg the grabbed point in the body's frame (from its centre of mass), m
/// @param target Vec3Arg where the point is pulled to, world, m
/// @param hertz? number spring frequency, Hz (default 4); damping ratio 0.5 at the centre of mass
/// @return Joint the grab (a Joint: set_target, release, force)
/// @example local g = world.grab(crate, {0, 0.5, 0}, {0, 3, 0})
/// @example g:set_target({2, 3, 0})
int worldGrab(lua_State* L) {
  ScenarioHost& host = *ScenarioHost::from(L);
  const physics::BodyId body = checkBody(L, 1);
  const Vec3 local = checkVec3(L, 2, "world.grab local_point");
  const Vec3 target = checkVec3(L, 3, "world.grab target");
  const double hz = lua_isnoneornil(L, 4) ? 4.0 : checkNumber(L, 4, "world.grab hertz");
  if (!(hz > 0 && hz <= 60)) throw LuaArgError("world.grab: hertz must be in (0, 60]");
  const physics::Body& b = host.world().body(body);
  if (b.type != physics::BodyType::Dynamic) throw LuaArgError("world.grab: the body must be dynamic");
  const physics::JointDef d = physics::makeGrabDef(host.world(), body, local, target, Real(hz));
  auto id = host.scene().joints().createJoint(d);
  if (!id) throw LuaArgError("world.grab: " + id.error());
  host.world().wake(body);
  pushJoint(L, id.value());
  return 1;
}

/// @function world.joint_solver
/// @return string the scene's joint solver now: "lagrange" or "impulse"
int worldJointSolver(lua_State* L) {
  lua_pushstring(L, physics::jointSolverName(ScenarioHost::from(L)->scene().jointSolver()));
  return 1;
}

/// @function world.set_joint_solver
/// Switches the joint solver while running ("lagrange": Lagrange
/// multipliers from the joints' sparse factor; "impulse": impulses solved
/// with the contacts). Joints that exist switch too.
/// @param name string "lagrange" or "impulse"
int worldSetJointSolver(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  physics::JointSolverKind kind;
  if (!physics::parseJointSolver(name, &kind))
    throw LuaArgError(std::string("world.set_joint_solver: expected \"lagrange\" or \"impulse\", got \"") + name + "\"");
  ScenarioHost::from(L)->scene().setJointSolver(kind);
  return 0;
}

/// @function world.set_dt
/// Changes the fixed time step from the next step on (also while playing).
/// @param dt number the step, s, in [0.0005, 0.1]
/// @example world.set_dt(1 / 120)
int worldSetDt(lua_State* L) {
  const double dt = checkNumber(L, 1, "world.set_dt dt");
  if (!(dt >= 0.0005 && dt <= 0.1)) throw LuaArgError("world.set_dt: dt must be in [0.0005, 0.1] s");
  ScenarioHost::from(L)->scene().requestDt(dt);
  return 0;
}

/// @function world.dt
/// @return number the fixed time step in use, s
int worldDt(lua_State* L) {
  lua_pushnumber(L, ScenarioHost::from(L)->scene().dt_s());
  return 1;
}

/// @class Joint
/// A handle returned by world.joint and world.grab. Methods other than
/// is_valid fail on a joint that was removed or broke.

/// @function Joint:is_valid
/// @return boolean false once the joint was removed, released or broke (or a body of it removed)
int jointIsValid(lua_State* L) {
  const physics::JointId id = checkJoint(L, 1, false);
  physics::JointSystem* js = ScenarioHost::from(L)->scene().jointsIfAny();
  lua_pushboolean(L, js && js->isValid(id));
  return 1;
}

/// @function Joint:remove
/// Removes the joint (grab:release() does the same).
/// @return boolean true if it was still there
int jointRemove(lua_State* L) {
  const physics::JointId id = checkJoint(L, 1, false);
  physics::JointSystem* js = ScenarioHost::from(L)->scene().jointsIfAny();
  lua_pushboolean(L, js && js->destroyJoint(id));
  return 1;
}

/// @function Joint:release
/// Lets go of a grab (the same as remove).
/// @return boolean true if it was still there
int jointRelease(lua_State* L) { return jointRemove(L); }

/// @function Joint:set_target
/// Moves the world end of a joint held to the world (a grab's target).
/// @param p Vec3Arg the new target, m
int jointSetTarget(lua_State* L) {
  const physics::JointId id = checkJoint(L, 1);
  const Vec3 p = checkVec3(L, 2, "Joint:set_target point");
  if (!ScenarioHost::from(L)->scene().joints().setWorldAnchor(id, p))
    throw LuaArgError("Joint:set_target: only for joints held to the world (b = nil) and grabs");
  return 0;
}

/// @function Joint:set_motor
/// Hinge motor: drive the angle's rate towards speed with at most max_torque.
/// @param speed number rad/s
/// @param max_torque number N m (0 turns the motor off)
int jointSetMotor(lua_State* L) {
  const physics::JointId id = checkJoint(L, 1);
  const double speed = checkNumber(L, 2, "Joint:set_motor speed");
  const double torque = checkNumber(L, 3, "Joint:set_motor max_torque");
  if (torque < 0) throw LuaArgError("Joint:set_motor: max_torque must be >= 0 N m");
  ScenarioHost::from(L)->scene().joints().setMotor(id, Real(speed), Real(torque));
  return 0;
}

/// @function Joint:angle
/// @return number hinge angle or cone-twist twist angle now, rad (0 for other types)
int jointAngle(lua_State* L) {
  lua_pushnumber(L, ScenarioHost::from(L)->scene().joints().jointAngle_rad(checkJoint(L, 1)));
  return 1;
}

/// @function Joint:force
/// @return number the constraint force on the anchor in the last step, N
/// @return number the constraint torque of the angular rows, N m
int jointForce(lua_State* L) {
  const physics::JointId id = checkJoint(L, 1);
  physics::JointSystem& js = ScenarioHost::from(L)->scene().joints();
  lua_pushnumber(L, js.lastForce_N(id).norm());
  lua_pushnumber(L, js.lastTorque_Nm(id).norm());
  return 2;
}

int jointToString(lua_State* L) {
  auto* ref = static_cast<JointRef*>(luaL_checkudata(L, 1, kJointMeta));
  lua_pushfstring(L, "Joint(%d)", int(ref->id.index));
  return 1;
}

int jointEq(lua_State* L) {
  auto* a = static_cast<JointRef*>(luaL_testudata(L, 1, kJointMeta));
  auto* b = static_cast<JointRef*>(luaL_testudata(L, 2, kJointMeta));
  lua_pushboolean(L, a && b && a->id == b->id);
  return 1;
}

const luaL_Reg kWorldJoint[] = {
    {"joint", guarded<worldJoint>},
    {"grab", guarded<worldGrab>},
    {"joint_solver", guarded<worldJointSolver>},
    {"set_joint_solver", guarded<worldSetJointSolver>},
    {"set_dt", guarded<worldSetDt>},
    {"dt", guarded<worldDt>},
    {nullptr, nullptr},
};
const luaL_Reg kMethods[] = {
    {"is_valid", guarded<jointIsValid>},
    {"remove", guarded<jointRemove>},
    {"release", guarded<jointRelease>},
    {"set_target", guarded<jointSetTarget>},
    {"set_motor", guarded<jointSetMotor>},
    {"angle", guarded<jointAngle>},
    {"force", guarded<jointForce>},
    {nullptr, nullptr},
};

}  // namespace

void openJointBindings(lua_State* L, int envIndex) {
  registerType(L, {kJointMeta, kMethods, jointToString, jointEq});
  // Into the `world` table made by openWorldBindings.
  rawGetField(L, envIndex, "world");
  registerFunctions(L, -1, kWorldJoint);
  lua_pop(L, 1);
}

}  // namespace tumble::script
