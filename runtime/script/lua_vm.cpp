#include "script/lua_vm.h"
#include "script/internal/raw_access.h"
#include "script/internal/pattern_budget.h"

#include "core/assert.h"
#include "core/file_util.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

extern "C" {
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
}

namespace tumble::script {

namespace {
constexpr int kHookEvery = 1000;  // instructions between hook calls
const char kVmKey = 0;           // registry key: the LuaVm owning a state
const char kStoppedThreadsKey = 0;  // registry key: weak set of coroutines the budget stopped

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
  rawSetField(L, -2, "message");
  luaL_traceback(L, L, nullptr, 1);
  rawSetField(L, -2, "traceback");
  return 1;
}
}  // namespace

std::string ScriptError::summary() const {
  std::string s = "mod " + mod + ": ";
  // Budget errors name the callback instead of a line: "mod X: scenarios/y.lua:
  // on_update exceeded N instructions ..." (the line is in the message).
  if (!file.empty()) {
    s += file;
    if (line > 0 && !limit) {
      s += ':';
      s += std::to_string(line);
    }
    s += ": ";
  }
  return s + message;
}

LuaVm::LuaVm(const VmLimits& limits) : m_limits(limits) {
  m_L = lua_newstate(&LuaVm::allocate, this);
  TUMBLE_ASSERT(m_L, "lua_newstate failed: out of memory at start-up");
  lua_pushlightuserdata(m_L, this);
  lua_rawsetp(m_L, LUA_REGISTRYINDEX, &kVmKey);
  luaL_openlibs(m_L);
  // Pattern matching counts its steps against the budget (pattern_budget.h);
  // before the copies of `string` below and in the sandbox are made.
  installPatternBudget(m_L, this);
  // The string metatable is shared by every string in the state. Protect it
  // (getmetatable("") returns false, so it cannot be changed) and point its
  // __index at a private copy of the string library without string.dump:
  // ("").dump is then nil, and a mod changing its own `string` table does not
  // change what s:upper() means.
  lua_getglobal(m_L, "string");
  lua_pushnil(m_L);
  rawSetField(m_L, -2, "dump");
  lua_newtable(m_L);
  lua_pushnil(m_L);
  while (lua_next(m_L, -3) != 0) {
    lua_pushvalue(m_L, -2);
    lua_insert(m_L, -2);
    lua_rawset(m_L, -4);
  }
  lua_pushliteral(m_L, "");
  if (lua_getmetatable(m_L, -1)) {
    lua_pushvalue(m_L, -3);
    rawSetField(m_L, -2, "__index");
    lua_pushboolean(m_L, 0);
    rawSetField(m_L, -2, "__metatable");
    lua_pop(m_L, 1);
  }
  lua_pop(m_L, 3);
  lua_newtable(m_L);  // weak-keyed set of coroutines stopped by the budget
  lua_newtable(m_L);
  lua_pushliteral(m_L, "k");
  lua_setfield(m_L, -2, "__mode");
  lua_setmetatable(m_L, -2);
  lua_rawsetp(m_L, LUA_REGISTRYINDEX, &kStoppedThreadsKey);
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

void LuaVm::countHook(lua_State* L, lua_Debug* ar) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kVmKey);
  auto* vm = static_cast<LuaVm*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  if (!vm) return;
  if (!vm->m_budgetHit && lua_gethookcount(L) != kHookEvery) {
    // A coroutine left over from an earlier stopped call: back to normal.
    lua_sethook(L, &LuaVm::countHook, LUA_MASKCOUNT, kHookEvery);
    return;
  }
  vm->m_instructions += kHookEvery;
  if (vm->m_instructions <= vm->m_limits.instructionsPerCall && !vm->m_budgetHit) return;
  if (!vm->m_budgetHit) {
    vm->m_budgetHit = true;
    if (lua_getinfo(L, "Sl", ar)) {
      vm->m_budgetLine = ar->currentline;
      vm->m_budgetSource = ar->source ? ar->source : "";
    }
  }
  // From now on raise at every instruction, in this thread and in the main
  // one (a coroutine stopped here hands control back to its resumer, which
  // would otherwise run another kHookEvery instructions per caught error): a
  // pcall in the script catches the error, and the very next instruction
  // raises again, so the stop reaches the top however the loop is wrapped.
  lua_sethook(L, &LuaVm::countHook, LUA_MASKCOUNT, 1);
  if (L != vm->m_L) {
    lua_sethook(vm->m_L, &LuaVm::countHook, LUA_MASKCOUNT, 1);
    // Lua leaves hooks off in a coroutine that died by an error raised in a
    // hook, so its <close> handlers would run unbounded under
    // coroutine.close; remember it (weakly) and the sandbox's close refuses.
    lua_rawgetp(L, LUA_REGISTRYINDEX, &kStoppedThreadsKey);
    if (lua_istable(L, -1)) {
      lua_pushthread(L);
      lua_pushboolean(L, 1);
      lua_rawset(L, -3);
    }
    lua_pop(L, 1);
  }
  // No C++ object with a destructor lives in this frame, so lua_error may
  // longjmp from here. The message has no position: LuaVm::call names the
  // mod, file and callback.
  lua_pushfstring(L, "exceeded %I instructions (runaway loop?); the call was stopped",
                  lua_Integer(vm->m_limits.instructionsPerCall));
  lua_error(L);
}

bool LuaVm::charge(lua_State* L, std::uint64_t instructions) {
  if (m_callDepth == 0) return true;  // not inside a budgeted call
  if (!m_budgetHit && instructions <= m_limits.instructionsPerCall - std::min(m_instructions, m_limits.instructionsPerCall)) {
    m_instructions += instructions;
    return true;
  }
  if (!m_budgetHit) {
    m_budgetHit = true;
    lua_Debug ar;
    if (lua_getstack(L, 1, &ar) && lua_getinfo(L, "Sl", &ar)) {
      m_budgetLine = ar.currentline;
      m_budgetSource = ar.source ? ar.source : "";
    }
  }
  lua_sethook(L, &LuaVm::countHook, LUA_MASKCOUNT, 1);
  lua_sethook(m_L, &LuaVm::countHook, LUA_MASKCOUNT, 1);
  return false;
}

std::uint64_t LuaVm::instructionsLeft() const {
  if (m_callDepth == 0) return m_limits.instructionsPerCall;
  if (m_budgetHit) return 0;
  return m_limits.instructionsPerCall - std::min(m_instructions, m_limits.instructionsPerCall);
}

bool LuaVm::wasStoppedByBudget(lua_State* thread) {
  lua_rawgetp(thread, LUA_REGISTRYINDEX, &kStoppedThreadsKey);
  bool stopped = false;
  if (lua_istable(thread, -1)) {
    lua_pushthread(thread);
    stopped = lua_rawget(thread, -2) != LUA_TNIL;
    lua_pop(thread, 1);
  }
  lua_pop(thread, 1);
  return stopped;
}

namespace {
std::string formatBytes(std::size_t bytes) {
  if (bytes >= (1u << 20) && bytes % (1u << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  if (bytes >= 1024 && bytes % 1024 == 0) return std::to_string(bytes >> 10) + " KiB";
  return std::to_string(bytes) + " bytes";
}

// "@/abs/mods/base/lib/x.lua" -> "lib/x.lua" (the path inside the mod).
std::string modRelative(const std::string& mod, std::string path) {
  if (!path.empty() && (path[0] == '@' || path[0] == '=')) path.erase(0, 1);
  std::string marker = "/" + mod + "/";
  auto pos = path.rfind(marker);
  return pos == std::string::npos ? path : path.substr(pos + marker.size());
}

// Error messages and tracebacks go to the log, the HUD and the report; a
// script can raise a string of any length (error(string.rep("x", 1e6))), so
// they are cut to a readable size, saying how much was cut.
constexpr std::size_t kMaxMessageChars = 2000;
std::string clip(std::string text) {
  if (text.size() <= kMaxMessageChars) return text;
  const std::size_t cut = text.size() - kMaxMessageChars;
  text.resize(kMaxMessageChars);
  return text + "... (" + std::to_string(cut) + " more characters)";
}

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}
}  // namespace

bool LuaVm::call(int nargs, int nresults, const std::string& mod, const std::string& file,
                 const std::string& callback, ScriptError* error) {
  int base = lua_gettop(m_L) - nargs;  // index of the function
  lua_pushcfunction(m_L, messageHandler);
  lua_insert(m_L, base);
  ++m_calls;
  // A call made from inside a running one (an emitter file loaded by
  // particles.spawn, a vehicle file by vehicle.spawn) runs on the outer
  // call's budget: only the outermost call starts a fresh count.
  const bool outermost = m_callDepth == 0;
  if (outermost) {
    ++m_outerCalls;
    m_instructions = 0;
    m_budgetHit = false;
    m_budgetLine = 0;
    m_budgetSource.clear();
  }
  ++m_callDepth;
  int status = lua_pcall(m_L, nargs, nresults, base);
  --m_callDepth;
  lua_remove(m_L, base);
  bool budgetHit = m_budgetHit;
  if (outermost) {
    m_budgetHit = false;
    if (budgetHit) lua_sethook(m_L, &LuaVm::countHook, LUA_MASKCOUNT, kHookEvery);
  }
  if (status == LUA_OK) return true;
  std::string message, traceback;
  if (lua_istable(m_L, -1)) {
    rawGetField(m_L, -1, "message");
    message = lua_tostring(m_L, -1) ? lua_tostring(m_L, -1) : "";
    lua_pop(m_L, 1);
    rawGetField(m_L, -1, "traceback");
    traceback = lua_tostring(m_L, -1) ? lua_tostring(m_L, -1) : "";
    lua_pop(m_L, 1);
  } else if (lua_isstring(m_L, -1)) {
    message = lua_tostring(m_L, -1);  // memory errors skip the handler
  } else {
    message = "unknown error";
  }
  lua_pop(m_L, 1);
  if (!error) return false;
  message = clip(std::move(message));
  traceback = clip(std::move(traceback));
  const std::string what = callback.empty() ? std::string("the call") : callback;
  // A memory error the script caught and raised again arrives as a string.
  bool memory = status == LUA_ERRMEM || endsWith(message, "not enough memory");
  if (budgetHit || memory) {
    ScriptError e;
    e.mod = mod;
    e.file = file;
    e.traceback = traceback;
    e.limit = true;
    if (budgetHit) {
      std::string at = modRelative(mod, m_budgetSource);
      if (e.file.empty()) e.file = at;
      e.line = at == e.file ? m_budgetLine : 0;
      e.message = what + " exceeded " + std::to_string(m_limits.instructionsPerCall) +
                  " instructions (runaway loop?); stopped at " + at + ":" + std::to_string(m_budgetLine);
    } else {
      e.message = what + " exceeded the memory budget of " + formatBytes(m_limits.memoryBytes) +
                  " (a table or string that grows without end?)";
    }
    *error = e;
    return false;
  }
  *error = parseError(mod, message, traceback);
  if (error->file.empty()) error->file = file;
  if (endsWith(error->message, "stack overflow"))
    error->message += " (a function that calls itself without end?)";
  return false;
}

int LuaVm::loadFile(lua_State* L, const std::string& path) {
  auto text = readTextFile(path, std::size_t(16) << 20);
  if (!text) {
    lua_pushstring(L, text.error().c_str());
    return LUA_ERRFILE;
  }
  return luaL_loadbufferx(L, text->data(), text->size(), ("@" + path).c_str(), "t");
}

ScriptError LuaVm::parseError(const std::string& mod, const std::string& message, const std::string& traceback) {
  ScriptError e;
  e.mod = mod;
  e.traceback = traceback;
  e.message = message;
  // "path/to/mods/base/scenarios/drop.lua:12: text", read by hand: the
  // message is the script's own text (error("...") of any length), and a
  // regular expression engine recurses per character.
  const std::size_t colon = message.find(':');
  if (colon == std::string::npos || colon < 5 || message.compare(colon - 4, 4, ".lua") != 0 ||
      message.find('\n') < colon)
    return e;
  std::size_t digits = colon + 1;
  while (digits < message.size() && digits - colon <= 9 && message[digits] >= '0' && message[digits] <= '9') ++digits;
  if (digits == colon + 1 || message.compare(digits, 2, ": ") != 0) return e;
  const std::string path = message.substr(0, colon);
  e.line = std::stoi(message.substr(colon + 1, digits - colon - 1));
  e.message = message.substr(digits + 2);
  // Report the path inside the mod: after "/<mod>/" when present.
  std::string marker = "/" + mod + "/";
  auto pos = path.rfind(marker);
  e.file = pos == std::string::npos ? path : path.substr(pos + marker.size());
  return e;
}

}  // namespace tumble::script
