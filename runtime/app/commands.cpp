#include "core/cli_finite.h"
#include "app/commands.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "app/paths.h"
#include "app/simulation_loop.h"
#include "core/log.h"
#include "core/file_util.h"
#include "script/mod_bindings.h"
#include "script/mods.h"
#include "script/tunables.h"
#include "script/vehicle_defs.h"

namespace tumble::app {

namespace {

// State shared by the subcommands' callbacks; lives for the program.
struct CommandState {
  std::vector<std::string> modDirs;
  RunOptions run;
  PlayOptions play;
  std::string playScenarioRef;  // empty: the main menu
  PlayOptions design;           // `design`: the designer (app/designer_mode.h)
  std::string runScenarioRef;
  std::vector<std::string> runSets, playSets;
  std::string checkDir;
  Stopwatch clock;
};

Status parseSets(const std::vector<std::string>& sets, std::map<std::string, std::string>& out) {
  for (const std::string& s : sets) {
    auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      return makeError("--set " + s + ": expected KEY=VALUE (for example --set n=5 or --set physics.substeps=4)");
    out[s.substr(0, eq)] = s.substr(eq + 1);
  }
  return Ok{};
}

// Completes the scene options from what the command line gave.
Status finishSceneOptions(SceneOptions& scene, const std::string& ref, const CommandState& st,
                          const std::vector<std::string>& sets) {
  scene.scenarioRef = ref;
  scene.modDirs = st.modDirs;
  return parseSets(sets, scene.sets);
}


void addSceneOptions(CLI::App* cmd, SceneOptions& scene, std::vector<std::string>& sets) {
  cmd->add_option("--dt", scene.dt_s, "fixed time step, s (default 1/60)")->check(kFinite)->check(CLI::PositiveNumber);
  cmd->add_option("--substeps", scene.substeps, "physics substeps per step (default: the world's, 8)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--threads", scene.threads,
                  "threads of the physics step, 1..64 (default 1); the results are the same, bit for bit, for any "
                  "number")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--integrator", scene.integrator, "rigid-body integrator: symplectic_euler (default), euler, heun, rk4, verlet, implicit_euler, implicit_midpoint, sdirk2; overrides the scenario's integrator field");
  cmd->add_option("--set", sets, "KEY=VALUE: a scenario parameter (param() in Lua), a physics.* setting or a tunable (tune.NAME)");
  cmd->add_option("--seed", scene.seed, "seed for the scenario's random numbers (default 1)");
}

// The actions a mod's bindings.lua declares, by context: "  actions    vehicle: steer (axis), ...".
void listActions(const script::ModInfo& m) {
  script::ModBindings b = script::loadModBindings(m);
  std::string line;
  for (const input::ContextDef& c : b.set.contexts) {
    std::string names;
    for (const input::ActionDef& a : b.set.actions)
      if (a.context == c.name) names += (names.empty() ? "" : ", ") + a.name + (a.type == input::ActionType::Axis ? " (axis)" : "");
    line += (line.empty() ? "" : "; ") + c.name + ": " + (names.empty() ? "-" : names);
  }
  std::printf("  %-10s %s\n", "actions", line.empty() ? "-" : line.c_str());
  for (const auto& p : b.problems) std::printf("  problem: %s\n", p.text().c_str());
}

int listMods(const std::vector<std::string>& modDirs) {
  script::ModRegistry reg = script::ModRegistry::discover(modSearchDirs(modDirs));
  for (const script::ModInfo& m : reg.mods()) {
    std::printf("%s %s  %s\n  folder: %s\n", m.name.c_str(), m.version.c_str(), m.title.c_str(), m.dir.c_str());
    for (const char* folder : {"scenarios", "vehicles", "emitters"}) {
      auto names = script::ModRegistry::listLua(m, folder);
      std::string line;
      for (const auto& n : names) line += (line.empty() ? "" : ", ") + (std::string(folder) != "vehicles" ? m.name + ":" + n : n);
      std::printf("  %-10s %s\n", folder, line.empty() ? "-" : line.c_str());
    }
    listActions(m);
    for (const auto& n : script::ModRegistry::listLua(m, "vehicles")) {
      auto def = script::loadVehicleFile(m, n);
      if (!def) {
        std::printf("    %s:%s  problem: %s\n", m.name.c_str(), n.c_str(), def.error().c_str());
        continue;
      }
      const vehicle::VehicleDef& d = def.value();
      std::printf("    %s:%s  %s, %.0f kg, %.0f kW: %s\n", m.name.c_str(), n.c_str(), d.name.c_str(),
                  double(d.chassis.mass_kg), double(vehicle::peakPower_W(d.engine)) / 1000, d.description.c_str());
    }
  }
  for (const auto& p : reg.problems()) std::printf("problem: %s\n", p.text().c_str());
  return reg.problems().empty() ? 0 : 1;
}

int checkModDir(const std::string& dir, const std::vector<std::string>& modDirs) {
  // Dependencies resolve against every mod folder, as when playing.
  auto problems = script::checkMod(dir, modSearchDirs(modDirs));
  // Vehicle files are data: each is run and every field checked.
  if (auto mod = script::loadManifest(dir); mod) {
    auto vehicles = script::checkVehicles(mod.value());
    problems.insert(problems.end(), vehicles.begin(), vehicles.end());
  }
  if (problems.empty()) {
    std::printf("%s: no problems found\n", dir.c_str());
    return 0;
  }
  for (const auto& p : problems) std::printf("%s\n", p.text().c_str());
  std::printf("%zu problem%s in %s\n", problems.size(), problems.size() == 1 ? "" : "s", dir.c_str());
  return 1;
}

}  // namespace

void removeOrphanedUserTemporaries() {
  removeOrphanedTemporaries(script::userConfigDir(), 1);  // bindings.json, tune/*.json
  removeOrphanedTemporaries(script::savesDir(), 1);       // <mod>/*.json
}

void addCommands(CLI::App& cli, int* exitCode) {
  auto st = std::make_shared<CommandState>();
  cli.add_option("--mods", st->modDirs, "another folder to find mods in (repeatable)");
  cli.fallthrough();

  CLI::App* play = cli.add_subcommand("play", "play a scenario in a window (offscreen when there is no display)");
  play->add_option("scenario", st->playScenarioRef, "MOD:SCENARIO (default: the main menu)");
  play->add_option("--width", st->play.width, "window width, px")->check(CLI::Range(64, 16384));
  play->add_option("--height", st->play.height, "window height, px")->check(CLI::Range(64, 16384));
  play->add_option("--screenshot", st->play.screenshotPath,
                   "where play without a display writes its picture (with --frames: the last frame)");
  play->add_option("--frames", st->play.frames,
                   "play exactly N frames offscreen (one fixed step each unless paused), then stop")
      ->check(CLI::NonNegativeNumber);
  play->add_option("--events", st->play.eventsPath,
                   "scripted input pushed into SDL's event queue, one event a line: FRAME down|up SOURCE "
                   "(key:W, mouse:left, pad:a), FRAME axis pad_axis:NAME VALUE, FRAME move X Y, "
                   "FRAME wheel Y, FRAME quit; '#' starts a comment (docs/play-events.md); needs --frames");
  play->add_option("--report", st->play.reportPath,
                   "write what the player saw (JSON): scenario, pause menu, vehicle speed and distance, "
                   "frame times, state hash");
  play->add_flag("--mute", st->play.mute, "no sound: open no audio device");
  play->add_option("--quality", st->play.quality, "rendering quality preset: low, medium or high (default: the saved setting)")
      ->check(CLI::IsMember({"low", "medium", "high"}));
  play->add_option("--record", st->play.recordPath,
                   "write a replay of the session: the input its scripts read each step, the seed, scenario, "
                   "settings and versions (`run --replay FILE` plays it back; docs/replays.md)");
  addSceneOptions(play, st->play.scene, st->playSets);
  play->callback([st, exitCode, play] {
    st->play.screenshotGiven = play->count("--screenshot") > 0;
    st->play.sizeGiven = play->count("--width") > 0 || play->count("--height") > 0;
    st->play.menu = st->playScenarioRef.empty();
    if (st->play.menu) st->playScenarioRef = "base:drop";  // what play shows without a display
    if (auto s = finishSceneOptions(st->play.scene, st->playScenarioRef, *st, st->playSets); !s) {
      log::error(s.error());
      *exitCode = 1;
      return;
    }
    *exitCode = playScenario(st->play, st->clock);
  });

  CLI::App* design = cli.add_subcommand("design", "the scenario designer in a window: make a map, sculpt, paint, "
                                                   "place objects, drive it (F5), save it as a mod (docs/designer.md)");
  design->add_option("scenario", st->design.designRef, "MOD:SCENARIO a designer saved, or new (default: new)");
  design->add_option("--width", st->design.width, "window width, px")->check(CLI::Range(64, 16384));
  design->add_option("--height", st->design.height, "window height, px")->check(CLI::Range(64, 16384));
  design->add_option("--frames", st->design.frames, "play exactly N frames offscreen, then stop (with --events)")
      ->check(CLI::NonNegativeNumber);
  design->add_option("--events", st->design.eventsPath, "scripted input, as for play (docs/play-events.md); needs --frames");
  design->add_option("--report", st->design.reportPath, "write what the player saw (JSON), the designer's state included");
  design->add_option("--screenshot", st->design.screenshotPath, "with --frames: the last frame");
  design->add_flag("--mute", st->design.mute, "no sound: open no audio device");
  design->add_option("--quality", st->design.quality, "rendering quality preset: low, medium or high")
      ->check(CLI::IsMember({"low", "medium", "high"}));
  design->callback([st, exitCode, design] {
    st->design.screenshotGiven = design->count("--screenshot") > 0;
    st->design.sizeGiven = design->count("--width") > 0 || design->count("--height") > 0;
    st->design.design = true;
    if (auto s = finishSceneOptions(st->design.scene, "base:drop", *st, {}); !s) {
      log::error(s.error());
      *exitCode = 1;
      return;
    }
    *exitCode = playScenario(st->design, st->clock);
  });

  CLI::App* run = cli.add_subcommand("run", "run a scenario headless and check its expectations");
  run->add_option("scenario", st->runScenarioRef, "MOD:SCENARIO (not with --replay: the replay names it)");
  run->add_option("--replay", st->run.replayPath,
                  "play back a replay written by `play --record` headless and check that it ends in the recorded "
                  "state hash (exit 4 if not; docs/replays.md)");
  run->add_option("--save-state", st->run.saveStatePath,
                  "write a snapshot of the whole simulated state after the step that ends at or after --at T "
                  "(default: the end); the run goes on to its end (docs/snapshots.md)");
  run->add_option("--load-state", st->run.loadStatePath,
                  "start from a snapshot written by --save-state and run to the end: the snapshot names the "
                  "scenario and holds its seed, dt, substeps and --set values (docs/snapshots.md)");
  run->add_option("--seconds", st->run.seconds, "simulated seconds (default: the scenario's duration)")
      ->check(kFinite)->check(CLI::NonNegativeNumber);
  run->add_option("--steps", st->run.steps, "number of fixed steps (instead of --seconds)")
      ->check(CLI::NonNegativeNumber);
  run->add_option("--report", st->run.reportPath, "write the run report (JSON) here");
  run->add_option("--screenshot", st->run.screenshotPath, "render offscreen and save a PNG here");
  run->add_option("--at", st->run.screenshotAt_s,
                  "simulated time of the screenshot and of --save-state, s (default: the end)")
      ->check(kFinite)->check(CLI::NonNegativeNumber);
  run->add_option("--save-dir", st->run.saveDir,
                  "where the scenario's save.write files go (default: a throw-away folder removed at exit, "
                  "so runs never change the player's saves)");
  run->add_option("--width", st->run.width, "screenshot width, px")->check(CLI::Range(64, 16384));
  run->add_option("--height", st->run.height, "screenshot height, px")->check(CLI::Range(64, 16384));
  run->add_option("--audio-out", st->run.audioOutPath,
                  "render the scene's sound offline (no sound card needed) and write it here as a 48 kHz stereo WAV");
  run->add_flag("--freeze", st->run.scene.freezePhysics,
                "test switch: scripts run but the physics never steps; every base scenario must then fail an "
                "expectation (tests/scenarios/CMakeLists.txt)");
  run->add_option("--inject-nan", st->run.injectNanAtStep,
                  "test switch: before step N the first dynamic body's position and velocity become NaN; the run "
                  "must then fail")
      ->check(CLI::NonNegativeNumber);
  addSceneOptions(run, st->run.scene, st->runSets);
  run->callback([st, exitCode] {
    if (st->run.replayPath.empty() == st->runScenarioRef.empty()) {
      log::error(st->run.replayPath.empty() ? "run: give MOD:SCENARIO (or --replay FILE)"
                                             : "run --replay: the replay names its scenario; leave MOD:SCENARIO out");
      *exitCode = 1;
      return;
    }
    if (!st->run.loadStatePath.empty() && (!st->run.replayPath.empty() || !st->runSets.empty())) {
      log::error("run --load-state: the snapshot holds the run's --set values and input; give no --set or --replay");
      *exitCode = 1;
      return;
    }
    if (!st->run.replayPath.empty() && !st->runSets.empty()) {
      log::error("run --replay: the replay holds the session's --set values; give none");
      *exitCode = 1;
      return;
    }
    if (auto s = finishSceneOptions(st->run.scene, st->runScenarioRef, *st, st->runSets); !s) {
      log::error(s.error());
      *exitCode = 1;
      return;
    }
    *exitCode = runScenario(st->run, st->clock);
  });

  CLI::App* check = cli.add_subcommand("check", "validate a mod folder and list all its problems");
  check->add_option("moddir", st->checkDir, "the mod's folder")->required();
  check->callback([st, exitCode] { *exitCode = checkModDir(st->checkDir, st->modDirs); });

  CLI::App* list = cli.add_subcommand("list", "list mods, scenarios, vehicles and emitters");
  list->callback([st, exitCode] { *exitCode = listMods(st->modDirs); });

  cli.require_subcommand(1);
}

}  // namespace tumble::app
