#pragma once
// Runs one scenario: loads <mod>/scenarios/<name>.lua into the mod's sandboxed
// environment and calls its lifecycle (ARCHITECTURE.md):
//   on_start(ctx), on_update(ctx, dt) at the fixed rate, on_finish(ctx),
//   on_contact(ctx, a, b, impulse, point, normal) after a step for each
//   contact that began in it.
// Each host owns its Lua state (LuaVm), so every mod has its own tables:
// nothing one scenario does to `world`, `string` or _G reaches another.
// Errors never escape: each becomes a ScriptError (mod, file, line,
// traceback) and the game goes on. A callback that fails kMaxConsecutiveErrors
// times in a row is paused, so one broken line does not flood the log.
//
// Hot reload (reload(), driven by HotReload in hot_reload.h while playing):
// the scenario file runs again in the same Lua state and environment and its
// new table replaces the old one. Kept: the world and its bodies, globals of
// the mod's environment, expectations, score, tunables' values, and
// `ctx.state`, a table for the scenario's own data; then the new code's
// on_reload(ctx, state) is called with state = ctx.state (on_start is not
// run again). A scenario with on_reload owns its timers and triggers: those
// the old code made are dropped before on_reload runs (they would call old
// functions), so on_reload makes them again. Without on_reload they keep
// running. A file that does not compile, fails at top level or returns no
// table changes nothing: the old code keeps running and the error (file,
// line) is recorded. require'd files of the mod are loaded afresh.
//
// The host owns the scenario's Lua state and what lives in it (timers,
// triggers, emitter files, tunables, game state), never a simulation
// system: those are the app's, reached through SceneSystems. Per fixed step
// the app (app/fixed_step.cpp) calls update() before the physics and
// afterStep() after it. Neither calls into Lua unless there is something to
// call: on_update, a due timer, on_contact with a contact event, a trigger
// enter/exit.
//
// Files: scenario_host.cpp (lifecycle, ctx, errors, game state),
// scenario_load.cpp (load and hot reload), sandbox.cpp (the environment),
// globals.cpp (print, expect, param, hud_text), timers.cpp, triggers.cpp,
// emitter_cache.cpp, and bind_<topic>.cpp for each Lua module and type.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <utility>

#include "core/result.h"
#include "physics/joints/joint_system.h"
#include "physics/world.h"
#include "script/emitter_cache.h"
#include "script/lua_vm.h"
#include "script/mods.h"
#include "script/presentation.h"
#include "script/scenario_params.h"
#include "script/scene_systems.h"
#include "script/script_error.h"
#include "script/timers.h"
#include "script/triggers.h"
#include "script/tunables.h"
#include "vehicle/vehicle_def.h"

namespace tumble::script {

struct Expectation {
  std::string name;
  bool ok = false;
  bool isBool = false;
  double value = 0;  ///< the number, or 1/0 for a boolean
  std::optional<double> min, max;
};

/// How a message is meant: the HUD colours it (info white, warning yellow,
/// error red).
enum class MessageKind { Info, Warning, Error };
/// "info", "warning", "error".
const char* messageKindName(MessageKind kind);

/// game.message(text, seconds, kind): shown on the HUD from time_s for duration_s.
struct GameMessage {
  std::string text;
  double time_s = 0;
  double duration_s = 3;
  MessageKind kind = MessageKind::Info;
};

/// game.win / game.lose. The first call decides; later ones are ignored.
enum class Outcome { None, Won, Lost };

struct ScenarioOptions {
  std::map<std::string, std::string> params;  ///< --set KEY=VALUE for the script (param())
  std::uint64_t seed = 1;
  std::string scriptsDir;  ///< the runtime's Lua library (require "tumble.x")
  VmLimits limits;
  /// Other loadable mods, for references like "base:dust" (particles.spawn,
  /// vehicle.spawn). The scenario's own mod is always searched first.
  std::vector<ModInfo> mods;
  /// --set tune.NAME=VALUE (NAME without "tune."), applied over the file's.
  std::map<std::string, std::string> tuneSets;
  /// The mod's tunable overrides file to read at start (tunables.h); empty:
  /// none (headless runs: only --set, so a run depends on its command line).
  std::string tuneOverridesFile;
  /// Every known mod's folder by name, for "MOD:path" asset references.
  std::map<std::string, std::string> modDirs;
  /// Where save.read / save.write keep their files (one folder per mod);
  /// empty: the player's data folder (bind_save.cpp). `run` gives a
  /// throw-away folder so headless runs never touch the player's saves.
  std::string saveDir;
  /// `run --freeze` (a test switch): systems the script steps itself
  /// (ode.system) do not advance, like the scene's physics.
  bool freezeSimulation = false;
};

class ScenarioHost {
 public:
  static constexpr int kMaxConsecutiveErrors = 3;

  /// Loads and runs the scenario file's top level (scenario_load.cpp).
  /// Fails (Result error) if the file is missing, does not compile, errors
  /// at top level or does not return a table; the message names mod, file
  /// and line. `scene` must outlive the host.
  static Result<std::unique_ptr<ScenarioHost>> load(const ModInfo& mod, const std::string& scenario,
                                                    SceneSystems& scene, const ScenarioOptions& options);
  ~ScenarioHost();

  /// on_start, then the timers it made that are due at once (delay 0).
  void start();
  /// Before the physics of a step (time_s: the step's start): on_update.
  /// No Lua call when the scenario has none.
  void update(double time_s, double dt_s, std::int64_t step);
  /// After the physics of a step (time_s: the step's end): on_contact for
  /// each contact that began, trigger volumes' on_enter / on_exit, then the
  /// timers due by time_s. No Lua call, and no work beyond a few size
  /// checks, when the scenario has none of them.
  void afterStep(double time_s, std::int64_t step);
  /// on_finish; then each --set tune.NAME the scenario never declared is
  /// recorded as an error (a misspelt name must not pass silently).
  void finish(double time_s, std::int64_t step);
  /// Runs the (saved) scenario file again and switches to its code, as the
  /// header says (scenario_load.cpp). time_s/step: the current simulated
  /// time, for ctx. On an error the old code stays, the error is recorded
  /// in errors() and returned. reloadCount() counts the reloads that took effect.
  Status reload(double time_s, std::int64_t step);
  int reloadCount() const { return m_reloadCount; }
  /// The Lua part of a snapshot of the running scene (scenario_state.cpp:
  /// ctx.state, timers' schedule, random generators, game state,
  /// expectations). Refused, with where it was made, for what a snapshot
  /// cannot store: ctx.state that is not plain data, and without on_reload a
  /// timer made after on_start or a trigger volume.
  Result<std::string> saveState();
  /// Puts it back after on_start ran again; with on_reload, timers and
  /// triggers are dropped and on_reload(ctx, state) re-makes them.
  Status restoreState(const std::string& bytes, double time_s, std::int64_t step);
  bool hasOnReload();
  /// A path inside the mod's folder made relative to it ("scenarios/x.lua:12").
  std::string modRelative(const std::string& where) const;
  /// ode.system was called: returns the system's number (1, 2, ... in the
  /// order they were made), by which a snapshot finds it again after
  /// on_start made the systems anew (bind_ode.cpp, saveOdeSystems).
  int noteOdeSystem() { return ++m_odeSystemsMade; }
  /// Records an error that did not come from a Lua call (a reload hook, an
  /// overrides file); it shows on the HUD and in the report like the others.
  void recordError(ScriptError error);
  /// Tunables the scenario declared (tune.*), their live values.
  Tunables& tunables() { return m_tunables; }
  const Tunables& tunables() const { return m_tunables; }
  /// Turns problems the tunables found (a bad --set value) into errors.
  void reportTuneProblems();

  bool hasUpdate() const { return m_hasUpdate && !m_updatePaused; }
  bool hasContact() const { return m_hasContact && !m_contactPaused; }
  const std::string& title() const { return m_title; }
  /// Seconds the scenario asks to run for when --seconds/--steps are absent.
  double duration_s() const { return m_duration_s; }
  /// The scenario's `terrain = {...}` field, flattened to "terrain.KEY" =
  /// value (as --set would give them); `heightmap` is made an absolute path
  /// inside the mod. Empty when the scenario declares no terrain.
  const std::map<std::string, std::string>& terrainRequest() const { return m_terrainRequest; }
  /// True if the scenario's terrain table has a `build = function(map)`
  /// (script/terrain_build.h runs it; terrainRequest() then also holds
  /// "terrain.build" = "lua").
  bool hasTerrainBuild() const { return m_terrainBuildRef != 0; }
  /// Calls terrain.build with the one argument `pushArg` pushes, under the
  /// instruction and memory budgets; false and `err` filled on failure.
  bool callTerrainBuild(const std::function<void(lua_State*)>& pushArg, ScriptError* err);
  lua_State* luaState() { return m_vm.state(); }
  /// The scenario's `integrator = "rk4"` field (physics/integrate.h names),
  /// empty when absent; the app checks the name (--integrator wins).
  const std::string& integratorRequest() const { return m_integratorRequest; }
  /// The scenario's `joint_solver` field, if it has one (the app decides:
  /// --set physics.joint_solver wins).
  std::optional<physics::JointSolverKind> jointSolverRequest() const { return m_jointSolverRequest; }
  /// The scenario's `params = {...}` field (scenario_params.h): the
  /// parameters it reads, or nothing when it does not declare them.
  const ParamDecls& declaredParams() const { return m_params; }
  const std::vector<ScriptError>& errors() const { return m_errors; }
  const std::vector<Expectation>& expectations() const { return m_expectations; }
  /// Lines scripts asked to show on the HUD (hud_text), latest frame.
  const std::vector<std::string>& hudText() const { return m_hudText; }
  /// game.message lines, oldest first (at most kMaxMessages kept).
  const std::vector<GameMessage>& messages() const { return m_messages; }
  /// Messages still to be shown at time_s (for the HUD).
  std::vector<std::string> activeMessages(double time_s) const;
  /// game.score; hasScore() is false until a script sets one.
  double score() const { return m_score; }
  bool hasScore() const { return m_hasScore; }
  /// game.win / game.lose: the outcome, its reason and when it was decided.
  Outcome outcome() const { return m_outcome; }
  const std::string& outcomeReason() const { return m_outcomeReason; }
  double outcomeTime_s() const { return m_outcomeTime_s; }
  /// Simulated time of the callback being run (timers count from it).
  double now_s() const { return m_now_s; }

  /// The scene's systems, owned by the app (scene_systems.h).
  SceneSystems& scene() { return m_scene; }
  physics::World& world() { return m_scene.world(); }
  input::InputSystem& input() { return m_scene.input(); }
  /// Timers, trigger boxes and emitter files of this scenario.
  TimerQueue& timers() { return m_timers; }
  TriggerSet& triggers() { return m_triggers; }
  const TriggerSet& triggers() const { return m_triggers; }
  EmitterCache& emitters() { return m_emitters; }
  /// Vehicle definitions loaded so far, by "mod:name" (bind_vehicle.cpp).
  std::map<std::string, vehicle::VehicleDef>& vehicleDefCache() { return m_vehicleDefs; }
  const ModInfo& mod() const { return m_mod; }
  const std::string& scenarioFile() const { return m_file; }
  std::size_t luaMemoryBytes() const { return m_vm.memoryUsed(); }
  /// Lua calls made so far (0 per frame for a scenario without callbacks).
  std::uint64_t luaCallCount() const { return m_vm.callCount(); }

  static constexpr std::size_t kMaxMessages = 64;
  /// Bodies one callback (on_start, on_update, a timer, ...) may create:
  /// creating bodies is work done in C++, outside the instruction budget, so
  /// it has a budget of its own. 10 000 is 2.5 times the largest scene the
  /// project builds in one callback (a forest of 4000 models).
  static constexpr std::size_t kMaxBodiesPerCallback = 10000;
  /// Called by every binding that creates bodies, before it does; throws
  /// (naming `fn` and the limit) past kMaxBodiesPerCallback.
  void countBodiesCreated(std::size_t n, const char* fn);
  /// Counts work a binding does in C++ (one unit per sample per pass of a
  /// terrain filter, ...) against the running callback's instruction
  /// budget; throws, naming `fn` and the budget, if it does not fit.
  void chargeWork(lua_State* L, double units, const char* fn);

  // Used by the bindings (bind_*.cpp, globals.cpp).
  void addExpectation(Expectation e) { m_expectations.push_back(std::move(e)); }
  /// `run --inject-nan` (a test switch) in a scenario without bodies or
  /// ropes: the next OdeSystem:step leaves NaN in its state's first entry.
  void requestNanInjection() { m_nanInjectionPending = true; }
  bool takeNanInjection() { return std::exchange(m_nanInjectionPending, false); }
  const ScenarioOptions& options() const { return m_options; }
  void setHudText(std::vector<std::string> lines) { m_hudText = std::move(lines); }
  void addMessage(std::string text, double duration_s, MessageKind kind = MessageKind::Info);
  void setScore(double score) { m_score = score, m_hasScore = true; }
  void decide(Outcome outcome, std::string reason);
  /// Seed for random.new() without a seed: the run's seed mixed with a count.
  std::uint64_t nextRandomSeed();
  static ScenarioHost* from(lua_State* L);
  /// What the scenario asked to show: models, the camera, colours, lines
  /// (bind_model.cpp, bind_camera.cpp, ...); the app draws from it.
  Presentation& presentation() { return m_presentation; }
  const Presentation& presentation() const { return m_presentation; }

 private:
  ScenarioHost(const ModInfo& mod, SceneSystems& scene, const ScenarioOptions& options);
  void buildEnvironment();
  /// Loads and runs m_file's top level; leaves its table on the stack.
  bool runScenarioFile(ScriptError* err);
  /// Reads title, duration, terrain (first load only) and callbacks from the
  /// table on top of the stack and makes it the scenario; pops it.
  Status adoptScenarioTable(bool first);
  bool callLifecycle(const char* name, int nargs, bool* paused, int* consecutive);
  /// Calls the function below nargs args; records an error under `what`.
  bool callRecorded(int nargs, const std::string& what);
  void pushCtx(double time_s, double dt_s, std::int64_t step);
  void runTimers(double time_s, double dt_s, std::int64_t step);
  void runContacts(double time_s, std::int64_t step);
  void runTriggers();

  LuaVm m_vm;
  std::uint64_t m_bodyCountCall = 0;  ///< outermost call the count below belongs to
  std::size_t m_bodiesThisCall = 0;
  ModInfo m_mod;
  SceneSystems& m_scene;
  ScenarioOptions m_options;
  std::string m_file;
  std::string m_title, m_defaultTitle;
  double m_duration_s = 10;
  std::map<std::string, std::string> m_terrainRequest;
  int m_terrainBuildRef = 0;  ///< registry ref of terrain.build, 0 = none
  std::string m_integratorRequest;
  std::optional<physics::JointSolverKind> m_jointSolverRequest;
  ParamDecls m_params;
  int m_envRef = 0, m_scenarioRef = 0, m_ctxRef = 0;
  int m_requireCacheRef = 0;  ///< require's loaded-modules table
  int m_reloadCount = 0;
  Tunables m_tunables;
  bool m_hasUpdate = false, m_updatePaused = false;
  bool m_hasContact = false, m_contactPaused = false;
  int m_updateErrors = 0, m_contactErrors = 0;
  double m_now_s = 0;
  double m_dt_s = 1.0 / 60.0;  ///< the step of the last update(), for timers' ctx.dt
  std::vector<ScriptError> m_errors;
  std::vector<Expectation> m_expectations;
  bool m_nanInjectionPending = false;  ///< see requestNanInjection
  std::vector<std::string> m_hudText;
  std::vector<GameMessage> m_messages;
  double m_score = 0;
  bool m_hasScore = false;
  Outcome m_outcome = Outcome::None;
  std::string m_outcomeReason;
  double m_outcomeTime_s = 0;
  TimerQueue m_timers;
  TriggerSet m_triggers;
  EmitterCache m_emitters;
  std::vector<physics::ContactEvent> m_contactScratch;  ///< reused each step
  std::uint64_t m_randomCount = 0;
  int m_odeSystemsMade = 0;  ///< see noteOdeSystem
  std::uint32_t m_firstTimerAfterStart = 1;  ///< first timer id made after on_start (saveState)
  std::uint32_t m_firstTriggerAfterStart = 1;  ///< first trigger id made after on_start (saveState)
  std::map<std::string, vehicle::VehicleDef> m_vehicleDefs;
  Presentation m_presentation;
};

}  // namespace tumble::script
