#include "script/internal/lua_util.h"

#include <cmath>

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
      t = lua_getfield(L, idx, names[i]);
    }
    int isnum = 0;
    double c = lua_tonumberx(L, -1, &isnum);
    lua_pop(L, 1);
    if (!isnum || !std::isfinite(c))
      throw LuaArgError(std::string(what) + ": component " + names[i] + " must be a finite number");
    v[i] = Real(c);
  }
  return v;
}

double optNumberField(lua_State* L, int tableIdx, const char* key, double fallback) {
  int t = lua_getfield(L, tableIdx, key);
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
  int t = lua_getfield(L, tableIdx, key);
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
  int t = lua_getfield(L, tableIdx, key);
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
  int t = lua_getfield(L, tableIdx, key);
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

void pushVec3(lua_State* L, const Vec3& v) {
  lua_createtable(L, 0, 3);
  lua_pushnumber(L, v.x());
  lua_setfield(L, -2, "x");
  lua_pushnumber(L, v.y());
  lua_setfield(L, -2, "y");
  lua_pushnumber(L, v.z());
  lua_setfield(L, -2, "z");
}

void checkOptionFields(lua_State* L, int t, const std::string& fn, const std::set<std::string>& allowed) {
  lua_pushnil(L);
  while (lua_next(L, t) != 0) {
    lua_pop(L, 1);
    const std::string key = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : std::string("?");
    if (allowed.count(key) == 0) {
      lua_pop(L, 1);
      std::string valid;
      for (const auto& f : allowed) valid += (valid.empty() ? "" : ", ") + f;
      throw LuaArgError(fn + ": unknown option '" + key + "' (valid: " + valid + ")");
    }
  }
}

}  // namespace tumble::script
