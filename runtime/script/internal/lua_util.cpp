#include "script/internal/lua_util.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "input/binding.h"

namespace tumble::script {

/// @class Vec3
/// A vector as the API returns it: {x=, y=, z=}. Arguments also accept the
/// short form {x, y, z}. Colours use the same shape for {r, g, b}.
/// @field x number
/// @field y number up
/// @field z number

/// @alias Vec3Arg Vec3|number[] a vector argument: {x=, y=, z=} or {x, y, z}

/// @class Quat
/// A unit quaternion {w=, x=, y=, z=}.
/// @field w number
/// @field x number
/// @field y number
/// @field z number

int raiseLuaError(lua_State* L, const char* message) {
  luaL_where(L, 1);
  lua_pushstring(L, message);
  lua_concat(L, 2);
  return lua_error(L);
}

namespace {
int toStringProtected(lua_State* L) {
  luaL_tolstring(L, 1, nullptr);
  return 1;
}
}  // namespace

std::string toDisplayString(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  lua_pushcfunction(L, toStringProtected);
  lua_pushvalue(L, idx);
  if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
    std::string why = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "an error that is not a string";
    lua_pop(L, 1);
    if (why.size() > 200) why = why.substr(0, 200) + "...";
    throw LuaArgError("converting a " + std::string(luaL_typename(L, idx)) + " to text: its __tostring failed: " + why);
  }
  std::size_t len = 0;
  const char* s = lua_tolstring(L, -1, &len);
  std::string text(s, len);
  lua_pop(L, 1);
  return text;
}

double checkNumber(lua_State* L, int idx, const char* what) {
  int isnum = 0;
  double v = lua_tonumberx(L, idx, &isnum);
  if (!isnum) throw LuaArgError(std::string(what) + ": expected a number, got " + luaL_typename(L, idx));
  if (!std::isfinite(v)) throw LuaArgError(std::string(what) + ": expected a finite number, got " + std::to_string(v));
  return v;
}

Vec3 checkVec3(lua_State* L, int idx, const char* what) {
  idx = lua_absindex(L, idx);
  if (!lua_istable(L, idx))
    throw LuaArgError(std::string(what) + ": expected a vector {x, y, z}, got " + luaL_typename(L, idx));
  Vec3 v;
  static const char* names[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    int t = lua_rawgeti(L, idx, i + 1);
    if (t == LUA_TNIL) {
      lua_pop(L, 1);
      t = rawGetField(L, idx, names[i]);
    }
    int isnum = 0;
    double c = lua_tonumberx(L, -1, &isnum);
    lua_pop(L, 1);
    if (!isnum || !std::isfinite(c))
      throw LuaArgError(std::string(what) + ": component " + names[i] + " must be a finite number");
    v[i] = Real(c);
    // 1e300 is a finite double but inf as the world's float.
    if (!std::isfinite(v[i]))
      throw LuaArgError(std::string(what) + ": component " + names[i] + " must be a finite number the world can store (" +
                        std::to_string(c) + " is beyond float's 3.4e38)");
  }
  return v;
}

double optNumberField(lua_State* L, int tableIdx, const char* key, double fallback) {
  int t = rawGetField(L, tableIdx, key);
  if (t == LUA_TNIL) {
    lua_pop(L, 1);
    return fallback;
  }
  int isnum = 0;
  double v = lua_tonumberx(L, -1, &isnum);
  std::string type = luaL_typename(L, -1);
  lua_pop(L, 1);
  if (!isnum) throw LuaArgError(std::string("field '") + key + "': expected a number, got " + type);
  if (!std::isfinite(v)) throw LuaArgError(std::string("field '") + key + "': expected a finite number");
  return v;
}

bool optBoolField(lua_State* L, int tableIdx, const char* key, bool fallback) {
  int t = rawGetField(L, tableIdx, key);
  if (t == LUA_TNIL) {
    lua_pop(L, 1);
    return fallback;
  }
  if (t != LUA_TBOOLEAN) {
    std::string type = luaL_typename(L, -1);
    lua_pop(L, 1);
    throw LuaArgError(std::string("field '") + key + "': expected true or false, got " + type);
  }
  bool v = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return v;
}

std::string optStringField(lua_State* L, int tableIdx, const char* key, const std::string& fallback) {
  int t = rawGetField(L, tableIdx, key);
  if (t == LUA_TNIL) {
    lua_pop(L, 1);
    return fallback;
  }
  if (t != LUA_TSTRING) {
    std::string type = luaL_typename(L, -1);
    lua_pop(L, 1);
    throw LuaArgError(std::string("field '") + key + "': expected a string, got " + type);
  }
  std::string v = lua_tostring(L, -1);
  lua_pop(L, 1);
  return v;
}

bool optVec3Field(lua_State* L, int tableIdx, const char* key, Vec3* out) {
  tableIdx = lua_absindex(L, tableIdx);
  int t = rawGetField(L, tableIdx, key);
  if (t == LUA_TNIL) {
    lua_pop(L, 1);
    return false;
  }
  try {
    *out = checkVec3(L, -1, (std::string("field '") + key + "'").c_str());
  } catch (...) {
    lua_pop(L, 1);
    throw;
  }
  lua_pop(L, 1);
  return true;
}

Quat optRotationField(lua_State* L, int tableIdx, const char* key) {
  Vec3 rv = Vec3::Zero();
  optVec3Field(L, tableIdx, key, &rv);
  const Real angle = rv.norm();
  return angle > 0 ? Quat(Eigen::AngleAxis<Real>(angle, rv / angle)) : Quat::Identity();
}

void pushVec3(lua_State* L, const Vec3& v) {
  lua_createtable(L, 0, 3);
  lua_pushnumber(L, v.x());
  rawSetField(L, -2, "x");
  lua_pushnumber(L, v.y());
  rawSetField(L, -2, "y");
  lua_pushnumber(L, v.z());
  rawSetField(L, -2, "z");
}

namespace {
std::string validList(const std::set<std::string>& allowed) {
  std::string valid;
  for (const auto& f : allowed) valid += (valid.empty() ? "" : ", ") + f;
  return valid;
}
}  // namespace

std::string unknownFieldMessage(const std::string& key, const std::set<std::string>& allowed) {
  const std::vector<std::string> names(allowed.begin(), allowed.end());
  return "unknown field '" + key + "'" + input::didYouMean(key, names) + " (valid: " + validList(allowed) + ")";
}

void checkFields(lua_State* L, int t, const std::string& where, const std::set<std::string>& allowed) {
  t = lua_absindex(L, t);
  lua_pushnil(L);
  while (lua_next(L, t) != 0) {
    lua_pop(L, 1);
    if (lua_type(L, -1) != LUA_TSTRING) {
      const std::string type = luaL_typename(L, -1);
      lua_pop(L, 1);
      throw LuaArgError(where + ": a " + type + " key where a field name is expected (valid: " + validList(allowed) +
                        ")");
    }
    const std::string key = lua_tostring(L, -1);
    if (allowed.count(key) == 0) {
      lua_pop(L, 1);
      throw LuaArgError(where + ": " + unknownFieldMessage(key, allowed));
    }
  }
}

void checkStackBalance(lua_State* L, int argsOnEntry, int results, const char* binding) {
  const int top = lua_gettop(L);
  if (results >= 0 && results <= top && top <= argsOnEntry + results) return;
  std::fprintf(stderr, "Lua stack imbalance in %s: %d arguments, %d results, %d values on the stack at return "
                       "(pop what the binding pushed besides its results)\n",
               binding, argsOnEntry, results, top);
  std::abort();
}

void registerType(lua_State* L, const BoundType& type) {
  luaL_newmetatable(L, type.metatable);
  lua_newtable(L);
  luaL_setfuncs(L, type.methods, 0);
  rawSetField(L, -2, "__index");
  if (type.toString) {
    lua_pushcfunction(L, type.toString);
    rawSetField(L, -2, "__tostring");
  }
  if (type.equals) {
    lua_pushcfunction(L, type.equals);
    rawSetField(L, -2, "__eq");
  }
  if (type.collect) {
    lua_pushcfunction(L, type.collect);
    rawSetField(L, -2, "__gc");
  }
  lua_pushboolean(L, 0);
  rawSetField(L, -2, "__metatable");  // scripts cannot swap the methods
  lua_pop(L, 1);
}

void registerModule(lua_State* L, int envIndex, const char* name, const luaL_Reg* functions) {
  envIndex = lua_absindex(L, envIndex);
  lua_newtable(L);
  luaL_setfuncs(L, functions, 0);
  rawSetField(L, envIndex, name);
}

void registerFunctions(lua_State* L, int tableIndex, const luaL_Reg* functions) {
  tableIndex = lua_absindex(L, tableIndex);
  for (const luaL_Reg* f = functions; f->name; ++f) {
    lua_pushcfunction(L, f->func);
    rawSetField(L, tableIndex, f->name);
  }
}

}  // namespace tumble::script
