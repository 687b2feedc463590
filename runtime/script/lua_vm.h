#pragma once
// One Lua 5.4 state with the limits a mod runs under:
//  - a memory budget enforced by the allocator (allocation fails past it,
//    which Lua reports as "not enough memory");
//  - an instruction budget per callback, checked by a count hook, so a
//    runaway loop is stopped with a clear message and the game goes on;
//  - protected calls that turn every error (Lua or C++) into a ScriptError
//    with file, line and traceback.
#include <cstddef>
#include <cstdint>
#include <string>

#include "script/script_error.h"

struct lua_State;
struct lua_Debug;

namespace tumble::script {

struct VmLimits {
  std::size_t memoryBytes = 256u << 20;          ///< per state
  std::uint64_t instructionsPerCall = 50'000'000;  ///< per protected call
};

class LuaVm {
 public:
  explicit LuaVm(const VmLimits& limits = {});
  ~LuaVm();
  LuaVm(const LuaVm&) = delete;
  LuaVm& operator=(const LuaVm&) = delete;

  lua_State* state() const { return m_L; }
  const VmLimits& limits() const { return m_limits; }
  std::size_t memoryUsed() const { return m_used; }
  /// Protected calls made so far (tests use it to prove a frame made none).
  std::uint64_t callCount() const { return m_calls; }
  /// Serial number of the outermost protected call running or last run
  /// (calls nested in it share it): per-callback budgets key on it.
  std::uint64_t outerCallSerial() const { return m_outerCalls; }

  /// Calls the function below nargs arguments on the stack, protected and
  /// under the instruction budget. On error fills *error and returns false.
  /// `file` is the mod-relative file the callback lives in and `callback` its
  /// name; a budget error reads "mod X: scenarios/y.lua: on_update exceeded N
  /// instructions" (ScriptError::summary). Leaves nresults values on success,
  /// nothing on failure.
  bool call(int nargs, int nresults, const std::string& mod, const std::string& file, const std::string& callback,
            ScriptError* error);
  /// Older form: `what` is the callback's name, the file is not known.
  bool call(int nargs, int nresults, const std::string& mod, const std::string& what, ScriptError* error) {
    return call(nargs, nresults, mod, std::string(), what, error);
  }

  /// Compiles a Lua source file (text only) and pushes the chunk, as
  /// luaL_loadfilex does, but reads the file with core's bounded reader:
  /// a FIFO, device or folder, or a file over 16 MiB, is an error pushed as
  /// the message (LUA_ERRFILE), never a read that blocks or never ends.
  static int loadFile(lua_State* L, const std::string& path);

  /// Turns a Lua error message plus traceback into a ScriptError. Chunk
  /// names are "@<mod dir>/<file>"; the mod-relative file is reported.
  /// Counts `instructions` of work a binding does in C++ on the running
  /// call's behalf (a terrain filter, ...) against its instruction budget.
  /// Returns false, and marks the budget as hit so the script stops at its
  /// next instruction, if that work does not fit in what is left.
  bool charge(lua_State* L, std::uint64_t instructions);
  /// Instructions left of the running call's budget (0 once it is hit); a
  /// whole budget outside any call.
  std::uint64_t instructionsLeft() const;

  /// True if the instruction budget stopped `thread` (a coroutine): Lua
  /// leaves hooks off in it, so its <close> handlers must not run.
  static bool wasStoppedByBudget(lua_State* thread);

  static ScriptError parseError(const std::string& mod, const std::string& message, const std::string& traceback);

 private:
  static void* allocate(void* ud, void* ptr, std::size_t osize, std::size_t nsize);
  static void countHook(lua_State* L, lua_Debug* ar);

  lua_State* m_L = nullptr;
  VmLimits m_limits;
  std::size_t m_used = 0;
  std::uint64_t m_instructions = 0;
  std::uint64_t m_calls = 0;
  std::uint64_t m_outerCalls = 0;
  int m_callDepth = 0;  ///< protected calls running (nested ones share the budget)
  /// Set once the running call exceeded its instruction budget; from then on
  /// every hook tick raises again, so a script cannot pcall its way past it.
  bool m_budgetHit = false;
  int m_budgetLine = 0;        ///< line the runaway code was stopped at
  std::string m_budgetSource;  ///< its chunk name ("@path")
};

}  // namespace tumble::script
