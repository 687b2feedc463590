// world.snapshot() and world.restore(snapshot): a scenario tries something
// and undoes it. The snapshot is the simulated state of the scene's systems
// as exact bits (script/systems_state.h: the rigid-body world with its
// contacts, warm starts and springs; the joints; vehicles; ropes and
// cloth; particle emitters), held in Lua memory (it counts against the scenario's memory
// budget and goes with the garbage collector).
//
//   local before = world.snapshot()
//   ball:apply_impulse{0, 50, 0}   -- try it ...
//   world.restore(before)          -- ... and undo it
#include <cstring>

#include "core/byte_stream.h"
#include "script/internal/bind_common.h"
#include "script/presentation.h"
#include "script/systems_state.h"

namespace tumble::script {
namespace {

constexpr const char* kSnapshotMeta = "tumble.WorldSnapshot";
constexpr std::uint32_t kSnapshotMagic = 0x54534e50;  // "TSNP"

std::string pack(const SystemsState& s) {
  ByteWriter w;
  w.pod(kSnapshotMagic);
  for (const std::string* part : {&s.jointSolver, &s.world, &s.joints, &s.vehicles, &s.ropesAndCloth, &s.particles}) w.text(*part);
  return w.take();
}

bool unpack(const std::string& bytes, SystemsState& s) {
  ByteReader r(bytes);
  if (r.pod<std::uint32_t>() != kSnapshotMagic) return false;
  for (std::string* part : {&s.jointSolver, &s.world, &s.joints, &s.vehicles, &s.ropesAndCloth, &s.particles})
    *part = r.text(bytes.size());
  return r.ok() && r.atEnd();
}

/// @class WorldSnapshot
/// The scene's simulated state at one moment (world.snapshot), for world.restore.

/// @function world.snapshot
/// The scene's whole simulated state now, exactly: every body's pose,
/// velocities, mass, material and sleep state, the contacts with their
/// warm-start impulses, springs and world settings (gravity); every joint
/// and both joint solvers' memory; the vehicles' engines, gears and wheels;
/// ropes and cloth; particle emitters and their particles. Lua state
/// (locals, ctx.state, timers, a driving helper's memory) is not part of it.
/// @return WorldSnapshot in memory, for world.restore in the same run
/// @example local before = world.snapshot()
int worldSnapshot(lua_State* L) {
  const std::string bytes = pack(saveSystems(ScenarioHost::from(L)->scene()));
  void* p = lua_newuserdatauv(L, bytes.size(), 0);
  std::memcpy(p, bytes.data(), bytes.size());
  luaL_setmetatable(L, kSnapshotMeta);
  return 1;
}

/// @function world.restore
/// Puts the scene back to a snapshot exactly: stepping on from it gives the
/// same bits as stepping on from the moment it was taken. Bodies, joints
/// and emitters made since are removed; ones removed since come back with
/// their shapes (static models too, from their triangles). Vehicles
/// spawned, re-tuned or removed since come back as they were; the scene
/// must still have the same ropes and cloth. An error leaves the scene as
/// it was. Handles to what came back are valid again. Lua state is not
/// touched.
/// @param snapshot WorldSnapshot from world.snapshot
/// @example world.restore(before)
int worldRestore(lua_State* L) {
  auto* p = static_cast<const char*>(luaL_testudata(L, 1, kSnapshotMeta));
  if (!p)
    throw LuaArgError(std::string("world.restore: expected a WorldSnapshot (from world.snapshot), got ") +
                      luaL_typename(L, 1));
  SystemsState saved;
  if (!unpack(std::string(p, lua_rawlen(L, 1)), saved)) throw LuaArgError("world.restore: a damaged WorldSnapshot");
  SceneSystems& scene = ScenarioHost::from(L)->scene();
  // All or nothing: a part refused after others were restored puts back
  // the state from before the call, saved from this very scene, so every
  // part of it goes back (every shape is stored whole). Should that fail
  // all the same, the error says what the scene is left with.
  const SystemsState now = saveSystems(scene);
  const std::map<std::string, std::string>& modDirs = ScenarioHost::from(L)->options().modDirs;
  auto inMods = [&](const std::string& file) { return isFileInMods(file, modDirs); };
  if (Status st = restoreSystems(scene, saved, inMods); !st) {
    if (Status back = restoreSystems(scene, now, inMods); !back)
      throw LuaArgError("world.restore: " + st.error() + "; and the state before the call could not be put back (" +
                        back.error() + "): the bodies are the snapshot's, the rest as before the call");
    throw LuaArgError("world.restore: " + st.error());
  }
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
