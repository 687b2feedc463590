#include "script/lua_vm.h"

#include "core/assert.h"

#include <cstdlib>
#include <cstring>
#include <regex>

extern "C" {
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
}

namespace tumble::script {

namespace {
constexpr int kHookEvery = 1000;  // instructions between hook calls
const char kVmKey = 0;           // registry key: the LuaVm owning a state

int messageHandler(lua_State* L) {
  // Keep the message; add the traceback as a second value via a table.
  const char* msg = lua_tostring(L, 1);
  if (!msg) {
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) {
      msg = lua_tostring(L, -1);
    } else {
      msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
    }
  }
  lua_newtable(L);
  lua_pushstring(L, msg);
  lua_setfield(L, -2, "message");
  luaL_traceback(L, L, nullptr, 1);
  lua_setfield(L, -2, "traceback");
  return 1;
}
}  // namespace

std::string ScriptError::summary() const {
  std::string s = "mod " + mod + ": ";
  if (!file.empty()) s += file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": ";
  return s + message;
}

LuaVm::LuaVm(const VmLimits& limits) : m_limits(limits) {
  m_L = lua_newstate(&LuaVm::allocate, this);
  TUMBLE_ASSERT(m_L, "lua_newstate failed: out of memory at start-up");
  lua_pushlightuserdata(m_L, this);
  lua_rawsetp(m_L, LUA_REGISTRYINDEX, &kVmKey);
  luaL_openlibs(m_L);
  // Protect the shared string metatable: a mod may not replace it.
  lua_pushliteral(m_L, "");
  if (lua_getmetatable(m_L, -1)) {
    lua_pushboolean(m_L, 0);
    lua_setfield(m_L, -2, "__metatable");
    lua_pop(m_L, 1);
  }
  lua_pop(m_L, 1);
  lua_sethook(m_L, &LuaVm::countHook, LUA_MASKCOUNT, kHookEvery);
}

LuaVm::~LuaVm() {
  if (m_L) lua_close(m_L);
}

void* LuaVm::allocate(void* ud, void* ptr, std::size_t osize, std::size_t nsize) {
  auto* vm = static_cast<LuaVm*>(ud);
  std::size_t old = ptr ? osize : 0;
  if (nsize == 0) {
    vm->m_used -= old;
    std::free(ptr);
    return nullptr;
  }
  if (nsize > old && vm->m_used - old + nsize > vm->m_limits.memoryBytes) return nullptr;  // Lua raises "not enough memory"
  void* p = std::realloc(ptr, nsize);
  if (p) vm->m_used = vm->m_used - old + nsize;
  return p;
}

void LuaVm::countHook(lua_State* L, lua_Debug*) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kVmKey);
  auto* vm = static_cast<LuaVm*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  if (!vm) return;
  vm->m_instructions += kHookEvery;
  if (vm->m_instructions > vm->m_limits.instructionsPerCall) {
    vm->m_instructions = 0;  // let the error handler run
    luaL_error(L, "%s exceeded %d million instructions (runaway loop?); the call was stopped",
               vm->m_what.c_str(), int(vm->m_limits.instructionsPerCall / 1000000));
  }
}

bool LuaVm::call(int nargs, int nresults, const std::string& mod, const std::string& what, ScriptError* error) {
  int base = lua_gettop(m_L) - nargs;  // index of the function
  lua_pushcfunction(m_L, messageHandler);
  lua_insert(m_L, base);
  m_instructions = 0;
  m_what = what;
  m_mod = mod;
  int status = lua_pcall(m_L, nargs, nresults, base);
  lua_remove(m_L, base);
  if (status == LUA_OK) return true;
  std::string message, traceback;
  if (lua_istable(m_L, -1)) {
    lua_getfield(m_L, -1, "message");
    message = lua_tostring(m_L, -1) ? lua_tostring(m_L, -1) : "";
    lua_pop(m_L, 1);
    lua_getfield(m_L, -1, "traceback");
    traceback = lua_tostring(m_L, -1) ? lua_tostring(m_L, -1) : "";
    lua_pop(m_L, 1);
  } else if (lua_isstring(m_L, -1)) {
    message = lua_tostring(m_L, -1);  // memory errors skip the handler
  } else {
    message = "unknown error";
  }
  if (status == LUA_ERRMEM) message = what + ": mod exceeded its memory budget (" +
                                      std::to_string(m_limits.memoryBytes >> 20) + " MiB): " + message;
  lua_pop(m_L, 1);
  if (error) *error = parseError(mod, message, traceback);
  return false;
}

ScriptError LuaVm::parseError(const std::string& mod, const std::string& message, const std::string& traceback) {
  ScriptError e;
  e.mod = mod;
  e.traceback = traceback;
  e.message = message;
  // "path/to/mods/base/scenarios/drop.lua:12: text"
  static const std::regex re(R"(^([^\n:]+\.lua):(\d+): ([\s\S]*)$)");
  std::smatch m;
  if (std::regex_match(message, m, re)) {
    std::string path = m[1];
    e.line = std::stoi(m[2]);
    e.message = m[3];
    // Report the path inside the mod: after "/<mod>/" when present.
    std::string marker = "/" + mod + "/";
    auto pos = path.rfind(marker);
    e.file = pos == std::string::npos ? path : path.substr(pos + marker.size());
  }
  return e;
}

}  // namespace tumble::script
