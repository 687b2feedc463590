// world.snapshot() and world.restore(snapshot): a scenario tries something
// and undoes it. The snapshot is the rigid-body world's whole state as exact
// bits (physics::World::saveState: bodies, contact cache with warm starts,
// broad phase order, sleep, springs, settings), held in Lua memory (it counts
// against the scenario's memory budget and goes with the garbage collector).
//
//   local before = world.snapshot()
//   ball:apply_impulse{0, 50, 0}   -- try it ...
//   world.restore(before)          -- ... and undo it
#include <cstring>

#include "physics/deformable.h"
#include "physics/joints/joint_system.h"
#include "script/internal/bind_common.h"

namespace tumble::script {
namespace {

constexpr const char* kSnapshotMeta = "tumble.WorldSnapshot";

/// Joints, vehicles, particles, ropes and cloth keep state of their own that
/// a world snapshot does not hold: restoring only the bodies under them would
/// not put the scene back, so both calls refuse while one exists.
void refuseOtherSystems(lua_State* L, const char* fn) {
  SceneSystems& s = ScenarioHost::from(L)->scene();
  const char* what = s.jointsIfAny() && s.jointsIfAny()->jointCount() > 0 ? "joints"
                     : s.vehiclesIfAny()                                   ? "vehicles"
                     : s.particlesIfAny()                                  ? "particle emitters"
                     : s.deformablesIfAny()                                ? "ropes or cloth"
                                                                           : nullptr;
  if (what)
    throw LuaArgError(std::string(fn) + ": the scene has " + what +
                      "; a world snapshot holds the rigid bodies, their contacts and springs only");
}

/// @class WorldSnapshot
/// The rigid-body world at one moment (world.snapshot), for world.restore.

/// @function world.snapshot
/// The rigid-body world's whole state now, exactly: every body's pose,
/// velocities, mass, material and sleep state, the contacts with their
/// warm-start impulses, springs and world settings (gravity). Refused while
/// the scene has joints, vehicles, particle emitters, ropes or cloth, whose
/// own state it does not hold. Lua state (locals, ctx.state, timers) is not
/// part of it.
/// @return WorldSnapshot in memory, for world.restore in the same run
/// @example local before = world.snapshot()
int worldSnapshot(lua_State* L) {
  refuseOtherSystems(L, "world.snapshot");
  const std::string bytes = ScenarioHost::from(L)->world().saveState();
  void* p = lua_newuserdatauv(L, bytes.size(), 0);
  std::memcpy(p, bytes.data(), bytes.size());
  luaL_setmetatable(L, kSnapshotMeta);
  return 1;
}

/// @function world.restore
/// Puts the world back to a snapshot exactly: stepping on from it gives the
/// same bits as stepping on from the moment it was taken. The world must
/// still have the same bodies: a body made or removed since is an error
/// naming the first body slot that differs (the world is then unchanged).
/// Body handles stay valid. Lua state is not touched.
/// @param snapshot WorldSnapshot from world.snapshot
/// @example world.restore(before)
int worldRestore(lua_State* L) {
  refuseOtherSystems(L, "world.restore");
  auto* p = static_cast<const char*>(luaL_testudata(L, 1, kSnapshotMeta));
  if (!p)
    throw LuaArgError(std::string("world.restore: expected a WorldSnapshot (from world.snapshot), got ") +
                      luaL_typename(L, 1));
  const std::string bytes(p, lua_rawlen(L, 1));
  if (Status st = ScenarioHost::from(L)->world().restoreState(bytes); !st)
    throw LuaArgError("world.restore: " + st.error());
  return 0;
}

int snapshotToString(lua_State* L) {
  lua_pushfstring(L, "WorldSnapshot (%d bytes)", int(lua_rawlen(L, 1)));
  return 1;
}

const luaL_Reg kNoMethods[] = {{nullptr, nullptr}};
const luaL_Reg kFunctions[] = {
    {"snapshot", guarded<worldSnapshot>},
    {"restore", guarded<worldRestore>},
    {nullptr, nullptr},
};

}  // namespace

void openWorldSnapshotBindings(lua_State* L, int envIndex) {
  registerType(L, BoundType{kSnapshotMeta, kNoMethods, snapshotToString});
  if (rawGetField(L, envIndex, "world") != LUA_TTABLE) {
    lua_pop(L, 1);
    return;
  }
  registerFunctions(L, lua_gettop(L), kFunctions);
  lua_pop(L, 1);
}

}  // namespace tumble::script
