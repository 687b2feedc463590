// Rag-dolls for scripts: spawn_ragdoll{...} builds the default human
// (physics/joints/ragdoll.h) in the scene's JointSystem, which the host then
// drives before every World::step; joints_error() reads the anchor error.
//
//   local doll = spawn_ragdoll{position = {0, 1, 0}, height = 1.8, mass = 75}
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

/// @function spawn_ragdoll
/// Creates the default human (11 parts, 10 joints; Winter's anthropometric
/// table, see ragdoll.cpp) with its feet at `position` when standing.
/// Adjacent parts do not collide; the parts sleep and wake together.
/// @param def table position? Vec3Arg (m, default {0,0,0}), height? number
///   (m, default 1.75), mass? number (kg, default 75), rotation? Vec3Arg
///   rotation vector (axis times angle, rad)
/// @return table the part Bodies keyed by part name (pelvis, torso, head,
///   upper_arm_l, lower_arm_l, upper_arm_r, lower_arm_r, upper_leg_l,
///   lower_leg_l, upper_leg_r, lower_leg_r)
/// @example local doll = spawn_ragdoll{position = {0, 2, 0}, rotation = {1.5, 0, 0}}
int spawnRagdoll(lua_State* L) {
  if (!lua_istable(L, 1))
    throw LuaArgError("spawn_ragdoll: expected a table, e.g. spawn_ragdoll{position = {0, 1, 0}, height = 1.8}");
  ScenarioHost& host = *ScenarioHost::from(L);
  Vec3 position = Vec3::Zero(), rv = Vec3::Zero();
  double height = 1.75, mass = 75;
  try {
    optVec3Field(L, 1, "position", &position);
    optVec3Field(L, 1, "rotation", &rv);
    height = optNumberField(L, 1, "height", height);
    mass = optNumberField(L, 1, "mass", mass);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string("spawn_ragdoll: ") + e.what());
  }
  if (!(height > 0.1 && height < 100)) throw LuaArgError("spawn_ragdoll: field 'height' must be in (0.1, 100) m");
  if (!(mass > 0 && std::isfinite(mass))) throw LuaArgError("spawn_ragdoll: field 'mass' must be > 0 kg");
  Quat q = Quat::Identity();
  if (rv.norm() > 0) q = Quat(Eigen::AngleAxis<Real>(rv.norm(), rv / rv.norm()));
  physics::RagdollDesc desc = physics::defaultHuman(Real(height), Real(mass));
  auto r = physics::buildRagdoll(host.world(), host.joints(), desc, position, q);
  if (!r) throw LuaArgError("spawn_ragdoll: " + r.error());
  lua_createtable(L, 0, int(desc.parts.size()));
  for (std::size_t i = 0; i < desc.parts.size(); ++i) {
    pushBody(L, r.value().bodies[i]);
    lua_setfield(L, -2, desc.parts[i].name.c_str());
  }
  return 1;
}

/// @function joints_error
/// @return number the largest joint anchor separation now (m), 0 without joints; springs (grabs) do not count
/// @return number the largest seen since the start (m)
int jointsError(lua_State* L) {
  physics::JointSystem* j = ScenarioHost::from(L)->jointsIfAny();
  lua_pushnumber(L, j ? j->anchorError_m(false) : 0.0);
  lua_pushnumber(L, j ? j->maxAnchorError_m() : 0.0);
  return 2;
}

}  // namespace

void openRagdollBindings(lua_State* L, int envIndex) {
  lua_pushcfunction(L, guarded<spawnRagdoll>);
  lua_setfield(L, envIndex, "spawn_ragdoll");
  lua_pushcfunction(L, guarded<jointsError>);
  lua_setfield(L, envIndex, "joints_error");
}

}  // namespace tumble::script
