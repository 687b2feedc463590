#pragma once
// Snapshots of a running scene: `run --save-state FILE --at T` writes the
// whole simulated state after the step that ends at or after T, and
// `run --load-state FILE` starts a run from it. A run split this way ends
// in the same state hash as the run without a split (tests/app/
// scene_state_test.cpp checks every base scenario that can be split).
//
// What is stored, exactly (floats as their bits): the rigid-body world
// (physics::World::saveState: bodies, contact cache with warm starts, broad
// phase order, sleep, springs, settings), the scenario's Lua state as far as
// C++ can keep it (script::ScenarioHost::saveState: ctx.state, timers'
// schedule, random generators, game state, expectations), the run's clock
// and step. Loading makes the scene from the snapshot's options, runs
// on_start again (it re-makes shapes, locals and timers), then puts the saved
// state back and checks that the world's state hash is the saved one.
//
// Also the joints (physics::JointSystem::saveState: every joint, both
// solvers' memory), vehicles (vehicle::VehicleSystem::saveState), ropes and
// cloth (physics::DeformableSystem::saveState) and particle emitters with
// their particles (particles::ParticleSystem::saveState), through
// script/systems_state.h. Refused at save time, with a message saying what
// and why: Lua state a snapshot cannot keep
// (script/scenario_state.cpp). The file is JSON (docs/snapshots.md), written
// atomically, with the engine build, the mods' versions and a checksum:
// another build, other mod versions, another scenario, or a damaged or
// edited file is refused with a message naming the field.
#include <cstdint>
#include <map>
#include <string>

#include "app/scene.h"
#include "core/result.h"
#include "script/systems_state.h"

namespace tumble::app {

/// Where a run is in simulated time (run_command.cpp's clock).
struct RunClock {
  long long step = 0;      ///< steps done
  double time_s = 0;       ///< simulated time now
  double baseTime_s = 0;   ///< time at the last change of the step length
  long long baseStep = 0;  ///< step index of that change
  double stepDt_s = 0;     ///< the step length since then
};

struct SceneStateFile {
  /// 2: the joints (joint solver and state) and the other systems' states.
  static constexpr int kFormatVersion = 2;
  std::string scenario;  ///< MOD:SCENARIO
  std::uint64_t seed = 1;
  double dt_s = 1.0 / 60.0;
  int substeps = 0;
  std::string integrator;
  std::map<std::string, std::string> sets;
  std::string engineBuild;
  std::map<std::string, std::string> modVersions;
  RunClock clock;
  double requestedDt_s = 0;  ///< world.set_dt, 0 none
  std::string stateHash;     ///< the scene's state hash when saved
  script::SystemsState systems;  ///< world, joints, vehicles, ropes and cloth, particles (bytes each)
  std::string script;            ///< the scenario's Lua state (bytes)
};

/// Checks that the scene can be saved (the message names what cannot) and
/// writes the snapshot atomically.
Status saveSceneState(Scene& scene, const RunClock& clock, const std::string& path);
/// Reads and checks a snapshot file: format, version, checksum, each
/// field's type. Messages name the file and the field.
Result<SceneStateFile> loadSceneState(const std::string& path);
/// The options a loaded run uses: the snapshot's scenario, seed, dt,
/// substeps, integrator and --set values over `options`.
void applySceneStateOptions(const SceneStateFile& s, SceneOptions& options);
/// After scene.start(): refuses another engine build or other mod versions
/// (naming them), puts the saved state back and checks the state hash.
Status restoreSceneState(Scene& scene, const SceneStateFile& s, const std::string& path);

}  // namespace tumble::app
