// Loading a scenario file and hot reload (scenario_host.h says what a
// reload keeps).
#include <cstring>
#include <filesystem>

#include "core/log.h"
#include "script/scenario_host.h"
#include "script/internal/raw_access.h"
#include "script/lua_vm.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace fs = std::filesystem;

namespace tumble::script {

/// @class Scenario
/// What a scenario file returns. Every field is optional.
/// @field title string shown in the window title and the HUD
/// @field duration number seconds `tumble run` simulates without --seconds/--steps (default 10)
/// @field joint_solver string "impulse" (default: impulses solved together with the contacts) or "lagrange" (Lagrange multipliers solved with the joints' sparse factor each substep: tighter on long chains); --set physics.joint_solver=... overrides it
/// @field integrator string how the world advances bodies between contact solves: "symplectic_euler" (default), "euler", "heun", "rk4", "verlet", "implicit_euler", "implicit_midpoint", "sdirk2"; --integrator overrides it
/// @field params table<string, ParamDeclaration>? the parameters the scenario reads with param(); when present, --set NAME=VALUE must name one of them with a value of its default's type (checked before the run starts), param(NAME) without a default returns the declared one, and the run report lists each with the value used
/// @field on_start fun(ctx: Ctx) called once before the first step
/// @field on_update fun(ctx: Ctx, dt: number) called before every fixed step (dt in s)
/// @field on_contact fun(ctx: Ctx, a: Body, b: Body, impulse: number, point: Vec3, normal: Vec3) called after a step for each pair of bodies that began touching in it; impulse in N s, normal from a to b
/// @field on_finish fun(ctx: Ctx) called once after the last step: the place for expect()
/// @field on_reload fun(ctx: Ctx, state: table) called after a hot reload, in the new code, with state = ctx.state; re-make timers and triggers here (the old ones were dropped) and refresh locals from state; also called after `run --load-state` restored a snapshot (docs/snapshots.md)

/// @class Ctx
/// The context passed to every callback (the same table each time).
/// @field time number simulated time, s (for on_update: the step's start; for on_contact: its end)
/// @field dt number the fixed step, s (0 in on_start and on_finish)
/// @field step integer index of the step
/// @field seed integer the run's seed (--seed)
/// @field state table yours: kept for the whole run, across hot reloads (on_reload gets it) and in snapshots (plain data: numbers, strings, booleans, bodies, tables of them; docs/snapshots.md); keep what reloaded code needs here

Result<std::unique_ptr<ScenarioHost>> ScenarioHost::load(const ModInfo& mod, const std::string& scenario,
                                                          SceneSystems& scene, const ScenarioOptions& options) {
  fs::path file = fs::path(mod.dir) / "scenarios" / (scenario + ".lua");
  std::string where = "mod " + mod.name + ": scenarios/" + scenario + ".lua";
  if (!fs::exists(file)) {
    std::string known;
    for (auto& s : ModRegistry::listLua(mod, "scenarios")) known += (known.empty() ? "" : ", ") + s;
    return makeError(where + ": no such scenario (this mod has: " + (known.empty() ? "none" : known) + ")");
  }
  std::unique_ptr<ScenarioHost> host(new ScenarioHost(mod, scene, options));
  host->m_file = "scenarios/" + scenario + ".lua";
  host->m_defaultTitle = mod.name + ":" + scenario;
  ScriptError err;
  if (!host->runScenarioFile(&err)) return makeError(err.summary() + (err.traceback.empty() ? "" : "\n" + err.traceback));
  if (Status st = host->adoptScenarioTable(true); !st) return makeError(st.error());
  return host;
}

bool ScenarioHost::runScenarioFile(ScriptError* err) {
  lua_State* L = m_vm.state();
  const std::string path = (fs::path(m_mod.dir) / m_file).string();
  if (LuaVm::loadFile(L, std::string(path.c_str())) != LUA_OK) {
    *err = LuaVm::parseError(m_mod.name, lua_tostring(L, -1), "");
    if (err->file.empty()) err->file = m_file;
    lua_pop(L, 1);
    return false;
  }
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_envRef);
  lua_setupvalue(L, -2, 1);
  if (!m_vm.call(0, 1, m_mod.name, m_file, "top level", err)) return false;
  if (!lua_istable(L, -1)) {
    lua_pop(L, 1);
    err->mod = m_mod.name;
    err->file = m_file;
    err->line = 0;
    err->traceback.clear();
    err->message = "must return a table {on_start = function(ctx) ... end, ...}";
    return false;
  }
  return true;
}

Status ScenarioHost::adoptScenarioTable(bool first) {
  // The table is on top of the stack; it is popped either way.
  lua_State* L = m_vm.state();
  const std::string where = "mod " + m_mod.name + ": " + m_file;
  const std::string title = m_title;
  const double duration = m_duration_s;
  auto fail = [&](int pop, std::string message) -> Status {
    lua_pop(L, pop);
    m_title = title;
    m_duration_s = duration;
    return makeError(std::move(message));
  };
  rawGetField(L, -1, "title");
  m_title = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : m_defaultTitle;
  lua_pop(L, 1);
  rawGetField(L, -1, "duration");
  if (lua_type(L, -1) == LUA_TNUMBER && lua_tonumber(L, -1) > 0) m_duration_s = lua_tonumber(L, -1);
  else if (!lua_isnil(L, -1)) {
    return fail(2, where + ": field 'duration' must be a number of seconds > 0");
  }
  lua_pop(L, 1);
  // joint_solver = "lagrange" | "impulse"; --set physics.joint_solver wins.
  rawGetField(L, -1, "joint_solver");
  if (!lua_isnil(L, -1)) {
    physics::JointSolverKind kind;
    if (lua_type(L, -1) != LUA_TSTRING || !physics::parseJointSolver(lua_tostring(L, -1), &kind))
      return fail(2, where + ": field 'joint_solver' must be \"lagrange\" or \"impulse\"");
    m_jointSolverRequest = kind;
  }
  lua_pop(L, 1);
  auto params = readParamDecls(L, -1, where);
  if (!params) return fail(1, params.error());
  m_params = std::move(params.value());
  rawGetField(L, -1, "integrator");
  if (lua_type(L, -1) == LUA_TSTRING) m_integratorRequest = lua_tostring(L, -1);
  else if (!lua_isnil(L, -1))
    return fail(2, where + ": field 'integrator' must be a string such as \"rk4\" (see tumble run --help)");
  lua_pop(L, 1);
  // terrain = {generate = 7, size = 1025, ...} or {heightmap = "assets/map.png"}
  rawGetField(L, -1, "terrain");
  if (!first) {
    // A terrain is built once, before on_start; a reload keeps it.
  } else if (lua_istable(L, -1)) {
    lua_pushnil(L);
    while (lua_next(L, -2) != 0) {
      bool keyOk = lua_type(L, -2) == LUA_TSTRING;
      if (keyOk && std::strcmp(lua_tostring(L, -2), "build") == 0) {
        if (!lua_isfunction(L, -1))
          return fail(4, where + ": terrain.build must be a function(map) that shapes the height map");
        m_terrainBuildRef = luaL_ref(L, LUA_REGISTRYINDEX);  // pops the function
        m_terrainRequest["terrain.build"] = "lua";
        continue;
      }
      bool valueOk = lua_type(L, -1) == LUA_TSTRING || lua_type(L, -1) == LUA_TNUMBER;
      if (!keyOk || !valueOk) {
        return fail(4, where + ": field 'terrain' must be a table of name = number or string (and an optional "
                                 "build = function(map)), e.g. terrain = {generate = 7, size = 1025}");
      }
      std::string key = lua_tostring(L, -2);
      std::string value = lua_tostring(L, -1);  // converts numbers in place (value copy only)
      lua_pop(L, 1);
      if (key == "heightmap") {
        fs::path path = fs::weakly_canonical(fs::path(m_mod.dir) / value);
        fs::path root = fs::weakly_canonical(fs::path(m_mod.dir));
        auto rel = path.lexically_relative(root);
        if (rel.empty() || *rel.begin() == "..") {
          return fail(3, where + ": terrain.heightmap \"" + value + "\" leaves the mod's folder; paths stay inside it");
        }
        value = path.string();
      }
      m_terrainRequest["terrain." + key] = value;
    }
  } else if (!lua_isnil(L, -1)) {
    return fail(2, where + ": field 'terrain' must be a table, e.g. terrain = {generate = 7, size = 1025}");
  }
  lua_pop(L, 1);
  bool hasUpdate = false, hasContact = false;
  for (const char* cb : {"on_start", "on_update", "on_finish", "on_reload", "on_contact"}) {
    rawGetField(L, -1, cb);
    bool bad = !lua_isnil(L, -1) && !lua_isfunction(L, -1);
    if (std::strcmp(cb, "on_update") == 0) hasUpdate = lua_isfunction(L, -1);
    if (std::strcmp(cb, "on_contact") == 0) hasContact = lua_isfunction(L, -1);
    lua_pop(L, 1);
    if (bad) return fail(1, where + ": field '" + cb + "' must be a function");
  }
  m_hasUpdate = hasUpdate;
  m_hasContact = hasContact;
  if (m_scenarioRef) luaL_unref(L, LUA_REGISTRYINDEX, m_scenarioRef);
  m_scenarioRef = luaL_ref(L, LUA_REGISTRYINDEX);
  return Ok{};
}

// ---- hot reload -------------------------------------------------------------------

Status ScenarioHost::reload(double time_s, std::int64_t step) {
  lua_State* L = m_vm.state();
  const int top = lua_gettop(L);
  // The mod's own modules are forgotten so that require loads saved files
  // again; kept aside to be put back if the new code fails. The runtime's
  // library (tumble.*) stays loaded.
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_requireCacheRef);
  const int cache = lua_gettop(L);
  lua_newtable(L);
  const int saved = lua_gettop(L);
  lua_pushnil(L);
  while (lua_next(L, cache) != 0) {
    bool own = lua_type(L, -2) == LUA_TSTRING && std::strncmp(lua_tostring(L, -2), "tumble.", 7) != 0;
    if (own) {
      lua_pushvalue(L, -2);
      lua_insert(L, -2);
      lua_rawset(L, saved);  // saved[k] = v
      lua_pushvalue(L, -1);
      lua_pushnil(L);
      lua_rawset(L, cache);  // cache[k] = nil (allowed while traversing)
    } else {
      lua_pop(L, 1);
    }
  }
  ScriptError err;
  bool ok = runScenarioFile(&err);
  bool hasOnReload = false;
  if (ok) {
    rawGetField(L, -1, "on_reload");
    hasOnReload = lua_isfunction(L, -1);
    lua_pop(L, 1);
    if (Status st = adoptScenarioTable(false); !st) {
      ok = false;
      err = ScriptError{};
      err.mod = m_mod.name;
      err.file = m_file;
      // "mod X: scenarios/y.lua: field ..." -> "field ..." (file is a field of its own).
      const std::string prefix = "mod " + m_mod.name + ": " + m_file + ": ";
      err.message = st.error().rfind(prefix, 0) == 0 ? st.error().substr(prefix.size()) : st.error();
    }
  }
  if (!ok) {
    lua_pushnil(L);
    while (lua_next(L, saved) != 0) {
      lua_pushvalue(L, -2);
      lua_insert(L, -2);
      lua_rawset(L, cache);
    }
    lua_settop(L, top);
    err.message = "reload failed, the previous code keeps running: " + err.message;
    recordError(err);
    return makeError(err.summary());
  }
  lua_settop(L, top);
  ++m_reloadCount;
  m_updatePaused = m_contactPaused = false;  // the fix may be in this save
  m_updateErrors = m_contactErrors = 0;
  if (hasOnReload) {  // the new code makes its own; the old ones would call old functions
    m_timers.clear();
    m_triggers.clear();
  }
  log::info("mod " + m_mod.name + ": " + m_file + " reloaded");
  Status result = Ok{};
  if (hasOnReload) {
    pushCtx(time_s, 0, step);
    rawGetField(L, -1, "state");
    std::size_t before = m_errors.size();
    if (!callLifecycle("on_reload", 2, nullptr, nullptr) && m_errors.size() > before)
      result = makeError(m_errors.back().summary());
  }
  // The old chunk, its closures and modules are garbage now; collect them so
  // the memory a mod uses does not grow with each save.
  lua_gc(L, LUA_GCCOLLECT, 0);
  return result;
}

}  // namespace tumble::script
