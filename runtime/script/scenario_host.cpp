#include "script/scenario_host.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/log.h"
#include "core/random.h"
#include "script/internal/bindings.h"
#include "script/internal/lua_util.h"
#include "script/sandbox.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace tumble::script {

namespace {
const char kHostKey = 0;  // registry: ScenarioHost*
}  // namespace

ScenarioHost* ScenarioHost::from(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kHostKey);
  auto* host = static_cast<ScenarioHost*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return host;
}

void ScenarioHost::countBodiesCreated(std::size_t n, const char* fn) {
  if (m_bodyCountCall != m_vm.outerCallSerial()) {
    m_bodyCountCall = m_vm.outerCallSerial();
    m_bodiesThisCall = 0;
  }
  if (m_bodiesThisCall + n > kMaxBodiesPerCallback)
    throw LuaArgError(std::string(fn) + ": this callback already created " + std::to_string(m_bodiesThisCall) +
                      " bodies; one callback may create at most " + std::to_string(kMaxBodiesPerCallback) +
                      " (the per-callback body limit); create the rest in later steps");
  m_bodiesThisCall += n;
}

void ScenarioHost::chargeWork(lua_State* L, double units, const char* fn) {
  const double n = std::ceil(std::max(units, 0.0));
  if (n < 1.8e19 && m_vm.charge(L, std::uint64_t(n))) return;
  throw LuaArgError(std::string(fn) + ": " + std::to_string(std::uint64_t(std::min(n, 1.8e19))) +
                    " units of work (one per sample per pass) do not fit in what is left of the callback's budget of " +
                    std::to_string(m_vm.limits().instructionsPerCall) + " instructions; use a smaller map or fewer passes");
}

ScenarioHost::ScenarioHost(const ModInfo& mod, SceneSystems& scene, const ScenarioOptions& options)
    : m_vm(options.limits),
      m_mod(mod),
      m_scene(scene),
      m_options(options),
      m_timers(m_vm.state()),
      m_triggers(m_vm.state()),
      m_emitters(m_vm, m_mod, m_options.mods) {
  lua_State* L = m_vm.state();
  lua_pushlightuserdata(L, this);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kHostKey);
  buildEnvironment();
  if (!options.tuneOverridesFile.empty()) {
    if (Status st = m_tunables.loadOverrides(options.tuneOverridesFile); !st) {
      // A corrupt settings file must not stop the game: defaults, and say so.
      log::warn(st.error());
      m_messages.push_back({st.error(), 0, 10, MessageKind::Warning});
    }
  }
  for (const auto& [name, text] : options.tuneSets) {
    if (Status st = m_tunables.setText(name, text, "--set"); !st) log::error(st.error());
  }
}

ScenarioHost::~ScenarioHost() = default;

void ScenarioHost::buildEnvironment() {
  lua_State* L = m_vm.state();
  pushSandboxEnvironment(L, SandboxPaths{m_mod.dir, m_options.scriptsDir}, m_options.seed, &m_requireCacheRef);
  const int env = lua_gettop(L);
  openGlobalBindings(L, env);
  openBodyType(L);
  openWorldBindings(L, env);
  openGameBindings(L, env);
  openTimerBindings(L, env);
  openRandomBindings(L, env);
  openTriggerBindings(L, env);
  openRagdollBindings(L, env);
  openEmitterBindings(L, env);
  openInputBindings(L, env);
  openTuneBindings(L, env);
  openVehicleBindings(L, env);
  openSaveBindings(L, env);
  openModelBindings(L, env);
  openCameraBindings(L, env);
  openSoundBindings(L, env);
  openEnvironmentBindings(L, env);
  openDeformableBindings(L, env);
  openOdeBindings(L, env);
  openSpringBindings(L, env);
  openWorldSnapshotBindings(L, env);
  openJointBindings(L, env);
  openHudBindings(L, env);
  guardEnvironment(L, env);
  m_envRef = luaL_ref(L, LUA_REGISTRYINDEX);  // pops env

  lua_newtable(L);  // ctx, with ctx.state kept across reloads
  lua_newtable(L);
  rawSetField(L, -2, "state");
  m_ctxRef = luaL_ref(L, LUA_REGISTRYINDEX);
}

void ScenarioHost::recordError(ScriptError error) {
  log::error(error.summary());
  m_errors.push_back(std::move(error));
}

void ScenarioHost::reportTuneProblems() {
  for (std::string& p : m_tunables.takeProblems()) {
    ScriptError e;
    e.mod = m_mod.name;
    e.file = m_file;
    e.message = std::move(p);
    recordError(std::move(e));
  }
}

void ScenarioHost::pushCtx(double time_s, double dt_s, std::int64_t step) {
  lua_State* L = m_vm.state();
  m_now_s = time_s;
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_ctxRef);
  lua_pushnumber(L, time_s);
  rawSetField(L, -2, "time");
  lua_pushnumber(L, dt_s);
  rawSetField(L, -2, "dt");
  lua_pushinteger(L, step);
  rawSetField(L, -2, "step");
  lua_pushinteger(L, lua_Integer(m_options.seed));
  rawSetField(L, -2, "seed");
}

bool ScenarioHost::callTerrainBuild(const std::function<void(lua_State*)>& pushArg, ScriptError* err) {
  lua_State* L = m_vm.state();
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_terrainBuildRef);
  pushArg(L);
  return m_vm.call(1, 0, m_mod.name, m_file, "terrain.build", err);
}

bool ScenarioHost::callRecorded(int nargs, const std::string& what) {
  ScriptError err;
  if (m_vm.call(nargs, 0, m_mod.name, m_file, what, &err)) return true;
  m_errors.push_back(err);
  log::error(err.summary() + "\n" + err.traceback);
  return false;
}

bool ScenarioHost::callLifecycle(const char* name, int nargs, bool* paused, int* consecutive) {
  // Stack: ctx [, args...]
  lua_State* L = m_vm.state();
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_scenarioRef);
  rawGetField(L, -1, name);
  lua_remove(L, -2);
  if (!lua_isfunction(L, -1)) {
    lua_pop(L, 1 + nargs);
    return true;
  }
  lua_insert(L, -1 - nargs);
  if (callRecorded(nargs, name)) {
    if (consecutive) *consecutive = 0;
    return true;
  }
  if (consecutive && ++*consecutive >= kMaxConsecutiveErrors && paused) {
    *paused = true;
    ScriptError note = m_errors.back();
    note.limit = false;
    note.message = std::string(name) + " failed " + std::to_string(kMaxConsecutiveErrors) +
                   " times in a row and was paused (last error: " + note.message + ")";
    m_errors.push_back(note);
    log::warn(note.summary());
  }
  return false;
}

void ScenarioHost::start() {
  pushCtx(0, 0, 0);
  callLifecycle("on_start", 1, nullptr, nullptr);
  m_firstTimerAfterStart = m_timers.nextId();
  m_firstTriggerAfterStart = m_triggers.nextId();
  // Timers on_start made with delay 0 fire now, before the first step.
  if (m_timers.anyDue(0)) runTimers(0, 0, 0);
}

void ScenarioHost::update(double time_s, double dt_s, std::int64_t step) {
  m_now_s = time_s;
  m_dt_s = dt_s;
  m_presentation.clearScriptLines();
  if (!hasUpdate()) return;
  pushCtx(time_s, dt_s, step);
  lua_pushnumber(m_vm.state(), dt_s);
  callLifecycle("on_update", 2, &m_updatePaused, &m_updateErrors);
}

void ScenarioHost::afterStep(double time_s, std::int64_t step) {
  m_now_s = time_s;
  if (hasContact() && !world().contactEvents().empty()) runContacts(time_s, step);
  if (m_triggers.liveCount() > 0) runTriggers();
  if (m_timers.anyDue(time_s)) runTimers(time_s, m_dt_s, step);
}

void ScenarioHost::finish(double time_s, std::int64_t step) {
  pushCtx(time_s, 0, step);
  callLifecycle("on_finish", 1, nullptr, nullptr);
  // A --set tune.X that nothing declared is most likely a typo: say so
  // rather than let the run silently use the default.
  for (const std::string& name : m_tunables.undeclared("--set")) {
    std::string known;
    for (const Tunable& t : m_tunables.items()) known += (known.empty() ? "" : ", ") + t.name;
    ScriptError e;
    e.mod = m_mod.name;
    e.file = m_file;
    e.message = "--set tune." + name + ": the scenario declared no tunable \"" + name + "\" (declared: " +
                (known.empty() ? std::string("none") : known) + ")";
    recordError(std::move(e));
  }
}

// ---- contacts, triggers, timers ---------------------------------------------------

void ScenarioHost::runContacts(double time_s, std::int64_t step) {
  // Copy first: a callback may remove bodies or create new ones.
  m_contactScratch.assign(world().contactEvents().begin(), world().contactEvents().end());
  lua_State* L = m_vm.state();
  for (const physics::ContactEvent& e : m_contactScratch) {
    if (!hasContact()) break;
    if (!world().isValid(e.a) || !world().isValid(e.b)) continue;  // removed by an earlier callback
    pushCtx(time_s, 0, step);
    pushBody(L, e.a);
    pushBody(L, e.b);
    lua_pushnumber(L, e.impulse_Ns);
    pushVec3(L, e.point_m);
    pushVec3(L, e.normal);
    callLifecycle("on_contact", 6, &m_contactPaused, &m_contactErrors);
  }
}

void ScenarioHost::runTriggers() {
  lua_State* L = m_vm.state();
  m_triggers.update(world(), [&](physics::BodyId body, std::uint32_t trigger, bool enter) {
    pushBody(L, body);
    pushTrigger(L, trigger);
    callRecorded(2, enter ? "trigger on_enter" : "trigger on_exit");
  });
}

void ScenarioHost::runTimers(double time_s, double dt_s, std::int64_t step) {
  lua_State* L = m_vm.state();
  ScriptError lastError;
  auto fire = [&](bool periodic, bool* failed) {
    pushCtx(time_s, dt_s, step);
    ScriptError err;
    if (!m_vm.call(1, 1, m_mod.name, m_file, periodic ? "timer.every" : "timer.after", &err)) {
      *failed = true;
      lastError = err;
      m_errors.push_back(err);
      log::error(err.summary() + "\n" + err.traceback);
      return false;
    }
    const bool stop = lua_isboolean(L, -1) && !lua_toboolean(L, -1);  // returning false stops it
    lua_pop(L, 1);
    return !stop;
  };
  auto gaveUp = [&] {
    ScriptError note = lastError;
    note.limit = false;
    note.message = "timer.every callback failed " + std::to_string(TimerQueue::kMaxConsecutiveErrors) +
                   " times in a row and was cancelled (last error: " + lastError.message + ")";
    m_errors.push_back(note);
    log::warn(note.summary());
  };
  m_timers.fireDue(time_s, fire, gaveUp);
}

// ---- game state -------------------------------------------------------------------

const char* messageKindName(MessageKind kind) {
  switch (kind) {
    case MessageKind::Info: return "info";
    case MessageKind::Warning: return "warning";
    case MessageKind::Error: return "error";
  }
  return "info";
}

void ScenarioHost::addMessage(std::string text, double duration_s, MessageKind kind) {
  if (m_messages.size() >= kMaxMessages) m_messages.erase(m_messages.begin());
  m_messages.push_back({std::move(text), m_now_s, duration_s, kind});
}

std::vector<std::string> ScenarioHost::activeMessages(double time_s) const {
  std::vector<std::string> lines;
  for (const GameMessage& m : m_messages)
    if (time_s >= m.time_s - 1e-9 && time_s < m.time_s + m.duration_s) lines.push_back(m.text);
  return lines;
}

void ScenarioHost::decide(Outcome outcome, std::string reason) {
  if (m_outcome != Outcome::None) return;
  m_outcome = outcome;
  m_outcomeReason = std::move(reason);
  m_outcomeTime_s = m_now_s;
}

std::uint64_t ScenarioHost::nextRandomSeed() {
  // splitmix64 of (seed, count): distinct, reproducible streams.
  std::uint64_t state = m_options.seed + 0x9E3779B97F4A7C15ull * m_randomCount++;
  return splitmix64(state);
}

}  // namespace tumble::script
