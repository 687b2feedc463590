#include "script/definition_fields.h"

#include <cmath>
#include <cstdio>

#include "script/internal/lua_util.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace tumble::script {

std::string unknownFieldText(const std::string& key, const std::set<std::string>& names) {
  return unknownFieldMessage(key, names);
}

namespace fields {

namespace {
std::string typeName(lua_State* L, int idx) { return luaL_typename(L, idx); }

bool finiteNumberAt(lua_State* L, int idx, Real* out) {
  if (lua_type(L, idx) != LUA_TNUMBER) return false;
  const double v = lua_tonumber(L, idx);
  if (!std::isfinite(v)) return false;
  *out = Real(v);
  return true;
}
}  // namespace

Real readNumber(lua_State* L, const std::string& path, const char* unit) {
  Real v = 0;
  if (!finiteNumberAt(L, -1, &v))
    throw FieldError(path + ": expected a finite number" + (*unit ? std::string(" (") + unit + ")" : std::string()) +
                     ", got " + (lua_type(L, -1) == LUA_TNUMBER ? std::to_string(lua_tonumber(L, -1)) : typeName(L, -1)));
  return v;
}

bool readBool(lua_State* L, const std::string& path) {
  if (lua_type(L, -1) != LUA_TBOOLEAN) throw FieldError(path + ": expected true or false, got " + typeName(L, -1));
  return lua_toboolean(L, -1);
}

std::string readString(lua_State* L, const std::string& path) {
  if (lua_type(L, -1) != LUA_TSTRING) throw FieldError(path + ": expected a string, got " + typeName(L, -1));
  std::size_t n = 0;
  const char* s = lua_tolstring(L, -1, &n);
  return std::string(s, n);
}

std::vector<Real> readNumbers(lua_State* L, const std::string& path) {
  if (!lua_istable(L, -1)) throw FieldError(path + ": expected a list of numbers, got " + typeName(L, -1));
  std::vector<Real> v;
  const lua_Integer n = lua_Integer(lua_rawlen(L, -1));
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, -1, i);
    Real x = 0;
    const bool ok = finiteNumberAt(L, -1, &x);
    lua_pop(L, 1);
    if (!ok) throw FieldError(path + ": item " + std::to_string(i) + " is not a finite number");
    v.push_back(x);
  }
  return v;
}

Vec3 readVec3(lua_State* L, const std::string& path, const char* unit) {
  std::vector<Real> v;
  try {
    v = readNumbers(L, path);
  } catch (const FieldError&) {
    v.clear();
  }
  if (v.size() != 3) throw FieldError(path + ": expected three numbers {x, y, z} (" + unit + ")");
  return Vec3(v[0], v[1], v[2]);
}

vehicle::Curve readCurve(lua_State* L, const std::string& path, const char* xUnit, const char* yUnit) {
  const std::string form =
      std::string("expected a list of points {{x, y}, ...} with x in ") + xUnit + " and y in " + yUnit;
  if (!lua_istable(L, -1)) throw FieldError(path + ": " + form);
  std::vector<std::pair<Real, Real>> pts;
  const lua_Integer n = lua_Integer(lua_rawlen(L, -1));
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, -1, i);
    Real x = 0, y = 0;
    bool ok = lua_istable(L, -1) && lua_rawlen(L, -1) == 2;
    if (ok) {
      lua_rawgeti(L, -1, 1);
      lua_rawgeti(L, -2, 2);
      ok = finiteNumberAt(L, -2, &x) && finiteNumberAt(L, -1, &y);
      lua_pop(L, 2);
    }
    lua_pop(L, 1);
    if (!ok) throw FieldError(path + ": point " + std::to_string(i) + ": " + form);
    pts.emplace_back(x, y);
  }
  return vehicle::Curve(std::move(pts));
}

void pushNumber(lua_State* L, double v) { lua_pushnumber(L, v); }
void pushBool(lua_State* L, bool v) { lua_pushboolean(L, v); }
void pushString(lua_State* L, const std::string& v) { lua_pushlstring(L, v.data(), v.size()); }

void pushVec3(lua_State* L, const Vec3& v) {
  lua_createtable(L, 3, 0);
  for (int i = 0; i < 3; ++i) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, i + 1);
  }
}

void pushNumbers(lua_State* L, const std::vector<Real>& v) {
  lua_createtable(L, int(v.size()), 0);
  for (std::size_t i = 0; i < v.size(); ++i) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, lua_Integer(i + 1));
  }
}

void pushCurve(lua_State* L, const vehicle::Curve& c) {
  lua_createtable(L, int(c.points().size()), 0);
  int i = 1;
  for (const auto& [x, y] : c.points()) {
    lua_createtable(L, 2, 0);
    lua_pushnumber(L, x);
    lua_rawseti(L, -2, 1);
    lua_pushnumber(L, y);
    lua_rawseti(L, -2, 2);
    lua_rawseti(L, -2, i++);
  }
}

void forEachKey(lua_State* L, const std::string& path, const std::function<void(const std::string&)>& each) {
  if (!lua_istable(L, -1))
    throw FieldError((path.empty() ? std::string() : path + ": ") + "expected a table, got " + typeName(L, -1));
  const int t = lua_gettop(L);
  lua_pushnil(L);
  while (lua_next(L, t) != 0) {
    lua_pop(L, 1);
    if (lua_type(L, -1) != LUA_TSTRING) {
      const std::string type = typeName(L, -1);
      lua_settop(L, t);
      throw FieldError((path.empty() ? std::string() : path + ": ") + "a " + type +
                       " key where a field name is expected (fields are name = value)");
    }
    std::size_t n = 0;
    const char* s = lua_tolstring(L, -1, &n);
    try {
      each(std::string(s, n));
    } catch (...) {
      lua_settop(L, t);
      throw;
    }
  }
}

bool getRaw(lua_State* L, const char* key) {
  lua_pushstring(L, key);
  if (lua_rawget(L, -2) == LUA_TNIL) {
    lua_pop(L, 1);
    return false;
  }
  return true;
}

void pop(lua_State* L) { lua_pop(L, 1); }
void newTable(lua_State* L) { lua_newtable(L); }
void setField(lua_State* L, const char* key) { rawSetField(L, -2, key); }
void setIndex(lua_State* L, int i) { lua_rawseti(L, -2, i); }

int listLength(lua_State* L, const std::string& path, const char* form) {
  if (!lua_istable(L, -1)) throw FieldError(path + ": expected " + form + ", got " + typeName(L, -1));
  return int(lua_rawlen(L, -1));
}

void getItem(lua_State* L, int i) { lua_rawgeti(L, -1, i); }

std::string showNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string showNumbers(const std::vector<Real>& v) {
  std::string out = "{";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) out.append(", ");
    out.append(showNumber(v[i]));
  }
  out.append("}");
  return out;
}

std::string showVec3(const Vec3& v) { return showNumbers({v.x(), v.y(), v.z()}); }

std::string quoted(const std::string& text) {
  std::string out;
  out.reserve(text.size() + 2);
  out.push_back('"');
  out.append(text);
  out.push_back('"');
  return out;
}

}  // namespace fields
}  // namespace tumble::script
