#pragma once
// Binding helpers. Lua (compiled as C) raises errors with longjmp, which
// would skip C++ destructors. So bindings never call lua_error themselves:
// they throw LuaArgError (or any std::exception escapes), and guarded<F>
// catches it, lets the C++ frame unwind, and only then raises the Lua error.
// Argument checks below throw instead of using luaL_check*.
#include <set>
#include <stdexcept>
#include <string>

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

#include "core/math.h"

namespace tumble::script {

struct LuaArgError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Raises the pending message as a Lua error (with position info).
int raiseLuaError(lua_State* L, const char* message);

template <int (*F)(lua_State*)>
int guarded(lua_State* L) {
  char buffer[512];
  {
    try {
      return F(L);
    } catch (const std::exception& e) {
      std::snprintf(buffer, sizeof buffer, "%s", e.what());
    }
  }
  return raiseLuaError(L, buffer);
}

/// Number at idx; must be finite. `what` names the argument for the message.
double checkNumber(lua_State* L, int idx, const char* what);
/// Vector from a table {x, y, z} or {x=, y=, z=}; must be finite.
Vec3 checkVec3(lua_State* L, int idx, const char* what);
/// Optional field of the table at tableIdx; throws if present but wrong.
double optNumberField(lua_State* L, int tableIdx, const char* key, double fallback);
bool optBoolField(lua_State* L, int tableIdx, const char* key, bool fallback);
std::string optStringField(lua_State* L, int tableIdx, const char* key, const std::string& fallback);
bool optVec3Field(lua_State* L, int tableIdx, const char* key, Vec3* out);
void pushVec3(lua_State* L, const Vec3& v);  ///< as a table {x=, y=, z=}
/// Throws "<fn>: unknown option 'k' (valid: ...)" for a string key of the
/// table at t that is not in `allowed` (a misspelt field is never ignored).
void checkOptionFields(lua_State* L, int t, const std::string& fn, const std::set<std::string>& allowed);

}  // namespace tumble::script
