#include "script/sandbox.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <initializer_list>

#include "script/internal/lua_util.h"
#include "script/lua_vm.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
}

namespace fs = std::filesystem;

namespace tumble::script {

namespace {

// Copies the named fields of table `src` (global) into a new table.
void copyLibrary(lua_State* L, const char* lib, std::initializer_list<const char*> names) {
  lua_getglobal(L, lib);
  lua_createtable(L, 0, int(names.size()));
  for (const char* n : names) {
    rawGetField(L, -2, n);
    rawSetField(L, -2, n);
  }
  lua_remove(L, -2);
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

/// @function coroutine.close
/// The standard coroutine.close, except for a coroutine the instruction
/// budget stopped: Lua runs such a coroutine's pending <close> handlers with
/// the budget's hook off, so they are not run; the call returns false and
/// says why.
/// @param co thread
/// @return boolean true when the coroutine was closed cleanly
/// @return any? the error object, or the reason the handlers were not run
int sandboxCoroutineClose(lua_State* L) {
  lua_State* co = lua_tothread(L, 1);
  if (co && LuaVm::wasStoppedByBudget(co)) {
    lua_pushboolean(L, 0);
    lua_pushliteral(L, "coroutine.close: the instruction budget stopped this coroutine; its <close> handlers "
                       "are not run");
    return 2;
  }
  lua_pushvalue(L, lua_upvalueindex(1));  // the real coroutine.close
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

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
    rawSetField(L, -2, f->name);
  }
  lua_pushcclosure(L, forbiddenIndex, 1);
  rawSetField(L, -2, "__index");
  lua_pushboolean(L, 0);
  rawSetField(L, -2, "__metatable");
  lua_setmetatable(L, idx);
}


// "tumble.vec", "lib.util": identifiers separated by dots (checked by hand:
// no regular expression over a mod's text).
bool isModuleName(const std::string& name) {
  bool atStart = true;
  for (unsigned char c : name) {
    if (c == '.') {
      if (atStart) return false;
      atStart = true;
    } else if (std::isalpha(c) || c == '_' || (!atStart && std::isdigit(c))) {
      atStart = false;
    } else {
      return false;
    }
  }
  return !atStart;
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
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError("require: expected a module name (a string)");
  std::string name = lua_tostring(L, 1);
  if (!isModuleName(name))
    throw LuaArgError("require: \"" + name + "\" is not a module name like \"tumble.vec\" or \"lib.util\"");
  rawGetField(L, lua_upvalueindex(1), name.c_str());  // loaded cache
  if (lua_touserdata(L, -1) == &kLoadingKey)
    throw LuaArgError("require: \"" + name + "\" requires itself (a circular require); move the shared part "
                      "into a third module");
  if (!lua_isnil(L, -1)) return 1;
  lua_pop(L, 1);
  std::string rel = name;
  std::replace(rel.begin(), rel.end(), '.', '/');
  rel += ".lua";
  fs::path path = name.rfind("tumble.", 0) == 0 ? fs::path(lua_tostring(L, lua_upvalueindex(4))) / rel
                                                 : fs::path(lua_tostring(L, lua_upvalueindex(3))) / rel;
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw LuaArgError("require: module \"" + name + "\" not found (looked for " + path.string() +
                      "); C modules are not allowed in mods");
  // The file itself must stay inside its folder: a symbolic link in the mod
  // pointing at /etc/passwd is not followed out.
  const fs::path root = fs::weakly_canonical(name.rfind("tumble.", 0) == 0 ? fs::path(lua_tostring(L, lua_upvalueindex(4)))
                                                                            : fs::path(lua_tostring(L, lua_upvalueindex(3))), ec);
  const fs::path inside = fs::weakly_canonical(path, ec).lexically_relative(root);
  if (ec || inside.empty() || *inside.begin() == "..")
    throw LuaArgError("require: module \"" + name + "\" (" + path.string() + ") leads outside the mod's folder");
  if (LuaVm::loadFile(L, std::string(path.c_str())) != LUA_OK) {
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "cannot load module";
    lua_pop(L, 1);
    throw LuaArgError(msg);
  }
  lua_pushvalue(L, lua_upvalueindex(2));  // env
  lua_setupvalue(L, -2, 1);
  lua_pushlightuserdata(L, const_cast<char*>(&kLoadingKey));
  rawSetField(L, lua_upvalueindex(1), name.c_str());
  lua_pushstring(L, name.c_str());
  if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "error in module " + name;
    lua_pop(L, 1);
    lua_pushnil(L);
    rawSetField(L, lua_upvalueindex(1), name.c_str());
    throw LuaArgError(msg);
  }
  if (lua_isnil(L, -1)) {
    lua_pop(L, 1);
    lua_pushboolean(L, 1);
  }
  lua_pushvalue(L, -1);
  rawSetField(L, lua_upvalueindex(1), name.c_str());
  return 1;
}


}  // namespace

void pushSandboxEnvironment(lua_State* L, const SandboxPaths& paths, std::uint64_t seed, int* requireCacheRef) {
  // Deterministic random numbers: math.random is seeded with the run's seed.
  lua_getglobal(L, "math");
  rawGetField(L, -1, "randomseed");
  lua_pushinteger(L, lua_Integer(seed));
  lua_call(L, 1, 0);
  lua_pop(L, 1);

  lua_newtable(L);  // env
  const int env = lua_gettop(L);
  for (const char* name : {"assert", "error", "ipairs", "next", "pairs", "pcall", "rawequal", "rawget", "rawlen",
                           "rawset", "select", "tonumber", "tostring", "type", "getmetatable", "_VERSION"}) {
    lua_getglobal(L, name);
    rawSetField(L, env, name);
  }
  copyLibrary(L, "math", {"abs", "acos", "asin", "atan", "ceil", "cos", "deg", "exp", "floor", "fmod", "huge", "log",
                          "max", "maxinteger", "min", "mininteger", "modf", "pi", "rad", "random", "randomseed",
                          "sin", "sqrt", "tan", "tointeger", "type", "ult"});
  rawSetField(L, env, "math");
  copyLibrary(L, "string", {"byte", "char", "find", "format", "gmatch", "gsub", "len", "lower", "match", "pack",
                            "packsize", "rep", "reverse", "sub", "unpack", "upper"});
  guardTable(L, -1, std::begin(kForbiddenString), std::end(kForbiddenString));
  rawSetField(L, env, "string");
  copyLibrary(L, "table", {"concat", "insert", "move", "pack", "remove", "sort", "unpack"});
  rawSetField(L, env, "table");
  copyLibrary(L, "utf8", {"char", "charpattern", "codes", "codepoint", "len", "offset"});
  rawSetField(L, env, "utf8");
  copyLibrary(L, "coroutine", {"close", "create", "isyieldable", "resume", "running", "status", "wrap", "yield"});
  rawGetField(L, -1, "close");
  lua_pushcclosure(L, sandboxCoroutineClose, 1);
  rawSetField(L, -2, "close");
  rawSetField(L, env, "coroutine");
  copyLibrary(L, "os", {"clock", "time", "date", "difftime"});
  guardTable(L, -1, std::begin(kForbiddenOs), std::end(kForbiddenOs));
  rawSetField(L, env, "os");
  lua_getglobal(L, "setmetatable");
  lua_pushcclosure(L, sandboxSetMetatable, 1);
  rawSetField(L, env, "setmetatable");
  luaL_loadbufferx(L, kXpcallSource, sizeof kXpcallSource - 1, "=[sandbox xpcall]", "t");
  lua_getglobal(L, "pcall");
  lua_getglobal(L, "type");
  lua_getglobal(L, "error");
  lua_call(L, 3, 1);
  rawSetField(L, env, "xpcall");
  lua_pushcfunction(L, sandboxCollectGarbage);
  rawSetField(L, env, "collectgarbage");
  lua_pushvalue(L, env);
  lua_getglobal(L, "load");
  lua_pushcclosure(L, sandboxLoad, 2);
  rawSetField(L, env, "load");
  lua_newtable(L);  // require cache
  lua_pushvalue(L, -1);
  *requireCacheRef = luaL_ref(L, LUA_REGISTRYINDEX);
  lua_pushvalue(L, env);
  lua_pushstring(L, paths.modDir.c_str());
  lua_pushstring(L, paths.scriptsDir.c_str());
  lua_pushcclosure(L, guarded<sandboxRequire>, 4);
  rawSetField(L, env, "require");
  lua_pushvalue(L, env);
  rawSetField(L, env, "_G");
}

void pushDataEnvironment(lua_State* L) {
  lua_newtable(L);
  copyLibrary(L, "math", {"abs", "acos", "asin", "atan", "ceil", "cos", "deg", "exp", "floor", "fmod", "huge", "log",
                          "max", "maxinteger", "min", "mininteger", "modf", "pi", "rad", "sin", "sqrt", "tan",
                          "tointeger", "type", "ult"});
  rawSetField(L, -2, "math");
  copyLibrary(L, "string", {"byte", "char", "find", "format", "gmatch", "gsub", "len", "lower", "match", "rep",
                            "reverse", "sub", "upper"});
  rawSetField(L, -2, "string");
  copyLibrary(L, "table", {"concat", "insert", "move", "pack", "remove", "sort", "unpack"});
  rawSetField(L, -2, "table");
  for (const char* name : {"ipairs", "pairs", "select", "tonumber", "tostring", "type", "error", "assert"}) {
    lua_getglobal(L, name);
    rawSetField(L, -2, name);
  }
}

void guardEnvironment(lua_State* L, int idx) {
  guardTable(L, idx, std::begin(kForbiddenGlobals), std::end(kForbiddenGlobals));
}

}  // namespace tumble::script
