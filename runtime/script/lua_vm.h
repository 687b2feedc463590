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

  /// Calls the function below nargs arguments on the stack, protected and
  /// under the instruction budget. On error fills *error (mod name taken from
  /// `mod`, `what` names the callback for budget messages) and returns false.
  /// Leaves nresults values on success, nothing on failure.
  bool call(int nargs, int nresults, const std::string& mod, const std::string& what, ScriptError* error);

  /// Turns a Lua error message plus traceback into a ScriptError. Chunk
  /// names are "@<mod dir>/<file>"; the mod-relative file is reported.
  static ScriptError parseError(const std::string& mod, const std::string& message, const std::string& traceback);

 private:
  static void* allocate(void* ud, void* ptr, std::size_t osize, std::size_t nsize);
  static void countHook(lua_State* L, lua_Debug* ar);

  lua_State* m_L = nullptr;
  VmLimits m_limits;
  std::size_t m_used = 0;
  std::uint64_t m_instructions = 0;
  std::string m_what;  ///< callback being run, for the budget message
  std::string m_mod;
};

}  // namespace tumble::script
