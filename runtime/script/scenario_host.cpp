#include "script/scenario_host.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <regex>

#include "core/log.h"
#include "core/random.h"
#include "physics/deformable.h"
#include "physics/joints/joint_system.h"
#include "script/internal/emitter_table.h"
#include "vehicle/vehicle_system.h"
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

/// @function print
/// Writes its arguments, separated by tabs, to the log as "mod NAME: ...".
/// @param ... any values, converted with tostring
/// @example print("spawned", world.body_count(), "bodies")
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

/// @function load
/// Compiles a chunk of Lua text, as the standard load, but only text: binary
/// chunks (precompiled bytecode) can crash the VM and are refused. Without
/// `env` the chunk sees the mod's own environment, never the real globals.
/// @param chunk string|function source text, or a function returning pieces of it
/// @param name? string chunk name for error messages
/// @param mode? string must be "t" (the default); "b" and "bt" raise an error
/// @param env? table the chunk's _ENV (default: the mod's environment)
/// @return function|nil the compiled chunk, or nil and a message
/// @return string? the error message when compiling failed
/// @example local f = load("return 1 + 2")  -- f() == 3
int sandboxLoad(lua_State* L) {
  int n = lua_gettop(L);
  const char* mode = luaL_optstring(L, 3, "t");
  if (std::strcmp(mode, "t") != 0)
    return luaL_error(L, "load: binary chunks are not allowed in mods (mode \"%s\"; use \"t\" or leave it out)", mode);
  if (lua_type(L, 1) == LUA_TSTRING && lua_rawlen(L, 1) > 0 && lua_tostring(L, 1)[0] == LUA_SIGNATURE[0]) {
    lua_pushnil(L);
    lua_pushliteral(L, "load: binary chunks are not allowed in mods (the chunk starts with \"\\27Lua\")");
    return 2;
  }
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

/// @function collectgarbage
/// The collector is the runtime's; mods may look and nudge, not stop it.
/// @param opt? string "count" (default), "step", "isrunning" or "collect"; others raise an error
/// @param arg? integer for "step": the step size in KiB
/// @return number|boolean "count": memory in use, KiB; "step": true if a cycle finished; "isrunning": true
/// @example hud_text(("Lua memory: %.0f KiB"):format(collectgarbage("count")))
int sandboxCollectGarbage(lua_State* L) {
  const char* opt = luaL_optstring(L, 1, "count");
  if (std::strcmp(opt, "count") == 0) {
    lua_pushnumber(L, lua_gc(L, LUA_GCCOUNT, 0) + lua_gc(L, LUA_GCCOUNTB, 0) / 1024.0);
  } else if (std::strcmp(opt, "step") == 0) {
    int kb = int(luaL_optinteger(L, 2, 0));
    lua_pushboolean(L, lua_gc(L, LUA_GCSTEP, kb < 0 ? 0 : kb));
  } else if (std::strcmp(opt, "isrunning") == 0) {
    lua_pushboolean(L, lua_gc(L, LUA_GCISRUNNING, 0));
  } else if (std::strcmp(opt, "collect") == 0) {
    lua_gc(L, LUA_GCCOLLECT, 0);
    lua_pushinteger(L, 0);
  } else {
    return luaL_error(L,
                      "collectgarbage(\"%s\") is not available to mods: the runtime owns the collector "
                      "(allowed: \"count\", \"step\", \"isrunning\", \"collect\")",
                      opt);
  }
  return 1;
}

/// @function setmetatable
/// The standard setmetatable, except that a metatable with a __gc field is
/// refused: Lua runs finalizers with hooks off, outside the instruction
/// budget, so an endless one could hang the game.
/// @param t table
/// @param mt table|nil
/// @return table t
int sandboxSetMetatable(lua_State* L) {
  if (lua_istable(L, 2)) {
    lua_pushliteral(L, "__gc");
    if (lua_rawget(L, 2) != LUA_TNIL)
      return luaL_error(L, "setmetatable: __gc is not available to mods (finalizers run outside the "
                           "instruction budget); release things explicitly instead");
    lua_pop(L, 1);
  }
  lua_pushvalue(L, lua_upvalueindex(1));  // the real setmetatable
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, 1);
  return 1;
}

// xpcall(f, handler, ...) for mods. Lua calls a message handler from inside
// the count hook when the budget stops a loop, and hooks are off there, so an
// endless handler could not be stopped. This one calls the handler after the
// error has unwound (no traceback is available to mods anyway: no debug).
const char kXpcallSource[] = R"lua(
local pcall, type, error = ...
local function handled(ok, ...) return false, ... end
return function(f, handler, ...)
  if type(handler) ~= "function" then error("bad argument #2 to 'xpcall' (function expected)", 2) end
  local function finish(ok, ...)
    if ok then return true, ... end
    return handled(pcall(handler, (...)))
  end
  return finish(pcall(f, ...))
end
)lua";

// Globals a mod might reach for but must not have, each with the reason and
// what to use instead. Reading one raises the message; other missing globals
// read as nil, as in plain Lua.
struct Forbidden {
  const char* name;
  const char* message;
};
const Forbidden kForbiddenGlobals[] = {
    {"io", "io is not available to mods: scripts cannot open files (put Lua data in your mod and require it)"},
    {"debug", "debug is not available to mods: it can break the sandbox (errors already carry a traceback)"},
    {"package", "package is not available to mods: require \"x.y\" loads <mod>/x/y.lua or scripts/tumble/...; "
                "C modules and package.loadlib are not allowed"},
    {"dofile", "dofile is not available to mods: use require \"x.y\" for <mod>/x/y.lua"},
    {"loadfile", "loadfile is not available to mods: use require \"x.y\" for <mod>/x/y.lua"},
    {"loadstring", "loadstring is Lua 5.1; use load(text) (text chunks only)"},
    {"unpack", "unpack is Lua 5.1; use table.unpack"},
    {"setfenv", "setfenv is Lua 5.1; pass an env table to load(text, name, \"t\", env)"},
    {"getfenv", "getfenv is Lua 5.1; use _ENV"},
    {"warn", "warn is not available to mods: use print (the log) or hud_text"},
};
const Forbidden kForbiddenOs[] = {
    {"execute", "os.execute is not available to mods: only os.clock, os.time, os.date and os.difftime are"},
    {"exit", "os.exit is not available to mods: end a scenario with game.win / game.lose or let it run out"},
    {"remove", "os.remove is not available to mods: scripts cannot touch files"},
    {"rename", "os.rename is not available to mods: scripts cannot touch files"},
    {"tmpname", "os.tmpname is not available to mods: scripts cannot touch files"},
    {"getenv", "os.getenv is not available to mods: use param(name, default) for settings"},
    {"setlocale", "os.setlocale is not available to mods: it would change number formatting for everyone"},
};
const Forbidden kForbiddenString[] = {
    {"dump", "string.dump is not available to mods: binary chunks cannot be loaded anyway"},
};

// __index of the env, os and string tables: upvalue 1 is a table name ->
// message of the forbidden keys.
int forbiddenIndex(lua_State* L) {
  if (lua_type(L, 2) != LUA_TSTRING) return 0;
  lua_pushvalue(L, 2);
  if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TSTRING) return 0;  // plain nil
  luaL_where(L, 1);
  lua_insert(L, -2);
  lua_concat(L, 2);
  return lua_error(L);  // no C++ objects in this frame
}

// Sets a protected metatable on the table at idx whose __index raises the
// message for each forbidden key.
void guardTable(lua_State* L, int idx, const Forbidden* begin, const Forbidden* end) {
  idx = lua_absindex(L, idx);
  lua_createtable(L, 0, 2);
  lua_createtable(L, 0, int(end - begin));
  for (const Forbidden* f = begin; f != end; ++f) {
    lua_pushstring(L, f->message);
    lua_setfield(L, -2, f->name);
  }
  lua_pushcclosure(L, forbiddenIndex, 1);
  lua_setfield(L, -2, "__index");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, idx);
}

const char kLoadingKey = 0;  // sentinel in the require cache: module being loaded

/// @function require
/// Loads a Lua module once and returns what it returned. "tumble.x" is the
/// runtime's library (scripts/tumble/x.lua); any other name is a file inside
/// the mod ("lib.util" -> <mod>/lib/util.lua). Nothing else: no C modules,
/// no paths outside the mod. A module requiring itself (directly or through
/// others) is an error that names it.
/// @param name string module name: letters, digits and _, separated by dots
/// @return any the module's value (true if it returned nothing)
/// @example local util = require "lib.util"
int sandboxRequire(lua_State* L) {
  ScenarioHost* host = ScenarioHost::from(L);
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError("require: expected a module name (a string)");
  std::string name = lua_tostring(L, 1);
  static const std::regex valid(R"(^[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z_][A-Za-z0-9_]*)*$)");
  if (!std::regex_match(name, valid))
    throw LuaArgError("require: \"" + name + "\" is not a module name like \"tumble.vec\" or \"lib.util\"");
  lua_getfield(L, lua_upvalueindex(1), name.c_str());  // loaded cache
  if (lua_touserdata(L, -1) == &kLoadingKey)
    throw LuaArgError("require: \"" + name + "\" requires itself (a circular require); move the shared part "
                      "into a third module");
  if (!lua_isnil(L, -1)) return 1;
  lua_pop(L, 1);
  std::string rel = name;
  std::replace(rel.begin(), rel.end(), '.', '/');
  rel += ".lua";
  fs::path path = name.rfind("tumble.", 0) == 0 ? fs::path(host->options().scriptsDir) / rel
                                                 : fs::path(host->mod().dir) / rel;
  if (!fs::exists(path))
    throw LuaArgError("require: module \"" + name + "\" not found (looked for " + path.string() +
                      "); C modules are not allowed in mods");
  if (luaL_loadfilex(L, path.c_str(), "t") != LUA_OK) {
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "cannot load module";
    lua_pop(L, 1);
    throw LuaArgError(msg);
  }
  lua_pushvalue(L, lua_upvalueindex(2));  // env
  lua_setupvalue(L, -2, 1);
  lua_pushlightuserdata(L, const_cast<char*>(&kLoadingKey));
  lua_setfield(L, lua_upvalueindex(1), name.c_str());
  lua_pushstring(L, name.c_str());
  if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "error in module " + name;
    lua_pop(L, 1);
    lua_pushnil(L);
    lua_setfield(L, lua_upvalueindex(1), name.c_str());
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

/// @function expect
/// Records an expectation that lands in the run report; a failed one makes
/// `tumble run` exit with status 2. A boolean without limits must be true; a
/// number needs limits.
/// @param name string what is checked, shown in the report
/// @param value number|boolean the measured value
/// @param limits? table {min = number, max = number}, inclusive
/// @return boolean whether the expectation held
/// @example expect("ball bounced back", ball:position().y, {min = 0.8, max = 1.2})
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

/// @function param
/// A scenario parameter from the command line (`--set name=value`),
/// converted to the type of the default; the default when not given.
/// @param name string parameter name
/// @param default any returned when absent; its type (number, boolean, string) decides the conversion
/// @return any the value
/// @example local count = param("count", 10)  -- tumble run mymod:rain --set count=50
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

/// @function hud_text
/// Replaces the scenario's lines on the HUD; they stay until the next call.
/// @param ... any one value per line, converted with tostring
/// @example hud_text(("height: %.2f m"):format(ball:position().y))
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
  if (options.input) {
    m_input = options.input;
  } else {
    m_ownInput = std::make_unique<input::InputSystem>();
    m_input = m_ownInput.get();
  }
  m_impulseJoints = options.jointSolver == "impulse";
  lua_State* L = m_vm.state();
  lua_pushlightuserdata(L, this);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kHostKey);
  buildEnvironment();
  if (!options.tuneOverridesFile.empty()) {
    if (Status st = m_tunables.loadOverrides(options.tuneOverridesFile); !st) {
      // A corrupt settings file must not stop the game: defaults, and say so.
      log::warn(st.error());
      m_messages.push_back({st.error(), 0, 10});
    }
  }
  for (const auto& [name, text] : options.tuneSets) {
    if (Status st = m_tunables.setText(name, text, "--set"); !st) log::error(st.error());
  }
}

ScenarioHost::~ScenarioHost() = default;

void ScenarioHost::buildEnvironment() {
  lua_State* L = m_vm.state();
  // Deterministic random numbers: math.random is seeded with the run's seed.
  lua_getglobal(L, "math");
  lua_getfield(L, -1, "randomseed");
  lua_pushinteger(L, lua_Integer(m_options.seed));
  lua_call(L, 1, 0);
  lua_pop(L, 1);

  lua_newtable(L);  // env
  int env = lua_gettop(L);
  for (const char* name : {"assert", "error", "ipairs", "next", "pairs", "pcall", "rawequal", "rawget", "rawlen",
                           "rawset", "select", "tonumber", "tostring", "type", "getmetatable", "_VERSION"}) {
    lua_getglobal(L, name);
    lua_setfield(L, env, name);
  }
  copyLibrary(L, "math", {"abs", "acos", "asin", "atan", "ceil", "cos", "deg", "exp", "floor", "fmod", "huge", "log",
                          "max", "maxinteger", "min", "mininteger", "modf", "pi", "rad", "random", "randomseed",
                          "sin", "sqrt", "tan", "tointeger", "type", "ult"});
  lua_setfield(L, env, "math");
  copyLibrary(L, "string", {"byte", "char", "find", "format", "gmatch", "gsub", "len", "lower", "match", "pack",
                            "packsize", "rep", "reverse", "sub", "unpack", "upper"});
  guardTable(L, -1, std::begin(kForbiddenString), std::end(kForbiddenString));
  lua_setfield(L, env, "string");
  copyLibrary(L, "table", {"concat", "insert", "move", "pack", "remove", "sort", "unpack"});
  lua_setfield(L, env, "table");
  copyLibrary(L, "utf8", {"char", "charpattern", "codes", "codepoint", "len", "offset"});
  lua_setfield(L, env, "utf8");
  copyLibrary(L, "coroutine", {"close", "create", "isyieldable", "resume", "running", "status", "wrap", "yield"});
  lua_setfield(L, env, "coroutine");
  copyLibrary(L, "os", {"clock", "time", "date", "difftime"});
  guardTable(L, -1, std::begin(kForbiddenOs), std::end(kForbiddenOs));
  lua_setfield(L, env, "os");
  lua_pushcfunction(L, sandboxPrint);
  lua_setfield(L, env, "print");
  lua_getglobal(L, "setmetatable");
  lua_pushcclosure(L, sandboxSetMetatable, 1);
  lua_setfield(L, env, "setmetatable");
  luaL_loadbufferx(L, kXpcallSource, sizeof kXpcallSource - 1, "=[sandbox xpcall]", "t");
  lua_getglobal(L, "pcall");
  lua_getglobal(L, "type");
  lua_getglobal(L, "error");
  lua_call(L, 3, 1);
  lua_setfield(L, env, "xpcall");
  lua_pushcfunction(L, sandboxCollectGarbage);
  lua_setfield(L, env, "collectgarbage");
  lua_pushvalue(L, env);
  lua_getglobal(L, "load");
  lua_pushcclosure(L, sandboxLoad, 2);
  lua_setfield(L, env, "load");
  lua_newtable(L);  // require cache
  lua_pushvalue(L, -1);
  m_requireCacheRef = luaL_ref(L, LUA_REGISTRYINDEX);
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
  openDeformableBindings(L, env);
  openOdeBindings(L, env);
  openSpringBindings(L, env);
  openJointBindings(L, env);
  lua_pushvalue(L, env);
  lua_setfield(L, env, "_G");
  guardTable(L, env, std::begin(kForbiddenGlobals), std::end(kForbiddenGlobals));
  m_envRef = luaL_ref(L, LUA_REGISTRYINDEX);  // pops env

  lua_newtable(L);  // ctx, with ctx.state kept across reloads
  lua_newtable(L);
  lua_setfield(L, -2, "state");
  m_ctxRef = luaL_ref(L, LUA_REGISTRYINDEX);
  lua_newtable(L);
  m_timerFnsRef = luaL_ref(L, LUA_REGISTRYINDEX);
  lua_newtable(L);
  m_emitterTablesRef = luaL_ref(L, LUA_REGISTRYINDEX);
}

/// @class Scenario
/// What a scenario file returns. Every field is optional.
/// @field title string shown in the window title and the HUD
/// @field duration number seconds `tumble run` simulates without --seconds/--steps (default 10)
/// @field joint_solver string "lagrange" (default; formulation A, Lagrange multipliers before the step) or "impulse" (formulation B, impulses solved with the contacts); --set physics.joint_solver=... overrides it
/// @field integrator string how the world advances bodies between contact solves: "symplectic_euler" (default), "euler", "heun", "rk4", "verlet", "implicit_euler", "implicit_midpoint", "sdirk2"; --integrator overrides it
/// @field on_start fun(ctx: Ctx) called once before the first step
/// @field on_update fun(ctx: Ctx, dt: number) called before every fixed step (dt in s)
/// @field on_contact fun(ctx: Ctx, a: Body, b: Body, impulse: number, point: Vec3, normal: Vec3) called after a step for each pair of bodies that began touching in it; impulse in N s, normal from a to b
/// @field on_finish fun(ctx: Ctx) called once after the last step: the place for expect()
/// @field on_reload fun(ctx: Ctx, state: table) called after a hot reload, in the new code, with state = ctx.state; re-make timers and triggers here (the old ones were dropped) and refresh locals from state

/// @class Ctx
/// The context passed to every callback (the same table each time).
/// @field time number simulated time, s (for on_update: the step's start; for on_contact: its end)
/// @field dt number the fixed step, s (0 in on_start and on_finish)
/// @field step integer index of the step
/// @field seed integer the run's seed (--seed)
/// @field state table yours: kept for the whole run and across hot reloads (on_reload gets it); keep what reloaded code needs here

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
  host->m_defaultTitle = mod.name + ":" + scenario;
  ScriptError err;
  if (!host->runScenarioFile(&err)) return makeError(err.summary() + (err.traceback.empty() ? "" : "\n" + err.traceback));
  if (Status st = host->adoptScenarioTable(true); !st) return makeError(st.error());
  return host;
}

bool ScenarioHost::runScenarioFile(ScriptError* err) {
  lua_State* L = m_vm.state();
  const std::string path = (fs::path(m_mod.dir) / m_file).string();
  if (luaL_loadfilex(L, path.c_str(), "t") != LUA_OK) {
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
  lua_getfield(L, -1, "title");
  m_title = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : m_defaultTitle;
  lua_pop(L, 1);
  lua_getfield(L, -1, "duration");
  if (lua_type(L, -1) == LUA_TNUMBER && lua_tonumber(L, -1) > 0) m_duration_s = lua_tonumber(L, -1);
  else if (!lua_isnil(L, -1)) {
    return fail(2, where + ": field 'duration' must be a number of seconds > 0");
  }
  lua_pop(L, 1);
  // joint_solver = "lagrange" | "impulse"; --set physics.joint_solver wins.
  lua_getfield(L, -1, "joint_solver");
  if (!lua_isnil(L, -1)) {
    physics::JointSolverKind kind;
    if (lua_type(L, -1) != LUA_TSTRING || !physics::parseJointSolver(lua_tostring(L, -1), &kind))
      return fail(2, where + ": field 'joint_solver' must be \"lagrange\" or \"impulse\"");
    if (m_options.jointSolver.empty()) m_impulseJoints = kind == physics::JointSolverKind::Impulse;
  }
  lua_pop(L, 1);
  lua_getfield(L, -1, "integrator");
  if (lua_type(L, -1) == LUA_TSTRING) m_integratorRequest = lua_tostring(L, -1);
  else if (!lua_isnil(L, -1))
    return fail(2, where + ": field 'integrator' must be a string such as \"rk4\" (see tumble run --help)");
  lua_pop(L, 1);
  // terrain = {generate = 7, size = 1025, ...} or {heightmap = "assets/map.png"}
  lua_getfield(L, -1, "terrain");
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
    lua_getfield(L, -1, cb);
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
    lua_getfield(L, -1, "on_reload");
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
  if (hasOnReload) dropTimersAndTriggers();
  log::info("mod " + m_mod.name + ": " + m_file + " reloaded");
  Status result = Ok{};
  if (hasOnReload) {
    pushCtx(time_s, 0, step);
    lua_getfield(L, -1, "state");
    std::size_t before = m_errors.size();
    if (!callLifecycle("on_reload", 2, nullptr, nullptr) && m_errors.size() > before)
      result = makeError(m_errors.back().summary());
  }
  // The old chunk, its closures and modules are garbage now; collect them so
  // the memory a mod uses does not grow with each save.
  lua_gc(L, LUA_GCCOLLECT, 0);
  return result;
}

void ScenarioHost::dropTimersAndTriggers() {
  lua_State* L = m_vm.state();
  luaL_unref(L, LUA_REGISTRYINDEX, m_timerFnsRef);
  lua_newtable(L);
  m_timerFnsRef = luaL_ref(L, LUA_REGISTRYINDEX);
  m_timers.clear();
  for (Trigger& t : m_triggers)
    if (t.id != 0) removeTrigger(t.id);
}

std::size_t ScenarioHost::activeTimerCount() const {
  lua_State* L = m_vm.state();
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_timerFnsRef);
  std::size_t n = 0;
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    lua_pop(L, 1);
    ++n;
  }
  lua_pop(L, 1);
  return n;
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
  lua_setfield(L, -2, "time");
  lua_pushnumber(L, dt_s);
  lua_setfield(L, -2, "dt");
  lua_pushinteger(L, step);
  lua_setfield(L, -2, "step");
  lua_pushinteger(L, lua_Integer(m_options.seed));
  lua_setfield(L, -2, "seed");
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
  lua_getfield(L, -1, name);
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
}

void ScenarioHost::update(double time_s, double dt_s, std::int64_t step) {
  m_now_s = time_s;
  m_scriptLines.clear();
  m_dt_s = dt_s;
  if (!m_timers.empty() && m_timers.front().due_s <= time_s + 1e-9) runTimers(time_s, dt_s, step);
  if (hasUpdate()) {
    pushCtx(time_s, dt_s, step);
    lua_pushnumber(m_vm.state(), dt_s);
    callLifecycle("on_update", 2, &m_updatePaused, &m_updateErrors);
  }
  // Last, so that every force of the step (scripts included) is in the
  // joints' Q; the app calls World::step right after this.
  if (m_joints) m_joints->beforeWorldStep();
  if (m_vehicles) m_vehicles->beforeStep(Real(dt_s));
}

vehicle::VehicleSystem& ScenarioHost::vehicles() {
  if (!m_vehicles) m_vehicles = std::make_unique<vehicle::VehicleSystem>(m_world);
  return *m_vehicles;
}

physics::JointSystem& ScenarioHost::joints() {
  if (!m_joints) {
    // Velocity-only projection when joints or jointed bodies are new (see
    // JointSettings::postStabilize): moving positions would push bodies
    // lying on the ground into it.
    physics::JointSettings js;
    js.projectPositions = false;
    js.solver = m_impulseJoints ? physics::JointSolverKind::Impulse : physics::JointSolverKind::Lagrange;
    m_joints = std::make_unique<physics::JointSystem>(m_world, js);
  }
  return *m_joints;
}

particles::ParticleSystem& ScenarioHost::particles() {
  if (!m_particles) {
    m_particles = std::make_unique<particles::ParticleSystem>(m_options.seed);
    m_particles->setGravity(m_world.settings().gravity_mps2.cast<float>());
  }
  return *m_particles;
}

Result<particles::EmitterDef> ScenarioHost::emitterDef(const std::string& ref, int overridesIdx) {
  lua_State* L = m_vm.state();
  if (overridesIdx) overridesIdx = lua_absindex(L, overridesIdx);
  // "mod:name" or "name" (this mod, then base).
  std::string modName, name = ref;
  if (auto colon = ref.find(':'); colon != std::string::npos) {
    modName = ref.substr(0, colon);
    name = ref.substr(colon + 1);
  }
  static const std::regex nameRe(R"(^[A-Za-z0-9_\-]+$)");
  if (!std::regex_match(name, nameRe) || (!modName.empty() && !std::regex_match(modName, nameRe)))
    return makeError("emitter \"" + ref + "\" is not of the form MOD:NAME or NAME (for example \"base:dust\")");
  std::vector<const ModInfo*> candidates;
  auto findMod = [&](const std::string& m) -> const ModInfo* {
    if (m == m_mod.name) return &m_mod;
    for (const ModInfo& info : m_options.mods)
      if (info.name == m) return &info;
    return nullptr;
  };
  if (!modName.empty()) {
    if (const ModInfo* m = findMod(modName)) candidates.push_back(m);
    else return makeError("emitter \"" + ref + "\": no mod named \"" + modName + "\" is loaded");
  } else {
    candidates.push_back(&m_mod);
    if (const ModInfo* base = findMod("base"); base && base != &m_mod) candidates.push_back(base);
  }
  const ModInfo* mod = nullptr;
  for (const ModInfo* m : candidates)
    if (fs::exists(fs::path(m->dir) / "emitters" / (name + ".lua"))) {
      mod = m;
      break;
    }
  if (!mod) {
    std::string known;
    for (const ModInfo* m : candidates)
      for (const std::string& e : ModRegistry::listLua(*m, "emitters")) known += (known.empty() ? "" : ", ") + m->name + ":" + e;
    return makeError("emitter \"" + ref + "\" not found (emitters/" + name + ".lua; known: " +
                     (known.empty() ? std::string("none") : known) + ")");
  }
  const std::string key = mod->name + ":" + name;
  const std::string path = (fs::path(mod->dir) / "emitters" / (name + ".lua")).string();
  const std::string file = "emitters/" + name + ".lua";
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_emitterTablesRef);
  if (lua_getfield(L, -1, key.c_str()) != LUA_TTABLE) {
    lua_pop(L, 1);
    std::string error;
    int line = 0;
    if (!runEmitterChunk(m_vm, path, mod->name, &error, &line)) {
      lua_pop(L, 1);
      return makeError("mod " + mod->name + ": " + file + (line > 0 ? ":" + std::to_string(line) : "") + ": " + error);
    }
    lua_pushvalue(L, -1);
    lua_setfield(L, -3, key.c_str());
  }
  // The file's fields, then the overrides on top, into a fresh table.
  lua_newtable(L);
  for (int src : {-2, overridesIdx}) {
    if (src == 0) continue;
    int from = src < 0 ? lua_gettop(L) - 1 : src;
    lua_pushnil(L);
    while (lua_next(L, from) != 0) {
      lua_pushvalue(L, -2);
      lua_insert(L, -2);
      lua_settable(L, -4);
    }
  }
  particles::EmitterDef def;
  std::vector<std::string> problems;
  readEmitterTable(L, -1, def, problems);
  lua_pop(L, 3);
  if (problems.empty()) return def;
  std::string msg;
  for (const std::string& p : problems) msg += (msg.empty() ? "" : "; ") + p;
  return makeError("mod " + mod->name + ": " + file + (overridesIdx ? " (with overrides)" : "") + ": " + msg);
}

physics::DeformableSystem& ScenarioHost::deformables() {
  if (!m_deformables) m_deformables = std::make_unique<physics::DeformableSystem>();
  return *m_deformables;
}

Eigen::Vector3f ScenarioHost::deformableColor(int id) const {
  auto it = m_deformableColors.find(id);
  return it == m_deformableColors.end() ? Eigen::Vector3f(0.9f, 0.6f, 0.2f) : it->second;
}

void ScenarioHost::addScriptLine(const ScriptLine& line) {
  if (m_scriptLines.size() < kMaxScriptLines) m_scriptLines.push_back(line);
}

void ScenarioHost::rememberEmitterSource(particles::EmitterId id, const std::string& ref, int overridesIdx) {
  lua_State* L = m_vm.state();
  // Drop the sources of emitters that are gone (bounded: one entry per live emitter).
  if (m_particles)
    std::erase_if(m_emitterSources, [&](const EmitterSource& e) {
      if (m_particles->isValid(e.id)) return false;
      if (e.overridesRef) luaL_unref(L, LUA_REGISTRYINDEX, e.overridesRef);
      return true;
    });
  EmitterSource source{id, ref, 0};
  if (overridesIdx) {
    overridesIdx = lua_absindex(L, overridesIdx);
    lua_newtable(L);  // a shallow copy: the script may change its table later
    lua_pushnil(L);
    while (lua_next(L, overridesIdx) != 0) {
      lua_pushvalue(L, -2);
      lua_insert(L, -2);
      lua_settable(L, -4);
    }
    source.overridesRef = luaL_ref(L, LUA_REGISTRYINDEX);
  }
  m_emitterSources.push_back(std::move(source));
}

Status ScenarioHost::reloadEmitterFile(const std::string& relPath) {
  // "emitters/smoke.lua" -> "smoke"
  std::string name = fs::path(relPath).stem().string();
  forgetEmitterDefinitions();
  // Read it now, so a broken file is reported at once (and nothing changes).
  if (auto def = emitterDef(m_mod.name + ":" + name, 0); !def) return makeError(def.error());
  if (!m_particles) return Ok{};
  lua_State* L = m_vm.state();
  const std::string qualified = m_mod.name + ":" + name;
  for (const EmitterSource& e : m_emitterSources) {
    if (!m_particles->isValid(e.id)) continue;
    // "name" means this mod first, so it resolves to this file too.
    if (e.ref != qualified && e.ref != name) continue;
    int idx = 0;
    if (e.overridesRef) {
      lua_rawgeti(L, LUA_REGISTRYINDEX, e.overridesRef);
      idx = lua_gettop(L);
    }
    auto def = emitterDef(e.ref, idx);
    if (idx) lua_pop(L, 1);
    if (!def) return makeError(def.error());
    m_particles->redefine(e.id, *def);
  }
  return Ok{};
}

void ScenarioHost::forgetEmitterDefinitions() {
  lua_State* L = m_vm.state();
  lua_newtable(L);
  lua_rawseti(L, LUA_REGISTRYINDEX, m_emitterTablesRef);
}

void ScenarioHost::setJointSolver(bool impulse) {
  m_impulseJoints = impulse;
  if (m_joints)
    m_joints->setSolver(impulse ? physics::JointSolverKind::Impulse : physics::JointSolverKind::Lagrange);
}

double ScenarioHost::jointErrorMax_m() const { return m_joints ? m_joints->maxAnchorError_m() : 0.0; }

void ScenarioHost::afterStep(double time_s, std::int64_t step) {
  m_now_s = time_s;
  if (hasContact() && !m_world.contactEvents().empty()) runContacts(time_s, step);
  if (m_liveTriggers > 0) runTriggers();
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

// ---- contacts -------------------------------------------------------------------

void ScenarioHost::runContacts(double time_s, std::int64_t step) {
  // Copy first: a callback may remove bodies or create new ones.
  m_contactScratch.assign(m_world.contactEvents().begin(), m_world.contactEvents().end());
  lua_State* L = m_vm.state();
  for (const physics::ContactEvent& e : m_contactScratch) {
    if (!hasContact()) break;
    if (!m_world.isValid(e.a) || !m_world.isValid(e.b)) continue;  // removed by an earlier callback
    pushCtx(time_s, 0, step);
    pushBody(L, e.a);
    pushBody(L, e.b);
    lua_pushnumber(L, e.impulse_Ns);
    pushVec3(L, e.point_m);
    pushVec3(L, e.normal);
    callLifecycle("on_contact", 6, &m_contactPaused, &m_contactErrors);
  }
}

// ---- timers -----------------------------------------------------------------------

namespace {
// Heap order: the earliest due first, ties in creation order.
bool laterTimer(const auto& a, const auto& b) { return a.due_s != b.due_s ? a.due_s > b.due_s : a.seq > b.seq; }
}  // namespace

std::uint32_t ScenarioHost::addTimer(double delay_s, double period_s) {
  lua_State* L = m_vm.state();
  Timer t;
  t.id = m_nextTimerId++;
  t.seq = m_timerSeq++;
  t.due_s = m_now_s + delay_s;
  t.period_s = period_s;
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_timerFnsRef);
  lua_insert(L, -2);
  lua_rawseti(L, -2, t.id);  // pops the function
  lua_pop(L, 1);
  m_timers.push_back(t);
  std::push_heap(m_timers.begin(), m_timers.end(), [](const Timer& a, const Timer& b) { return laterTimer(a, b); });
  return t.id;
}

bool ScenarioHost::timerActive(std::uint32_t id) const {
  lua_State* L = m_vm.state();
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_timerFnsRef);
  bool active = lua_rawgeti(L, -1, id) != LUA_TNIL;
  lua_pop(L, 2);
  return active;
}

bool ScenarioHost::cancelTimer(std::uint32_t id) {
  // The heap entry stays and is skipped when it comes due.
  bool active = timerActive(id);
  lua_State* L = m_vm.state();
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_timerFnsRef);
  lua_pushnil(L);
  lua_rawseti(L, -2, id);
  lua_pop(L, 1);
  return active;
}

void ScenarioHost::runTimers(double time_s, double dt_s, std::int64_t step) {
  lua_State* L = m_vm.state();
  auto later = [](const Timer& a, const Timer& b) { return laterTimer(a, b); };
  // Timers made while firing wait for the next update, even after(0): so a
  // timer that re-arms itself cannot keep this loop going.
  const std::uint64_t seqLimit = m_timerSeq;
  while (!m_timers.empty() && m_timers.front().due_s <= time_s + 1e-9 && m_timers.front().seq < seqLimit) {
    std::pop_heap(m_timers.begin(), m_timers.end(), later);
    Timer t = m_timers.back();
    m_timers.pop_back();
    lua_rawgeti(L, LUA_REGISTRYINDEX, m_timerFnsRef);
    if (lua_rawgeti(L, -1, t.id) != LUA_TFUNCTION) {  // cancelled
      lua_pop(L, 2);
      continue;
    }
    lua_remove(L, -2);
    pushCtx(time_s, dt_s, step);
    ScriptError err;
    bool ok = m_vm.call(1, 1, m_mod.name, m_file, t.period_s > 0 ? "timer.every" : "timer.after", &err);
    bool again = t.period_s > 0;
    if (ok) {
      again = again && !(lua_isboolean(L, -1) && !lua_toboolean(L, -1));  // returning false stops it
      lua_pop(L, 1);
      t.errors = 0;
    } else {
      m_errors.push_back(err);
      log::error(err.summary() + "\n" + err.traceback);
      if (again && ++t.errors >= kMaxConsecutiveErrors) {
        again = false;
        ScriptError note = err;
        note.limit = false;
        note.message = "timer.every callback failed " + std::to_string(kMaxConsecutiveErrors) +
                       " times in a row and was cancelled (last error: " + err.message + ")";
        m_errors.push_back(note);
        log::warn(note.summary());
      }
    }
    if (again && timerActive(t.id)) {
      // Keep the phase (due += period) but fire at most once per update.
      t.due_s += t.period_s;
      if (t.due_s <= time_s + 1e-9) t.due_s = time_s + t.period_s;
      m_timers.push_back(t);
      std::push_heap(m_timers.begin(), m_timers.end(), later);
    } else {
      cancelTimer(t.id);
    }
  }
}

// ---- triggers ---------------------------------------------------------------------

std::uint32_t ScenarioHost::addTrigger(const Vec3& center_m, const Vec3& halfSize_m, int onEnterIdx, int onExitIdx) {
  lua_State* L = m_vm.state();
  Trigger fresh;
  auto slot = std::find_if(m_triggers.begin(), m_triggers.end(), [](const Trigger& t) { return t.id == 0; });
  Trigger& t = slot != m_triggers.end() ? *slot : m_triggers.emplace_back(std::move(fresh));
  t.id = m_nextTriggerId++;
  t.inside.clear();
  t.center_m = center_m;
  t.half_m = halfSize_m;
  if (onEnterIdx) {
    lua_pushvalue(L, onEnterIdx);
    t.onEnterRef = luaL_ref(L, LUA_REGISTRYINDEX);
  }
  if (onExitIdx) {
    lua_pushvalue(L, onExitIdx);
    t.onExitRef = luaL_ref(L, LUA_REGISTRYINDEX);
  }
  ++m_liveTriggers;
  return t.id;
}

bool ScenarioHost::removeTrigger(std::uint32_t id) {
  for (Trigger& t : m_triggers) {
    if (t.id != id) continue;
    lua_State* L = m_vm.state();
    if (t.onEnterRef) luaL_unref(L, LUA_REGISTRYINDEX, t.onEnterRef);
    if (t.onExitRef) luaL_unref(L, LUA_REGISTRYINDEX, t.onExitRef);
    t.id = 0;  // the slot (and its vectors' capacity) is reused
    t.onEnterRef = t.onExitRef = 0;
    t.inside.clear();
    --m_liveTriggers;
    return true;
  }
  return false;
}

const std::vector<physics::BodyId>* ScenarioHost::triggerBodies(std::uint32_t id) const {
  for (const Trigger& t : m_triggers)
    if (t.id == id && id != 0) return &t.inside;
  return nullptr;
}

void ScenarioHost::runTriggers() {
  // 1. Who is inside now (non-static bodies, by centre of mass), in body
  //    index order, compared with the last step: enters and exits.
  m_triggerEvents.clear();
  for (Trigger& t : m_triggers) {
    if (t.id == 0) continue;
    t.scratch.clear();
    m_world.forEachBody([&](physics::BodyId id, const physics::Body& b) {
      if (b.type == physics::BodyType::Static) return;
      if (((b.position_m - t.center_m).cwiseAbs() - t.half_m).maxCoeff() <= 0) t.scratch.push_back(id);
    });
    auto before = [](physics::BodyId a, physics::BodyId b) {
      return a.index != b.index ? a.index < b.index : a.generation < b.generation;
    };
    std::size_t i = 0, j = 0;
    while (i < t.inside.size() || j < t.scratch.size()) {
      if (j == t.scratch.size() || (i < t.inside.size() && before(t.inside[i], t.scratch[j]))) {
        if (t.onExitRef) m_triggerEvents.push_back({t.id, t.inside[i], false});
        ++i;
      } else if (i == t.inside.size() || before(t.scratch[j], t.inside[i])) {
        if (t.onEnterRef) m_triggerEvents.push_back({t.id, t.scratch[j], true});
        ++j;
      } else {
        ++i, ++j;
      }
    }
    std::swap(t.inside, t.scratch);
  }
  // 2. Call back, after every trigger is updated (callbacks may add or
  //    remove triggers and bodies).
  lua_State* L = m_vm.state();
  for (const TriggerEvent& e : m_triggerEvents) {
    int ref = 0;
    for (const Trigger& t : m_triggers)
      if (t.id == e.trigger) ref = e.enter ? t.onEnterRef : t.onExitRef;
    if (!ref) continue;  // the trigger was removed by an earlier callback
    lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
    pushBody(L, e.body);
    pushTrigger(L, e.trigger);
    callRecorded(2, e.enter ? "trigger on_enter" : "trigger on_exit");
  }
}

// ---- game state -------------------------------------------------------------------

void ScenarioHost::addMessage(std::string text, double duration_s) {
  if (m_messages.size() >= kMaxMessages) m_messages.erase(m_messages.begin());
  m_messages.push_back({std::move(text), m_now_s, duration_s});
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

void ScenarioHost::setColor(physics::BodyId id, const Eigen::Vector3f& rgb) {
  if (m_colors.size() <= id.index) m_colors.resize(id.index + 1, Eigen::Vector3f(-1, -1, -1));
  m_colors[id.index] = rgb;
}

Eigen::Vector3f ScenarioHost::colorOf(physics::BodyId id) const {
  if (id.index < m_colors.size() && m_colors[id.index].x() >= 0) return m_colors[id.index];
  return Eigen::Vector3f(0.75f, 0.75f, 0.78f);
}

}  // namespace tumble::script
