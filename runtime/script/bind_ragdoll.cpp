// Rag-dolls for scripts: spawn_ragdoll{...} builds the default human, or a
// doll described part by part and joint by joint (the same RagdollDesc,
// physics/joints/ragdoll.h), in the scene's JointSystem; joints_error()
// reads the anchor error.
//
//   local doll = spawn_ragdoll{position = {0, 1, 0}, height = 1.8, mass = 75}
//   local small = spawn_ragdoll{position = {2, 0, 0}, scale = 0.5}
//   local own = spawn_ragdoll{parts = {...}, joints = {...}}   -- see spawn_ragdoll below
//   doll.head:position()
#include <cmath>

#include "physics/joints/ragdoll.h"
#include "script/internal/bind_common.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace tumble::script {
namespace {

/// Index of the part named by field `key` of the table at t.
int partField(lua_State* L, int t, const char* key, const physics::RagdollDesc& d) {
  const std::string name = optStringField(L, t, key, "");
  std::string valid;
  for (std::size_t i = 0; i < d.parts.size(); ++i) {
    if (d.parts[i].name == name) return int(i);
    valid += (valid.empty() ? "" : ", ") + d.parts[i].name;
  }
  if (name.empty()) throw LuaArgError(std::string("field '") + key + "' is required (a part's name)");
  throw LuaArgError(std::string("field '") + key + "': no part named '" + name + "' (parts: " + valid + ")");
}

// The default human's colours (linear RGB): skin, a blue shirt, dark trousers.
const Eigen::Vector3f kSkin(0.80f, 0.52f, 0.38f), kShirt(0.12f, 0.30f, 0.65f), kTrousers(0.16f, 0.17f, 0.22f);

/// Field `key` of the table at t as a colour {r, g, b} (each clamped to 0..1), or `fallback`.
Eigen::Vector3f colorField(lua_State* L, int t, const char* key, const Eigen::Vector3f& fallback) {
  Vec3 c;
  try {
    if (!optVec3Field(L, t, key, &c)) return fallback;
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(e.what()) + " (a colour {r, g, b}, each 0..1)");
  }
  if (!c.allFinite()) throw LuaArgError(std::string("field '") + key + "' must be finite (a colour {r, g, b}, each 0..1)");
  return c.cast<float>().cwiseMax(0.0f).cwiseMin(1.0f);
}

/// The default human's part colours from colors = {skin =, shirt =,
/// trousers =} (each optional): head and forearms skin, torso and upper
/// arms shirt, pelvis and legs trousers.
std::vector<Eigen::Vector3f> humanColors(lua_State* L, int t, const physics::RagdollDesc& d) {
  Eigen::Vector3f skin = kSkin, shirt = kShirt, trousers = kTrousers;
  if (rawGetField(L, t, "colors") != LUA_TNIL) {
    if (!lua_istable(L, -1)) throw LuaArgError("field 'colors' must be a table {skin =, shirt =, trousers =}");
    const int c = lua_gettop(L);
    checkFields(L, c, "colors", {"skin", "shirt", "trousers"});
    skin = colorField(L, c, "skin", skin);
    shirt = colorField(L, c, "shirt", shirt);
    trousers = colorField(L, c, "trousers", trousers);
  }
  lua_pop(L, 1);
  std::vector<Eigen::Vector3f> out;
  for (const physics::RagdollPart& p : d.parts) {
    const std::string& n = p.name;
    if (n == "head" || n.rfind("lower_arm", 0) == 0) out.push_back(skin);
    else if (n == "torso" || n.rfind("upper_arm", 0) == 0) out.push_back(shirt);
    else out.push_back(trousers);
  }
  return out;
}

/// The description table's parts = {...} and joints = {...} (see spawn_ragdoll);
/// each part's colour goes to `colors`.
physics::RagdollDesc readDescription(lua_State* L, int t, std::vector<Eigen::Vector3f>* colors) {
  physics::RagdollDesc d;
  if (rawGetField(L, t, "parts") != LUA_TTABLE) throw LuaArgError("field 'parts' must be a list of part tables");
  const int partsIdx = lua_gettop(L);
  const int nParts = int(lua_rawlen(L, partsIdx));
  if (nParts == 0) throw LuaArgError("field 'parts' must list at least one part");
  for (int i = 1; i <= nParts; ++i) {
    const std::string where = "parts[" + std::to_string(i) + "]";
    if (lua_rawgeti(L, partsIdx, i) != LUA_TTABLE) throw LuaArgError(where + " must be a table {name =, shape =, ...}");
    const int pt = lua_gettop(L);
    physics::RagdollPart p;
    try {
      checkFields(L, pt, where, {"name", "shape", "size", "radius", "length", "mass", "position", "rotation", "color"});
      p.name = optStringField(L, pt, "name", "");
      if (p.name.empty()) throw LuaArgError("field 'name' is required");
      for (const physics::RagdollPart& q : d.parts)
        if (q.name == p.name) throw LuaArgError("field 'name': '" + p.name + "' names two parts");
      const std::string shape = optStringField(L, pt, "shape", "box");
      if (shape == "box") {
        p.shape = physics::RagdollShape::Box;
        Vec3 size;
        if (!optVec3Field(L, pt, "size", &size)) throw LuaArgError("field 'size' is required for a box ({x, y, z}, m)");
        if (!(size.minCoeff() > 0)) throw LuaArgError("field 'size' must be > 0 m on every axis");
        p.halfExtents_m = size / 2;
      } else if (shape == "capsule") {
        p.shape = physics::RagdollShape::Capsule;
        p.radius_m = Real(optNumberField(L, pt, "radius", 0));
        if (!(p.radius_m > 0)) throw LuaArgError("field 'radius' must be > 0 m for a capsule");
        const Real length = Real(optNumberField(L, pt, "length", 0));
        if (!(length >= 0)) throw LuaArgError("field 'length' must be >= 0 m (the core between the caps' centres)");
        p.halfHeight_m = length / 2;
      } else {
        throw LuaArgError("field 'shape' must be \"box\" or \"capsule\", got \"" + shape + "\"");
      }
      p.mass_kg = Real(optNumberField(L, pt, "mass", 0));
      if (!(p.mass_kg > 0)) throw LuaArgError("field 'mass' is required and must be > 0 kg");
      if (!optVec3Field(L, pt, "position", &p.position_m)) throw LuaArgError("field 'position' is required ({x, y, z}, m)");
      p.orientation = optRotationField(L, pt);
      colors->push_back(colorField(L, pt, "color", kShirt));
    } catch (const LuaArgError& e) {
      throw LuaArgError(where + (p.name.empty() ? "" : " ('" + p.name + "')") + ": " + e.what());
    }
    d.parts.push_back(p);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  if (rawGetField(L, t, "joints") != LUA_TTABLE) throw LuaArgError("field 'joints' must be a list of joint tables ({} for none)");
  const int jointsIdx = lua_gettop(L);
  const int nJoints = int(lua_rawlen(L, jointsIdx));
  for (int k = 1; k <= nJoints; ++k) {
    const std::string where = "joints[" + std::to_string(k) + "]";
    if (lua_rawgeti(L, jointsIdx, k) != LUA_TTABLE) throw LuaArgError(where + " must be a table {type =, child =, parent =, ...}");
    const int jt = lua_gettop(L);
    physics::RagdollJoint j;
    try {
      checkFields(L, jt, where,
                        {"name", "type", "child", "parent", "anchor", "axis", "lower_angle", "upper_angle",
                         "swing_limit", "twist_lower", "twist_upper", "break_force"});
      j.name = optStringField(L, jt, "name", "");
      const std::string type = optStringField(L, jt, "type", "cone_twist");
      if (type == "ball") j.type = physics::JointType::Ball;
      else if (type == "hinge") j.type = physics::JointType::Hinge;
      else if (type == "cone_twist") j.type = physics::JointType::ConeTwist;
      else if (type == "fixed") j.type = physics::JointType::Fixed;
      else throw LuaArgError("field 'type' must be \"ball\", \"hinge\", \"cone_twist\" or \"fixed\", got \"" + type + "\"");
      j.partA = partField(L, jt, "child", d);
      j.partB = partField(L, jt, "parent", d);
      if (j.partA == j.partB) throw LuaArgError("fields 'child' and 'parent' must name different parts");
      if (!optVec3Field(L, jt, "anchor", &j.anchor_m)) throw LuaArgError("field 'anchor' is required ({x, y, z}, m)");
      optVec3Field(L, jt, "axis", &j.axis);
      if (!(j.axis.norm() > 0)) throw LuaArgError("field 'axis' must not be zero");
      j.axis.normalize();
      j.lowerAngle_rad = Real(optNumberField(L, jt, "lower_angle", -kPi / 2));
      j.upperAngle_rad = Real(optNumberField(L, jt, "upper_angle", kPi / 2));
      if (!(j.lowerAngle_rad <= j.upperAngle_rad))
        throw LuaArgError("fields 'lower_angle' and 'upper_angle' must have lower <= upper (rad)");
      j.swingLimit_rad = Real(optNumberField(L, jt, "swing_limit", j.swingLimit_rad));
      if (!(j.swingLimit_rad > 0 && j.swingLimit_rad < kPi)) throw LuaArgError("field 'swing_limit' must be in (0, pi) rad");
      j.twistLower_rad = Real(optNumberField(L, jt, "twist_lower", j.twistLower_rad));
      j.twistUpper_rad = Real(optNumberField(L, jt, "twist_upper", j.twistUpper_rad));
      if (!(j.twistLower_rad <= 0 && j.twistLower_rad > -kPi && j.twistUpper_rad >= 0 && j.twistUpper_rad < kPi))
        throw LuaArgError("fields 'twist_lower' and 'twist_upper' must be in (-pi, 0] and [0, pi) rad");
      j.breakForce_N = Real(optNumberField(L, jt, "break_force", 0));
      if (!(j.breakForce_N >= 0)) throw LuaArgError("field 'break_force' must be >= 0 N (0: unbreakable)");
    } catch (const LuaArgError& e) {
      throw LuaArgError(where + (j.name.empty() ? "" : " ('" + j.name + "')") + ": " + e.what());
    }
    d.joints.push_back(j);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  d.friction = Real(optNumberField(L, t, "friction", d.friction));
  if (!(d.friction >= 0)) throw LuaArgError("field 'friction' must be >= 0");
  return d;
}

/// Every length times s and every mass times s^3 (same density and shape).
void scaleDescription(physics::RagdollDesc& d, Real s) {
  for (physics::RagdollPart& p : d.parts) {
    p.halfExtents_m *= s;
    p.radius_m *= s;
    p.halfHeight_m *= s;
    p.position_m *= s;
    p.mass_kg *= s * s * s;
  }
  for (physics::RagdollJoint& j : d.joints) {
    j.anchor_m *= s;
    j.breakForce_N *= s * s * s;  // the same doll's weight, scaled
  }
}

/// @class RagdollPartDef
/// @field name string unique; the key of the part in the returned table
/// @field shape? string "box" (default) or "capsule"
/// @field size? Vec3Arg box: full size along the part's axes, m
/// @field radius? number capsule: radius, m
/// @field length? number capsule: core length between the caps' centres, along the part's Y, m (default 0)
/// @field mass number kg, > 0
/// @field position Vec3Arg centre of mass in the doll's frame (Y up, facing +Z, feet at y = 0), m
/// @field rotation? Vec3Arg the part's axes in the doll's frame: rotation vector, rad
/// @field color? Vec3Arg the part's colour {r, g, b}, each 0..1 (default a shirt blue)

/// @class RagdollJointDef
/// @field name? string for messages
/// @field type? string "ball", "hinge", "cone_twist" (default) or "fixed"
/// @field child string the part that hangs from the joint (a part's name)
/// @field parent string the part it hangs from
/// @field anchor Vec3Arg the joint point in the doll's frame, m
/// @field axis? Vec3Arg hinge axis, or twist axis pointing from the parent into the child, doll's frame (default {1, 0, 0})
/// @field lower_angle? number hinge: lower limit, rad (default -pi/2)
/// @field upper_angle? number hinge: upper limit, rad (default pi/2)
/// @field swing_limit? number cone_twist: largest swing from the axis, rad in (0, pi) (default pi/4)
/// @field twist_lower? number cone_twist: rad in (-pi, 0] (default -pi/8)
/// @field twist_upper? number cone_twist: rad in [0, pi) (default pi/8)
/// @field break_force? number the joint breaks above this force, N (0, the default: never)

/// @class RagdollDef
/// @field position? Vec3Arg where the doll's frame goes, m (default {0, 0, 0}; standing, the feet are there)
/// @field rotation? Vec3Arg turns the doll's frame: rotation vector, rad
/// @field scale? number every length times this, every mass times its cube (default 1)
/// @field height? number the default human only: standing height before scale, m (default 1.75)
/// @field mass? number the default human only: total mass before scale, kg (default 75)
/// @field parts? RagdollPartDef[] a doll of your own: its parts (then joints is required)
/// @field joints? RagdollJointDef[] its joints (parts joined by one do not collide with each other)
/// @field friction? number every part's friction (default 0.6)
/// @field colors? table the default human only: {skin =, shirt =, trousers =}, each a colour {r, g, b} 0..1 (head and forearms skin, torso and upper arms shirt, pelvis and legs trousers; defaults a light skin, a blue shirt, dark trousers)

/// @function spawn_ragdoll
/// Creates a rag-doll: the default human (11 parts, 10 joints; Winter's
/// anthropometric table, see ragdoll.cpp), or the parts and joints you
/// describe. Adjacent parts (joined by a joint) do not collide; the others
/// do; the parts sleep and wake together.
/// @param def RagdollDef placement, scale, and either height/mass or parts/joints
/// @return table the part Bodies keyed by part name (default human: pelvis, torso, head, upper_arm_l, lower_arm_l, upper_arm_r, lower_arm_r, upper_leg_l, lower_leg_l, upper_leg_r, lower_leg_r)
/// @example local doll = spawn_ragdoll{position = {0, 2, 0}, rotation = {1.5, 0, 0}}
/// @example local child = spawn_ragdoll{position = {2, 0, 0}, scale = 0.6}
/// @example local pendulum = spawn_ragdoll{position = {0, 3, 0}, parts = {
/// @example     {name = "top", shape = "box", size = {0.2, 0.2, 0.2}, mass = 2, position = {0, 0, 0}},
/// @example     {name = "arm", shape = "capsule", radius = 0.05, length = 0.8, mass = 1, position = {0, -0.5, 0}}},
/// @example   joints = {{type = "hinge", child = "arm", parent = "top", anchor = {0, 0, 0}, axis = {0, 0, 1},
/// @example             lower_angle = -1, upper_angle = 1}}}
int spawnRagdoll(lua_State* L) {
  const char* fn = "spawn_ragdoll";
  if (!lua_istable(L, 1))
    throw LuaArgError("spawn_ragdoll: expected a table, e.g. spawn_ragdoll{position = {0, 1, 0}, height = 1.8}");
  lua_settop(L, 1);
  ScenarioHost& host = *ScenarioHost::from(L);
  Vec3 position = Vec3::Zero();
  Quat q = Quat::Identity();
  physics::RagdollDesc desc;
  std::vector<Eigen::Vector3f> colors;
  try {
    checkFields(L, 1, fn, {"position", "rotation", "scale", "height", "mass", "parts", "joints", "friction", "colors"});
    optVec3Field(L, 1, "position", &position);
    q = optRotationField(L, 1);
    const Real scale = Real(optNumberField(L, 1, "scale", 1));
    if (!(scale > Real(0.01) && scale < 100)) throw LuaArgError("field 'scale' must be in (0.01, 100)");
    rawGetField(L, 1, "parts");
    const bool described = !lua_isnil(L, -1);
    lua_pop(L, 1);
    if (described) {
      for (const char* key : {"height", "mass", "colors"}) {
        rawGetField(L, 1, key);
        const bool given = !lua_isnil(L, -1);
        lua_pop(L, 1);
        if (given)
          throw LuaArgError(std::string("field '") + key +
                            "' is for the default human; with 'parts' give each part's size, mass and color");
      }
      desc = readDescription(L, 1, &colors);
    } else {
      const double height = optNumberField(L, 1, "height", 1.75), mass = optNumberField(L, 1, "mass", 75);
      if (!(height > 0.1 && height < 100)) throw LuaArgError("field 'height' must be in (0.1, 100) m");
      if (!(mass > 0)) throw LuaArgError("field 'mass' must be > 0 kg");
      desc = physics::defaultHuman(Real(height), Real(mass));
      desc.friction = Real(optNumberField(L, 1, "friction", desc.friction));
      colors = humanColors(L, 1, desc);
    }
    scaleDescription(desc, scale);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  host.countBodiesCreated(desc.parts.empty() ? 11 : desc.parts.size(), fn);  // the default doll has 11 parts
  auto r = physics::buildRagdoll(host.world(), host.scene().joints(), desc, position, q);
  if (!r) throw LuaArgError(std::string(fn) + ": " + r.error());
  lua_createtable(L, 0, int(desc.parts.size()));
  for (std::size_t i = 0; i < desc.parts.size(); ++i) {
    if (i < colors.size()) host.presentation().setColor(r.value().bodies[i], colors[i]);
    pushBody(L, r.value().bodies[i]);
    rawSetField(L, -2, desc.parts[i].name.c_str());
  }
  return 1;
}

/// @function joints_error
/// @return number the largest joint anchor separation now (m), 0 without joints; springs (grabs) do not count
/// @return number the largest seen since the start (m)
int jointsError(lua_State* L) {
  physics::JointSystem* j = ScenarioHost::from(L)->scene().jointsIfAny();
  lua_pushnumber(L, j ? j->anchorError_m(false) : 0.0);
  lua_pushnumber(L, j ? j->maxAnchorError_m() : 0.0);
  return 2;
}

const luaL_Reg kGlobals[] = {
    {"spawn_ragdoll", guarded<spawnRagdoll>},
    {"joints_error", guarded<jointsError>},
    {nullptr, nullptr},
};

}  // namespace

void openRagdollBindings(lua_State* L, int envIndex) { registerFunctions(L, envIndex, kGlobals); }

}  // namespace tumble::script
