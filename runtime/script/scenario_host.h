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
// Per frame the app calls update() before World::step and afterStep() after
// it. Neither calls into Lua unless there is something to call: on_update,
// a due timer, on_contact with a contact event, a trigger enter/exit.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "physics/world.h"
#include "script/lua_vm.h"
#include "script/mods.h"
#include "script/script_error.h"

namespace tumble::physics {
class JointSystem;
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
  /// --set physics.joint_solver: "lagrange" or "impulse" (checked by the
  /// app); empty: the scenario's joint_solver field, else lagrange.
  std::string jointSolver;
};

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
  void finish(double time_s, std::int64_t step);

  bool hasUpdate() const { return m_hasUpdate && !m_updatePaused; }
  bool hasContact() const { return m_hasContact && !m_contactPaused; }
  const std::string& title() const { return m_title; }
  /// Seconds the scenario asks to run for when --seconds/--steps are absent.
  double duration_s() const { return m_duration_s; }
  /// The scenario's `terrain = {...}` field, flattened to "terrain.KEY" =
  /// value (as --set would give them); `heightmap` is made an absolute path
  /// inside the mod. Empty when the scenario declares no terrain.
  const std::map<std::string, std::string>& terrainRequest() const { return m_terrainRequest; }
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
  /// The scene's joints, created on first use (spawn_ragdoll); null before.
  physics::JointSystem* jointsIfAny() { return m_joints.get(); }
  physics::JointSystem& joints();
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
  std::string m_title;
  double m_duration_s = 10;
  std::map<std::string, std::string> m_terrainRequest;
  int m_envRef = 0, m_scenarioRef = 0, m_ctxRef = 0;
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
  double m_dt_s = 1.0 / 60.0;       ///< the step of the last update()
  double m_requestedDt_s = 0;       ///< world.set_dt, 0 = none
  bool m_impulseJoints = false;  ///< joints() uses formulation B (joint_solver / --set physics.joint_solver)
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
/// world.joint, world.grab, ... and the Joint type (bind_joint.cpp); after openWorldBindings.
void openJointBindings(lua_State* L, int envIndex);

}  // namespace tumble::script
