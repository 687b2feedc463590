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
// Per frame the app calls update() before World::step and afterStep() after
// it. Neither calls into Lua unless there is something to call: on_update,
// a due timer, on_contact with a contact event, a trigger enter/exit.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "particles/particle_system.h"
#include "input/input_system.h"
#include "physics/world.h"
#include "script/lua_vm.h"
#include "script/mods.h"
#include "script/presentation.h"
#include "script/script_error.h"
#include "script/tunables.h"
#include "vehicle/vehicle_def.h"

namespace tumble::physics {
class JointSystem;
class DeformableSystem;
}
namespace tumble::vehicle {
class VehicleSystem;
}

namespace tumble::script {

struct Expectation {
  std::string name;
  bool ok = false;
  bool isBool = false;
  double value = 0;  ///< the number, or 1/0 for a boolean
  std::optional<double> min, max;
};

/// game.message(text, seconds): shown on the HUD from time_s for duration_s.
struct GameMessage {
  std::string text;
  double time_s = 0;
  double duration_s = 3;
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
  /// The actions scripts read (input.value, ...); not owned, must outlive
  /// the host. Null: the host makes an empty one (no actions).
  input::InputSystem* input = nullptr;
  /// --set tune.NAME=VALUE (NAME without "tune."), applied over the file's.
  std::map<std::string, std::string> tuneSets;
  /// The mod's tunable overrides file to read at start (tunables.h); empty:
  /// none (headless runs: only --set, so a run depends on its command line).
  std::string tuneOverridesFile;
  /// Every known mod's folder by name, for "MOD:path" asset references.
  std::map<std::string, std::string> modDirs;
  /// Bounds of a model file (world.add_static_model's collision box); the
  /// app provides it. Unset: static models cannot have collision = "box".
  ModelBoundsFn modelBounds;
  /// --set physics.joint_solver: "lagrange" or "impulse" (checked by the
  /// app); empty: the scenario's joint_solver field, else lagrange.
  std::string jointSolver;
  /// Triangles of a model file (world.model_mass_properties); from the app.
  ModelTrianglesFn modelTriangles;
  /// The mesh shape of a model file at a scale (world.add_static_model's
  /// collision = "mesh"), shared between placements; from the app. Unset:
  /// static models cannot have mesh collision.
  ModelMeshShapeFn modelMeshShape;
};

/// Emitters attached to bodies carry the body as an opaque anchor number
/// (particles never sees physics); the app turns it back into a BodyId.
inline std::uint64_t emitterAnchorOf(physics::BodyId id) {
  return (std::uint64_t(id.generation) << 32) | id.index;  // generation >= 1: never kNoAnchor
}
inline physics::BodyId bodyOfEmitterAnchor(std::uint64_t anchor) {
  return physics::BodyId{std::uint32_t(anchor & 0xffffffffu), std::uint32_t(anchor >> 32)};
}

class ScenarioHost {
 public:
  static constexpr int kMaxConsecutiveErrors = 3;

  /// Loads and runs the scenario file's top level. Fails (Result error) if
  /// the file is missing, does not compile, errors at top level or does not
  /// return a table; the message names mod, file and line.
  static Result<std::unique_ptr<ScenarioHost>> load(const ModInfo& mod, const std::string& scenario,
                                                    physics::World& world, const ScenarioOptions& options);
  ~ScenarioHost();

  void start();
  /// Before World::step: due timers, then on_update, then (when the scenario
  /// made rag-dolls) the joints' constraint forces. time_s: the step's start.
  void update(double time_s, double dt_s, std::int64_t step);
  /// After World::step (time_s: the step's end): on_contact for each contact
  /// that began, then trigger volumes' on_enter / on_exit. No Lua call, and
  /// no work beyond two size checks, when the scenario has neither.
  void afterStep(double time_s, std::int64_t step);
  /// on_finish; then each --set tune.NAME the scenario never declared is
  /// recorded as an error (a misspelt name must not pass silently).
  void finish(double time_s, std::int64_t step);
  /// Runs the (saved) scenario file again and switches to its code, as the
  /// header says. time_s/step: the current simulated time, for ctx. On an
  /// error the old code stays, the error is recorded in errors() and
  /// returned. reloadCount() counts the reloads that took effect.
  Status reload(double time_s, std::int64_t step);
  int reloadCount() const { return m_reloadCount; }
  /// Timers still to fire (not cancelled, not finished) and live triggers.
  std::size_t activeTimerCount() const;
  int triggerCount() const { return m_liveTriggers; }
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
  /// Display colour (linear RGB 0..1) of a body made by the script.
  Eigen::Vector3f colorOf(physics::BodyId id) const;
  physics::World& world() { return m_world; }
  /// The input actions scripts read (options.input, or the host's own empty set).
  input::InputSystem& input() { return *m_input; }
  /// The scene's joints, created on first use (spawn_ragdoll); null before.
  physics::JointSystem* jointsIfAny() { return m_joints.get(); }
  physics::JointSystem& joints();
  /// The scene's particle emitters, created on first use (particles.spawn);
  /// null before, so a scene without emitters has no particle pools.
  particles::ParticleSystem* particlesIfAny() { return m_particles.get(); }
  particles::ParticleSystem& particles();
  /// The emitter definition "mod:name" (or "name": this mod, then base) with
  /// the fields of the table at overridesIdx (0: none) on top. The file is
  /// read once and cached. Error: file, field and what is expected.
  Result<particles::EmitterDef> emitterDef(const std::string& ref, int overridesIdx);
  /// The scene's vehicles, created on first use (vehicle.spawn); null before.
  vehicle::VehicleSystem* vehiclesIfAny() { return m_vehicles.get(); }
  const vehicle::VehicleSystem* vehiclesIfAny() const { return m_vehicles.get(); }
  vehicle::VehicleSystem& vehicles();
  /// Vehicle definitions loaded so far, by "mod:name" (bind_vehicle.cpp).
  std::map<std::string, vehicle::VehicleDef>& vehicleDefCache() { return m_vehicleDefs; }
  /// The scene's ropes and cloth (bind_deformable.cpp), created on first
  /// use; null before. The app steps them after World::step.
  physics::DeformableSystem* deformablesIfAny() { return m_deformables.get(); }
  const physics::DeformableSystem* deformablesIfAny() const { return m_deformables.get(); }
  physics::DeformableSystem& deformables();
  void setDeformableColor(int id, const Eigen::Vector3f& rgb) { m_deformableColors[id] = rgb; }
  Eigen::Vector3f deformableColor(int id) const;
  /// Lines scripts drew with draw_line since the last update() (bind_ode.cpp).
  struct ScriptLine {
    Vec3 a_m, b_m;
    Eigen::Vector3f color;
  };
  const std::vector<ScriptLine>& scriptLines() const { return m_scriptLines; }
  void addScriptLine(const ScriptLine& line);
  static constexpr std::size_t kMaxScriptLines = 65536;
  /// Forgets the cached emitter files, so the next spawn reads them again
  /// (hot reload). Emitters already running keep their definitions.
  void forgetEmitterDefinitions();
  /// particles.spawn remembers which file (and overrides) an emitter came
  /// from, so a saved emitter file can change it while it runs.
  void rememberEmitterSource(particles::EmitterId id, const std::string& ref, int overridesIdx);
  /// Hot reload of emitters/<name>.lua of this mod: the file is read again
  /// and every running emitter spawned from it takes the new definition
  /// (with its spawn overrides on top). A broken file changes nothing and
  /// the error names the file and field.
  Status reloadEmitterFile(const std::string& relPath);
  /// Largest joint anchor separation seen (m), 0 without joints: the run
  /// report's joint_error_max_m.
  double jointErrorMax_m() const;
  /// Switches the joint formulation (world.set_joint_solver), also while running.
  void setJointSolver(bool impulse);
  /// The fixed step (s): the app's, or what world.set_dt asked for (the app
  /// reads requestedDt_s() before every step; 0 = no request).
  double dt_s() const { return m_requestedDt_s > 0 ? m_requestedDt_s : m_dt_s; }
  void requestDt(double dt_s) { m_requestedDt_s = dt_s; }
  double requestedDt_s() const { return m_requestedDt_s; }
  /// "lagrange" or "impulse": the formulation joints() uses (the report's joint_solver).
  const char* jointSolverName() const { return m_impulseJoints ? "impulse" : "lagrange"; }
  const ModInfo& mod() const { return m_mod; }
  const std::string& scenarioFile() const { return m_file; }
  std::size_t luaMemoryBytes() const { return m_vm.memoryUsed(); }
  /// Lua calls made so far (0 per frame for a scenario without callbacks).
  std::uint64_t luaCallCount() const { return m_vm.callCount(); }

  static constexpr std::size_t kMaxMessages = 64;

  // Used by the bindings (bind_*.cpp).
  void setColor(physics::BodyId id, const Eigen::Vector3f& rgb);
  void addExpectation(Expectation e) { m_expectations.push_back(std::move(e)); }
  const ScenarioOptions& options() const { return m_options; }
  void setHudText(std::vector<std::string> lines) { m_hudText = std::move(lines); }
  void addMessage(std::string text, double duration_s);
  void setScore(double score) { m_score = score, m_hasScore = true; }
  void decide(Outcome outcome, std::string reason);
  /// Timers (bind_timer.cpp): the function is on top of the stack and is
  /// popped. Returns the timer's id (> 0).
  std::uint32_t addTimer(double delay_s, double period_s);
  bool cancelTimer(std::uint32_t id);
  bool timerActive(std::uint32_t id) const;
  /// Trigger boxes (bind_trigger.cpp): on_enter / on_exit functions at the
  /// given stack indices (0 = none). Returns the trigger's id (> 0).
  std::uint32_t addTrigger(const Vec3& center_m, const Vec3& halfSize_m, int onEnterIdx, int onExitIdx);
  bool removeTrigger(std::uint32_t id);
  /// Bodies inside a trigger after the last step (empty for a removed one).
  const std::vector<physics::BodyId>* triggerBodies(std::uint32_t id) const;
  /// Seed for random.new() without a seed: the run's seed mixed with a count.
  std::uint64_t nextRandomSeed();
  static ScenarioHost* from(lua_State* L);
  /// Models on bodies, static scenery models and the camera request
  /// (bind_model.cpp, bind_camera.cpp); the app draws from it.
  Presentation& presentation() { return m_presentation; }
  const Presentation& presentation() const { return m_presentation; }

 private:
  struct Timer {
    double due_s = 0, period_s = 0;  ///< period 0: fires once
    std::uint64_t seq = 0;           ///< creation order: ties fire in it
    std::uint32_t id = 0;
    int errors = 0;                  ///< consecutive failures
  };
  struct Trigger {
    std::uint32_t id = 0;  ///< 0: removed slot
    Vec3 center_m = Vec3::Zero(), half_m = Vec3::Zero();
    int onEnterRef = 0, onExitRef = 0;  ///< registry refs, 0 = none
    std::vector<physics::BodyId> inside, scratch;  ///< sorted by index
  };
  struct TriggerEvent {
    std::uint32_t trigger;
    physics::BodyId body;
    bool enter;
  };

  ScenarioHost(const ModInfo& mod, physics::World& world, const ScenarioOptions& options);
  void buildEnvironment();
  /// Loads and runs m_file's top level; leaves its table on the stack.
  bool runScenarioFile(ScriptError* err);
  /// Reads title, duration, terrain (first load only) and callbacks from the
  /// table on top of the stack and makes it the scenario; pops it.
  Status adoptScenarioTable(bool first);
  void dropTimersAndTriggers();
  bool callLifecycle(const char* name, int nargs, bool* paused, int* consecutive);
  /// Calls the function below nargs args; records an error under `what`.
  bool callRecorded(int nargs, const std::string& what);
  void pushCtx(double time_s, double dt_s, std::int64_t step);
  void runTimers(double time_s, double dt_s, std::int64_t step);
  void runContacts(double time_s, std::int64_t step);
  void runTriggers();

  LuaVm m_vm;
  ModInfo m_mod;
  physics::World& m_world;
  ScenarioOptions m_options;
  std::string m_file;
  std::string m_title, m_defaultTitle;
  double m_duration_s = 10;
  std::map<std::string, std::string> m_terrainRequest;
  int m_terrainBuildRef = 0;  ///< registry ref of terrain.build, 0 = none
  std::string m_integratorRequest;
  int m_envRef = 0, m_scenarioRef = 0, m_ctxRef = 0;
  int m_requireCacheRef = 0;  ///< require's loaded-modules table
  int m_reloadCount = 0;
  Tunables m_tunables;
  bool m_hasUpdate = false, m_updatePaused = false;
  bool m_hasContact = false, m_contactPaused = false;
  int m_updateErrors = 0, m_contactErrors = 0;
  double m_now_s = 0;
  std::vector<ScriptError> m_errors;
  std::vector<Expectation> m_expectations;
  std::vector<std::string> m_hudText;
  std::vector<GameMessage> m_messages;
  double m_score = 0;
  bool m_hasScore = false;
  Outcome m_outcome = Outcome::None;
  std::string m_outcomeReason;
  double m_outcomeTime_s = 0;
  std::vector<Eigen::Vector3f> m_colors;  ///< by body slot index
  // Timers: a min-heap on (due, seq); functions live in a Lua table keyed by
  // id (m_timerFnsRef), so cancelling removes the function and a popped
  // timer without one is skipped.
  std::vector<Timer> m_timers;
  int m_timerFnsRef = 0;
  std::uint32_t m_nextTimerId = 1;
  std::uint64_t m_timerSeq = 0;
  std::vector<Trigger> m_triggers;
  std::uint32_t m_nextTriggerId = 1;
  int m_liveTriggers = 0;
  std::vector<TriggerEvent> m_triggerEvents;        ///< reused each step
  std::vector<physics::ContactEvent> m_contactScratch;  ///< reused each step
  std::uint64_t m_randomCount = 0;
  std::unique_ptr<physics::JointSystem> m_joints;  ///< see joints()
  std::unique_ptr<particles::ParticleSystem> m_particles;  ///< see particles()
  int m_emitterTablesRef = 0;  ///< registry table: "mod:name" -> the file's returned table
  struct EmitterSource {
    particles::EmitterId id;
    std::string ref;       ///< as given to particles.spawn
    int overridesRef = 0;  ///< registry ref of a copy of the overrides table, 0 = none
  };
  std::vector<EmitterSource> m_emitterSources;  ///< see rememberEmitterSource
  std::unique_ptr<input::InputSystem> m_ownInput;  ///< when options.input is null
  input::InputSystem* m_input = nullptr;
  std::unique_ptr<vehicle::VehicleSystem> m_vehicles;  ///< see vehicles(); after m_joints: removed first
  std::map<std::string, vehicle::VehicleDef> m_vehicleDefs;
  Presentation m_presentation;
  double m_dt_s = 1.0 / 60.0;       ///< the step of the last update()
  double m_requestedDt_s = 0;       ///< world.set_dt, 0 = none
  bool m_impulseJoints = false;  ///< joints() uses formulation B (joint_solver / --set physics.joint_solver)
  std::unique_ptr<physics::DeformableSystem> m_deformables;  ///< see deformables()
  std::map<int, Eigen::Vector3f> m_deformableColors;
  std::vector<ScriptLine> m_scriptLines;
};

/// Registers the `world` table and Body type (bind_world.cpp, bind_body.cpp).
void openWorldBindings(lua_State* L, int envIndex);
void openBodyType(lua_State* L);
void pushBody(lua_State* L, physics::BodyId id);
void pushTrigger(lua_State* L, std::uint32_t id);
/// game, timer, random and trigger tables (bind_game.cpp, bind_timer.cpp,
/// bind_random.cpp, bind_trigger.cpp), each set as a field of the env.
void openGameBindings(lua_State* L, int envIndex);
void openTimerBindings(lua_State* L, int envIndex);
void openRandomBindings(lua_State* L, int envIndex);
void openTriggerBindings(lua_State* L, int envIndex);
/// spawn_ragdoll and joints_error (bind_ragdoll.cpp), set in the env.
void openRagdollBindings(lua_State* L, int envIndex);
/// The `particles` table and Emitter type (bind_emitter.cpp).
void openEmitterBindings(lua_State* L, int envIndex);
/// The `input` table: actions by name, contexts, injection (bind_input.cpp).
void openInputBindings(lua_State* L, int envIndex);
/// The tune table (bind_tune.cpp).
void openTuneBindings(lua_State* L, int envIndex);
/// vehicle (bind_vehicle.cpp) and save (bind_save.cpp) tables.
void openVehicleBindings(lua_State* L, int envIndex);
void openSaveBindings(lua_State* L, int envIndex);
/// body:set_model and world.add_static_model (bind_model.cpp; after
/// openWorldBindings and openBodyType), and the camera table (bind_camera.cpp).
void openModelBindings(lua_State* L, int envIndex);
void openCameraBindings(lua_State* L, int envIndex);
/// deformable table (bind_deformable.cpp); ode table and draw_line (bind_ode.cpp).
void openDeformableBindings(lua_State* L, int envIndex);
void openOdeBindings(lua_State* L, int envIndex);
/// world.spring and world.remove_spring (bind_spring.cpp); after openWorldBindings.
void openSpringBindings(lua_State* L, int envIndex);
/// world.joint, world.grab, ... and the Joint type (bind_joint.cpp); after openWorldBindings.
void openJointBindings(lua_State* L, int envIndex);

}  // namespace tumble::script
