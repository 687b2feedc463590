#pragma once
// Replays: `play --record FILE` writes what a played session's scripts read
// of the player's input in every fixed step, with everything else the run
// depends on (scenario, seed, step, substeps, integrator, --set values, the
// player's saved tunable values, the engine build and the mods' versions);
// `run --replay FILE` runs the same steps headless with that input and
// checks that it ends in the recorded state hash.
//
// Determinism makes this enough: a scene's end state depends only on its
// options and on the input actions scripts read (InputSystem::StepState per
// action per step, the pointer and its ray). The file is JSON
// (docs/replays.md), written atomically, with a checksum over its content so
// a damaged or edited file is refused with a message that says so. A replay
// made by another engine build or with other mod versions is run with a
// warning naming the difference, and the end hash decides.
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/scene.h"
#include "core/result.h"
#include "input/input_system.h"

namespace tumble::app {

/// The engine's build id: the GNU build-id note the linker put into this
/// executable (hex), or "unknown" without one.
std::string engineBuildId();

/// The checksum a replay or a scene snapshot file carries: a hash of the
/// document's JSON text without its "checksum" field (hex).
std::string checksumOf(nlohmann::json doc);

/// What scripts read of the input in one step.
struct ReplayStep {
  std::vector<input::InputSystem::StepState> actions;  ///< in action order
  std::optional<std::array<float, 2>> pointer;          ///< normalised -1..1, y up (InputSystem::pointer)
  std::optional<std::array<double, 6>> pointerRay;      ///< origin (m), unit direction
  bool operator==(const ReplayStep&) const = default;
};

struct Replay {
  static constexpr int kFormatVersion = 1;
  std::string scenario;  ///< MOD:SCENARIO
  std::uint64_t seed = 1;
  double dt_s = 1.0 / 60.0;
  int substeps = 0;
  std::string integrator;
  std::map<std::string, std::string> sets;  ///< --set KEY=VALUE of the recorded session
  nlohmann::json tuneOverrides;  ///< the player's saved tunable values (the overrides file), or null
  std::string engineBuild;
  std::map<std::string, std::string> modVersions;  ///< every mod found: name -> version
  std::vector<std::string> actions;  ///< action names, in the order of each step's states
  std::vector<ReplayStep> steps;
  std::string stateHash;  ///< at the end of the last step
  double simulatedSeconds = 0;
};

/// Collects a played session's steps. start() after the scene started
/// (and again after a restart: the recording starts over).
class ReplayRecorder {
 public:
  void start(Scene& scene, const SceneOptions& options);
  /// After each fixed step.
  void afterStep(Scene& scene);
  /// Finishes the replay (state hash, time) and writes it atomically.
  Status write(Scene& scene, double simulatedSeconds, const std::string& path);
  const Replay& replay() const { return m_replay; }

 private:
  Replay m_replay;
};

nlohmann::json replayToJson(const Replay& r);
/// Reads and checks a replay file: format, version, checksum, every field's
/// type and range, each step's action count. Messages name the file and field.
Result<Replay> loadReplay(const std::string& path);
/// Differences between the replay's engine build and mod versions and this
/// program's (empty: none), one line each.
std::vector<std::string> replayVersionWarnings(const Replay& r, const Scene& scene);
/// Feeds the replay's step `index` to the scene's input before that step.
void playBackStep(const Replay& r, long long index, Scene& scene);

}  // namespace tumble::app
