#pragma once
// Binding helpers. Lua (compiled as C) raises errors with longjmp, which
// would skip C++ destructors. So bindings never call lua_error themselves:
// they throw LuaArgError (or any std::exception escapes), and guarded<F>
// catches it, lets the C++ frame unwind, and only then raises the Lua error.
// Argument checks below throw instead of using luaL_check*.
#include <cassert>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

#include "core/math.h"
#include "script/internal/raw_access.h"

namespace tumble::script {

struct LuaArgError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Raises the pending message as a Lua error (with position info).
int raiseLuaError(lua_State* L, const char* message);

/// Debug builds check every binding's stack balance (Defold's
/// DM_LUA_STACK_CHECK): a binding returns n results from the top of the
/// stack and may leave its arguments below them, but must not leave
/// anything else behind (a value pushed and forgotten grows the stack on
/// every call until Lua runs out of it).
void checkStackBalance(lua_State* L, int argsOnEntry, int results, const char* binding);

template <int (*F)(lua_State*)>
int guarded(lua_State* L) {
  char buffer[512];
  {
    try {
#ifndef NDEBUG
      const int argsOnEntry = lua_gettop(L);
      const int results = F(L);
      checkStackBalance(L, argsOnEntry, results, __PRETTY_FUNCTION__);
      return results;
#else
      return F(L);
#endif
    } catch (const std::exception& e) {
      std::snprintf(buffer, sizeof buffer, "%s", e.what());
    }
  }
  return raiseLuaError(L, buffer);
}

/// Registration of what bindings expose; every Lua-visible type and table
/// is made through these, so each has the same protections.
///
/// A userdata type: `methods` become its __index table, and __tostring,
/// __eq and __gc are set when given. The metatable is protected
/// (getmetatable returns false), so scripts cannot swap the methods.
struct BoundType {
  const char* metatable;          ///< registry name, e.g. "tumble.Body"
  const luaL_Reg* methods;        ///< ends with {nullptr, nullptr}
  lua_CFunction toString = nullptr;
  lua_CFunction equals = nullptr;
  lua_CFunction collect = nullptr;  ///< __gc: only for userdata that own C++ memory
};
void registerType(lua_State* L, const BoundType& type);
/// A table of functions (a module such as `timer`) set as env[name].
void registerModule(lua_State* L, int envIndex, const char* name, const luaL_Reg* functions);
/// Functions set as fields of the table at tableIndex (globals of the env,
/// or functions added to an existing module).
void registerFunctions(lua_State* L, int tableIndex, const luaL_Reg* functions);

/// tostring(value) for messages and the HUD, with the value's __tostring run
/// under lua_pcall: a __tostring that raises (or runs out of budget) becomes
/// a LuaArgError instead of a longjmp through the calling binding.
std::string toDisplayString(lua_State* L, int idx);

/// Number at idx; must be finite. `what` names the argument for the message.
double checkNumber(lua_State* L, int idx, const char* what);
/// Vector from a table {x, y, z} or {x=, y=, z=}; must be finite.
Vec3 checkVec3(lua_State* L, int idx, const char* what);
/// Optional field of the table at tableIdx; throws if present but wrong.
double optNumberField(lua_State* L, int tableIdx, const char* key, double fallback);
bool optBoolField(lua_State* L, int tableIdx, const char* key, bool fallback);
std::string optStringField(lua_State* L, int tableIdx, const char* key, const std::string& fallback);
bool optVec3Field(lua_State* L, int tableIdx, const char* key, Vec3* out);
/// The optional rotation vector field `key` (axis times angle, rad; the
/// `rotation` of world bodies, models, rag-dolls and trigger boxes) as a
/// quaternion; absent or zero: the identity. Errors as optVec3Field.
Quat optRotationField(lua_State* L, int tableIdx, const char* key = "rotation");
void pushVec3(lua_State* L, const Vec3& v);  ///< as a table {x=, y=, z=}
/// The one check for a table's field names, with one wording everywhere:
/// throws "<where>: unknown field 'k' (did you mean: x?) (valid: a, b, c)"
/// for a key of the table at t that is not in `allowed`, so a misspelt field
/// is never ignored. Keys are read raw (no metamethods run).
void checkFields(lua_State* L, int t, const std::string& where, const std::set<std::string>& allowed);
/// The message checkFields throws, for checks that collect problems
/// instead of throwing (definition files).
std::string unknownFieldMessage(const std::string& key, const std::set<std::string>& allowed);

}  // namespace tumble::script
