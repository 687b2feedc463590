#pragma once
// Raw table access for every value C++ reads from or writes to Lua.
//
// lua_getfield / lua_setfield / luaL_len run a table's __index, __newindex
// and __len metamethods, and a mod can put those on any table it hands to
// C++ (options, vectors, definitions, ctx, the scenario table). A metamethod
// that raises would longjmp through C++ frames (skipping destructors); one
// that removes a body would run while C++ holds that body's id. So C++ reads
// and writes tables raw, here, and only ever sees the values really stored.
extern "C" {
#include <lua.h>
}

namespace tumble::script {

/// Pushes t[key] without metamethods and returns its type. A value that is
/// not a table reads as nil, except userdata of the runtime's own types
/// (their metatables are protected, so their __index is the runtime's).
inline int rawGetField(lua_State* L, int idx, const char* key) {
  idx = lua_absindex(L, idx);
  const int type = lua_type(L, idx);
  if (type == LUA_TUSERDATA) return lua_getfield(L, idx, key);
  if (type != LUA_TTABLE) {
    lua_pushnil(L);
    return LUA_TNIL;
  }
  lua_pushstring(L, key);
  return lua_rawget(L, idx);
}

/// t[key] = value on top (popped), without metamethods; t is a table.
inline void rawSetField(lua_State* L, int idx, const char* key) {
  idx = lua_absindex(L, idx);
  if (lua_type(L, idx) != LUA_TTABLE) {
    lua_setfield(L, idx, key);  // never reached with user tables: C++ only writes tables
    return;
  }
  lua_pushstring(L, key);
  lua_insert(L, -2);
  lua_rawset(L, idx);
}

/// The border of a table without __len (0 for a value that is not a table).
inline lua_Integer rawLength(lua_State* L, int idx) {
  return lua_type(L, idx) == LUA_TTABLE ? lua_Integer(lua_rawlen(L, idx)) : 0;
}

}  // namespace tumble::script
