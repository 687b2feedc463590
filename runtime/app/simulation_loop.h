#pragma once
// `tumble run` (run_command.cpp) and `tumble play` (play_command.cpp). The
// per-frame path, in one place (STYLE.md): fixed-step simulation with
// an accumulator, Lua at the fixed rate, rendering interpolated between the
// last two steps.
//
//   SDL events -> the fixed steps due (app/fixed_step.cpp: input actions,
//     Lua, joints, vehicles, physics, ropes and cloth, after-step callbacks,
//     particles) -> render snapshot (interpolated) -> renderer -> HUD
#include <string>

#include "app/scene.h"
#include "core/process_stats.h"

namespace tumble::app {

struct RunOptions {
  SceneOptions scene;
  long long steps = -1;   ///< --steps; -1: from seconds
  double seconds = -1;    ///< --seconds; -1: the scenario's duration
  std::string reportPath;
  std::string screenshotPath;
  double screenshotAt_s = -1;  ///< -1: at the end
  int width = 1280, height = 720;
  /// --save-dir: where the scenario's save.write files go. Empty: a
  /// throw-away folder removed at exit, so a run never changes the player's
  /// saves and two identical runs read the same (no) saves.
  std::string saveDir;
  /// --audio-out: render the scene's sound offline (OpenAL Soft's loopback
  /// device, in step with simulated time) and write it here as a WAV.
  std::string audioOutPath;
  /// --inject-nan STEP (test switch): before step STEP the first dynamic
  /// body's position and velocity become NaN; -1: never. The world freezes
  /// the body and counts it (error.nan_events), and the run then fails the
  /// expectation "physics state stayed finite".
  long long injectNanAtStep = -1;
  /// --replay FILE: run a replay written by `play --record` (app/replay.h)
  /// and check that it ends in the recorded state.
  std::string replayPath;
  /// --save-state FILE: write a snapshot of the scene (app/scene_state.h)
  /// after the step that ends at or after --at (default: the end); the run
  /// goes on to its end as usual.
  std::string saveStatePath;
  /// --load-state FILE: start from a snapshot instead of from the start.
  std::string loadStatePath;
};

struct PlayOptions {
  SceneOptions scene;
  int width = 1280, height = 720;
  /// Without a display, play runs this long (or the scenario's duration if
  /// shorter), writes the screenshot and prints a summary.
  double offscreenSeconds = 5;
  std::string screenshotPath = "tumble-play.png";
  bool screenshotGiven = false;  ///< --screenshot was on the command line
  /// --frames N: play exactly N frames offscreen (one fixed step each
  /// unless paused), then stop; -1: until the player quits.
  long long frames = -1;
  std::string eventsPath;  ///< --events FILE: scripted input (app/play_events.h)
  std::string reportPath;  ///< --report FILE: what the player saw (docs/play-report.md)
  bool mute = false;       ///< --mute: no audio device at all
  /// No scenario on the command line: the main menu (app/main_menu.h).
  bool menu = false;
  bool sizeGiven = false;  ///< --width or --height given: they win over the saved settings
  std::string quality;     ///< --quality low|medium|high; empty: the saved setting
  std::string recordPath;  ///< --record FILE: a replay of the session (app/replay.h, docs/replays.md)
  /// `tumble design [MOD:SCENARIO | new]`: the designer instead of the menu
  /// (app/designer_mode.h); designRef empty or "new": the New map dialog.
  bool design = false;
  std::string designRef;
};

/// `tumble run`: headless unless a screenshot is asked for. Returns the exit
/// status (0 ok, 2 expectation failed, 3 script error, 1 could not start).
int runScenario(const RunOptions& options, const Stopwatch& processClock);

/// `tumble play`: a window, or offscreen when there is no display.
int playScenario(const PlayOptions& options, const Stopwatch& processClock);

}  // namespace tumble::app
