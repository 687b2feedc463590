#include "script/scenario_host.h"

#include <filesystem>
#include <regex>

#include "core/log.h"
#include "script/internal/lua_util.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
}

namespace fs = std::filesystem;

namespace tumble::script {

namespace {
const char kHostKey = 0;  // registry: ScenarioHost*

// ---- sandbox globals -------------------------------------------------------------

// Copies the named fields of table `src` (global) into a new table.
void copyLibrary(lua_State* L, const char* lib, std::initializer_list<const char*> names) {
  lua_getglobal(L, lib);
  lua_createtable(L, 0, int(names.size()));
  for (const char* n : names) {
    lua_getfield(L, -2, n);
    lua_setfield(L, -2, n);
  }
  lua_remove(L, -2);
}

int sandboxPrint(lua_State* L) {
  ScenarioHost* host = ScenarioHost::from(L);
  std::string line;
  int n = lua_gettop(L);
  for (int i = 1; i <= n; ++i) {
    std::size_t len = 0;
    const char* s = luaL_tolstring(L, i, &len);
    if (i > 1) line += '\t';
    line.append(s, len);
    lua_pop(L, 1);
  }
  log::info("mod " + (host ? host->mod().name : std::string("?")) + ": " + line);
  return 0;
}

// load(chunk [, name [, mode [, env]]]) restricted to text chunks; the
// default environment is the mod's sandbox, never the real globals.
int sandboxLoad(lua_State* L) {
  int n = lua_gettop(L);
  const char* mode = luaL_optstring(L, 3, "t");
  if (std::string(mode) != "t") return luaL_error(L, "load: binary chunks are not allowed in mods (mode must be \"t\")");
  lua_settop(L, 4);
  if (n < 4) {
    lua_pushvalue(L, lua_upvalueindex(1));  // the sandbox env
    lua_replace(L, 4);
  }
  lua_pushvalue(L, lua_upvalueindex(2));  // real load
  lua_pushvalue(L, 1);
  lua_pushvalue(L, 2);
  lua_pushliteral(L, "t");
  lua_pushvalue(L, 4);
  lua_call(L, 4, 2);
  return 2;
}

int sandboxCollectGarbage(lua_State* L) {
  const char* opt = luaL_optstring(L, 1, "count");
  if (std::string(opt) != "count") return luaL_error(L, "collectgarbage: only \"count\" is available to mods");
  lua_pushnumber(L, lua_gc(L, LUA_GCCOUNT, 0) + lua_gc(L, LUA_GCCOUNTB, 0) / 1024.0);
  return 1;
}

// require "tumble.x" -> <scripts>/tumble/x.lua; require "a.b" -> <mod>/a/b.lua.
// Nothing else: no C modules, no paths outside the mod and scripts/.
int sandboxRequire(lua_State* L) {
  ScenarioHost* host = ScenarioHost::from(L);
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError("require: expected a module name (a string)");
  std::string name = lua_tostring(L, 1);
  static const std::regex valid(R"(^[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*$)");
  if (!std::regex_match(name, valid))
    throw LuaArgError("require: \"" + name + "\" is not a module name like \"tumble.vec\" or \"lib.util\"");
  lua_getfield(L, lua_upvalueindex(1), name.c_str());  // loaded cache
  if (!lua_isnil(L, -1)) return 1;
  lua_pop(L, 1);
  std::string rel = std::regex_replace(name, std::regex(R"(\.)"), "/") + ".lua";
  fs::path path = name.rfind("tumble.", 0) == 0 ? fs::path(host->options().scriptsDir) / rel
                                                 : fs::path(host->mod().dir) / rel;
  if (!fs::exists(path))
    throw LuaArgError("require: module \"" + name + "\" not found (looked for " + path.string() +
                      "); C modules are not allowed in mods");
  if (luaL_loadfilex(L, path.c_str(), "t") != LUA_OK) {
    std::string msg = lua_tostring(L, -1);
    lua_pop(L, 1);
    throw LuaArgError(msg);
  }
  lua_pushvalue(L, lua_upvalueindex(2));  // env
  lua_setupvalue(L, -2, 1);
  lua_pushstring(L, name.c_str());
  if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "error in module";
    lua_pop(L, 1);
    throw LuaArgError(msg);
  }
  if (lua_isnil(L, -1)) {
    lua_pop(L, 1);
    lua_pushboolean(L, 1);
  }
  lua_pushvalue(L, -1);
  lua_setfield(L, lua_upvalueindex(1), name.c_str());
  return 1;
}

// expect(name, value, {min=, max=})
int luaExpect(lua_State* L) {
  ScenarioHost* host = ScenarioHost::from(L);
  Expectation e;
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError("expect: argument 1 must be the expectation's name (a string)");
  e.name = lua_tostring(L, 1);
  if (lua_isboolean(L, 2)) {
    e.isBool = true;
    e.value = lua_toboolean(L, 2) ? 1 : 0;
  } else if (lua_type(L, 2) == LUA_TNUMBER) {
    e.value = lua_tonumber(L, 2);
  } else {
    throw LuaArgError("expect(\"" + e.name + "\"): argument 2 must be a number or a boolean, got " +
                      luaL_typename(L, 2));
  }
  if (lua_istable(L, 3)) {
    lua_getfield(L, 3, "min");
    if (lua_type(L, -1) == LUA_TNUMBER) e.min = lua_tonumber(L, -1);
    lua_pop(L, 1);
    lua_getfield(L, 3, "max");
    if (lua_type(L, -1) == LUA_TNUMBER) e.max = lua_tonumber(L, -1);
    lua_pop(L, 1);
  } else if (!lua_isnoneornil(L, 3)) {
    throw LuaArgError("expect(\"" + e.name + "\"): argument 3 must be a table {min = ..., max = ...}");
  }
  if (e.isBool && !e.min && !e.max) {
    e.ok = e.value == 1;
  } else if (!e.min && !e.max) {
    throw LuaArgError("expect(\"" + e.name + "\"): a number needs limits, e.g. expect(name, v, {min = 0, max = 1})");
  } else {
    e.ok = std::isfinite(e.value) && (!e.min || e.value >= *e.min) && (!e.max || e.value <= *e.max);
  }
  lua_pushboolean(L, e.ok);
  host->addExpectation(std::move(e));
  return 1;
}

// param(name, default): the --set value converted to default's type.
int luaParam(lua_State* L) {
  ScenarioHost* host = ScenarioHost::from(L);
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError("param: argument 1 must be the parameter's name");
  std::string name = lua_tostring(L, 1);
  auto it = host->options().params.find(name);
  if (it == host->options().params.end()) {
    lua_settop(L, 2);
    return 1;
  }
  const std::string& text = it->second;
  switch (lua_type(L, 2)) {
    case LUA_TNUMBER: {
      char* end = nullptr;
      double v = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != 0 || !std::isfinite(v))
        throw LuaArgError("--set " + name + "=" + text + ": expected a number");
      lua_pushnumber(L, v);
      return 1;
    }
    case LUA_TBOOLEAN:
      if (text != "true" && text != "false") throw LuaArgError("--set " + name + "=" + text + ": expected true or false");
      lua_pushboolean(L, text == "true");
      return 1;
    default: lua_pushstring(L, text.c_str()); return 1;
  }
}

// hud_text(line, ...): lines shown on the HUD until replaced.
int luaHudText(lua_State* L) {
  std::vector<std::string> lines;
  for (int i = 1; i <= lua_gettop(L); ++i) {
    std::size_t len = 0;
    const char* s = luaL_tolstring(L, i, &len);
    lines.emplace_back(s, len);
    lua_pop(L, 1);
  }
  ScenarioHost::from(L)->setHudText(std::move(lines));
  return 0;
}

}  // namespace

ScenarioHost* ScenarioHost::from(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kHostKey);
  auto* host = static_cast<ScenarioHost*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return host;
}

ScenarioHost::ScenarioHost(const ModInfo& mod, physics::World& world, const ScenarioOptions& options)
    : m_vm(options.limits), m_mod(mod), m_world(world), m_options(options) {
  lua_State* L = m_vm.state();
  lua_pushlightuserdata(L, this);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kHostKey);
  buildEnvironment();
}

ScenarioHost::~ScenarioHost() = default;

void ScenarioHost::buildEnvironment() {
  lua_State* L = m_vm.state();
  // Deterministic random numbers: the run's seed.
  lua_getglobal(L, "math");
  lua_getfield(L, -1, "randomseed");
  lua_pushinteger(L, lua_Integer(m_options.seed));
  lua_call(L, 1, 0);
  lua_pop(L, 1);

  lua_newtable(L);  // env
  int env = lua_gettop(L);
  for (const char* name : {"assert", "error", "ipairs", "next", "pairs", "pcall", "rawequal", "rawget", "rawlen",
                           "rawset", "select", "tonumber", "tostring", "type", "xpcall", "getmetatable",
                           "setmetatable", "_VERSION"}) {
    lua_getglobal(L, name);
    lua_setfield(L, env, name);
  }
  copyLibrary(L, "math", {"abs", "acos", "asin", "atan", "ceil", "cos", "deg", "exp", "floor", "fmod", "huge", "log",
                          "max", "maxinteger", "min", "mininteger", "modf", "pi", "rad", "random", "randomseed",
                          "sin", "sqrt", "tan", "tointeger", "type", "ult"});
  lua_setfield(L, env, "math");
  copyLibrary(L, "string", {"byte", "char", "find", "format", "gmatch", "gsub", "len", "lower", "match", "pack",
                            "packsize", "rep", "reverse", "sub", "unpack", "upper"});
  lua_setfield(L, env, "string");
  copyLibrary(L, "table", {"concat", "insert", "move", "pack", "remove", "sort", "unpack"});
  lua_setfield(L, env, "table");
  copyLibrary(L, "utf8", {"char", "charpattern", "codes", "codepoint", "len", "offset"});
  lua_setfield(L, env, "utf8");
  copyLibrary(L, "coroutine", {"close", "create", "isyieldable", "resume", "running", "status", "wrap", "yield"});
  lua_setfield(L, env, "coroutine");
  copyLibrary(L, "os", {"clock", "time", "date", "difftime"});
  lua_setfield(L, env, "os");
  lua_pushcfunction(L, sandboxPrint);
  lua_setfield(L, env, "print");
  lua_pushcfunction(L, sandboxCollectGarbage);
  lua_setfield(L, env, "collectgarbage");
  lua_pushvalue(L, env);
  lua_getglobal(L, "load");
  lua_pushcclosure(L, sandboxLoad, 2);
  lua_setfield(L, env, "load");
  lua_newtable(L);  // require cache
  lua_pushvalue(L, env);
  lua_pushcclosure(L, guarded<sandboxRequire>, 2);
  lua_setfield(L, env, "require");
  lua_pushcfunction(L, guarded<luaExpect>);
  lua_setfield(L, env, "expect");
  lua_pushcfunction(L, guarded<luaParam>);
  lua_setfield(L, env, "param");
  lua_pushcfunction(L, guarded<luaHudText>);
  lua_setfield(L, env, "hud_text");
  openBodyType(L);
  openWorldBindings(L, env);
  lua_pushvalue(L, env);
  lua_setfield(L, env, "_G");
  m_envRef = luaL_ref(L, LUA_REGISTRYINDEX);  // pops env

  lua_newtable(L);
  m_ctxRef = luaL_ref(L, LUA_REGISTRYINDEX);
}

Result<std::unique_ptr<ScenarioHost>> ScenarioHost::load(const ModInfo& mod, const std::string& scenario,
                                                          physics::World& world, const ScenarioOptions& options) {
  fs::path file = fs::path(mod.dir) / "scenarios" / (scenario + ".lua");
  std::string where = "mod " + mod.name + ": scenarios/" + scenario + ".lua";
  if (!fs::exists(file)) {
    std::string known;
    for (auto& s : ModRegistry::listLua(mod, "scenarios")) known += (known.empty() ? "" : ", ") + s;
    return makeError(where + ": no such scenario (this mod has: " + (known.empty() ? "none" : known) + ")");
  }
  std::unique_ptr<ScenarioHost> host(new ScenarioHost(mod, world, options));
  host->m_file = "scenarios/" + scenario + ".lua";
  lua_State* L = host->m_vm.state();
  if (luaL_loadfilex(L, file.c_str(), "t") != LUA_OK) {
    ScriptError e = LuaVm::parseError(mod.name, lua_tostring(L, -1), "");
    lua_pop(L, 1);
    return makeError(e.summary());
  }
  lua_rawgeti(L, LUA_REGISTRYINDEX, host->m_envRef);
  lua_setupvalue(L, -2, 1);
  ScriptError err;
  if (!host->m_vm.call(0, 1, mod.name, host->m_file, &err)) return makeError(err.summary() + "\n" + err.traceback);
  if (!lua_istable(L, -1)) {
    lua_pop(L, 1);
    return makeError(where + ": must return a table {on_start = function(ctx) ... end, ...}");
  }
  lua_getfield(L, -1, "title");
  host->m_title = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : mod.name + ":" + scenario;
  lua_pop(L, 1);
  lua_getfield(L, -1, "duration");
  if (lua_type(L, -1) == LUA_TNUMBER && lua_tonumber(L, -1) > 0) host->m_duration_s = lua_tonumber(L, -1);
  else if (!lua_isnil(L, -1)) {
    lua_pop(L, 2);
    return makeError(where + ": field 'duration' must be a number of seconds > 0");
  }
  lua_pop(L, 1);
  for (const char* cb : {"on_start", "on_update", "on_finish", "on_reload"}) {
    lua_getfield(L, -1, cb);
    bool bad = !lua_isnil(L, -1) && !lua_isfunction(L, -1);
    if (std::string(cb) == "on_update") host->m_hasUpdate = lua_isfunction(L, -1);
    lua_pop(L, 1);
    if (bad) {
      lua_pop(L, 1);
      return makeError(where + ": field '" + cb + "' must be a function");
    }
  }
  host->m_scenarioRef = luaL_ref(L, LUA_REGISTRYINDEX);
  return host;
}

void ScenarioHost::pushCtx(double time_s, double dt_s, std::int64_t step) {
  lua_State* L = m_vm.state();
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_ctxRef);
  lua_pushnumber(L, time_s);
  lua_setfield(L, -2, "time");
  lua_pushnumber(L, dt_s);
  lua_setfield(L, -2, "dt");
  lua_pushinteger(L, step);
  lua_setfield(L, -2, "step");
  lua_pushinteger(L, lua_Integer(m_options.seed));
  lua_setfield(L, -2, "seed");
}

bool ScenarioHost::callLifecycle(const char* name, int nargs, bool* paused, int* consecutive) {
  // Stack: ctx [, args...]
  lua_State* L = m_vm.state();
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_scenarioRef);
  lua_getfield(L, -1, name);
  lua_remove(L, -2);
  if (!lua_isfunction(L, -1)) {
    lua_pop(L, 1 + nargs);
    return true;
  }
  lua_insert(L, -1 - nargs);
  ScriptError err;
  if (m_vm.call(nargs, 0, m_mod.name, m_file + " " + name, &err)) {
    if (consecutive) *consecutive = 0;
    return true;
  }
  m_errors.push_back(err);
  log::error(err.summary() + "\n" + err.traceback);
  if (consecutive && ++*consecutive >= kMaxConsecutiveErrors && paused) {
    *paused = true;
    ScriptError note = err;
    note.message = std::string(name) + " failed " + std::to_string(kMaxConsecutiveErrors) +
                   " times in a row and was paused (last error: " + err.message + ")";
    m_errors.push_back(note);
    log::warn(note.summary());
  }
  return false;
}

void ScenarioHost::start() {
  pushCtx(0, 0, 0);
  callLifecycle("on_start", 1, nullptr, nullptr);
}

void ScenarioHost::update(double time_s, double dt_s, std::int64_t step) {
  if (!hasUpdate()) return;
  pushCtx(time_s, dt_s, step);
  lua_pushnumber(m_vm.state(), dt_s);
  callLifecycle("on_update", 2, &m_updatePaused, &m_updateErrors);
}

void ScenarioHost::finish(double time_s, std::int64_t step) {
  pushCtx(time_s, 0, step);
  callLifecycle("on_finish", 1, nullptr, nullptr);
}

void ScenarioHost::setColor(physics::BodyId id, const Eigen::Vector3f& rgb) {
  if (m_colors.size() <= id.index) m_colors.resize(id.index + 1, Eigen::Vector3f(-1, -1, -1));
  m_colors[id.index] = rgb;
}

Eigen::Vector3f ScenarioHost::colorOf(physics::BodyId id) const {
  if (id.index < m_colors.size() && m_colors[id.index].x() >= 0) return m_colors[id.index];
  return Eigen::Vector3f(0.75f, 0.75f, 0.78f);
}

}  // namespace tumble::script
