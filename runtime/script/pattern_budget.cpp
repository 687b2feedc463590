#include "script/internal/pattern_budget.h"

#include <string_view>

#include "script/internal/pattern_cost.h"
#include "script/lua_vm.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace tumble::script {

namespace {

// Upvalues of the find, match and gsub wrappers: 1 Lua's function, 2 the LuaVm.
LuaVm* vmOf(lua_State* L, int upvalue) { return static_cast<LuaVm*>(lua_touserdata(L, lua_upvalueindex(upvalue))); }

// Lua's start position rule for find, match and gmatch (1-based; negative
// counts from the end), as a 0-based offset; may be past the end.
std::size_t startOffset(lua_Integer init, std::size_t len) {
  if (init > 0) return std::size_t(init) - 1;
  if (init == 0 || init < -lua_Integer(len)) return 0;
  return len + std::size_t(init + 1) - 1;
}

// Charges `cost` or raises the budget error. `exceeded`: the count passed
// what was left (the match is then not run).
void chargeOrRaise(lua_State* L, LuaVm* vm, const PatternCost& pc, std::uint64_t cap, const char* fn) {
  if (!pc.stopped() || pc.cost() <= cap) {
    if (vm->charge(L, pc.cost())) return;
  } else {
    vm->charge(L, pc.cost());  // marks the budget as hit
  }
  luaL_error(L,
             "string.%s: the pattern match needs more than the %I steps left of the call's budget of %I "
             "instructions (a pattern that backtracks on a long subject?); it was not run",
             fn, lua_Integer(cap), lua_Integer(vm->limits().instructionsPerCall));
}

// Calls Lua's own function (upvalue 1) with the arguments as given.
int callOriginal(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// The steps of a search from offset `from` as find, match and gsub make it:
// each start position in turn (only the first with a leading '^').
int findOrMatch(lua_State* L, bool find, const char* fn) {
  std::size_t ls = 0, lp = 0;
  const char* s = luaL_checklstring(L, 1, &ls);
  const char* p = luaL_checklstring(L, 2, &lp);
  const std::size_t init = startOffset(luaL_optinteger(L, 3, 1), ls);
  LuaVm* vm = vmOf(L, 2);
  const std::uint64_t cap = vm->instructionsLeft();
  PatternCost pc({s, ls}, {p, lp}, cap);
  if (init <= ls) {
    const std::string_view pattern(p, lp);
    if (find && (lua_toboolean(L, 4) || patternHasNoSpecials(pattern))) {
      // A plain substring search: at most one comparison of the pattern per position.
      pc.add(1 + (ls - init + 1) * (lp / 16 + 1));
    } else {
      const bool anchor = lp > 0 && p[0] == '^';
      std::size_t at = init;
      do {
        if (pc.matchAt(at, anchor ? 1 : 0) >= 0 || pc.stopped()) break;
      } while (at++ < ls && !anchor);
    }
  }
  chargeOrRaise(L, vm, pc, cap, fn);
  return callOriginal(L);
}

int budgetedFind(lua_State* L) { return findOrMatch(L, true, "find"); }
int budgetedMatch(lua_State* L) { return findOrMatch(L, false, "match"); }

int budgetedGsub(lua_State* L) {
  std::size_t ls = 0, lp = 0;
  const char* s = luaL_checklstring(L, 1, &ls);
  const char* p = luaL_checklstring(L, 2, &lp);
  const lua_Integer maxN = luaL_optinteger(L, 4, lua_Integer(ls) + 1);
  // Each replacement copies the replacement text (or the captures for a
  // function or table, whose own work is Lua and counted).
  std::size_t lr = 0;
  if (lua_type(L, 3) == LUA_TSTRING || lua_type(L, 3) == LUA_TNUMBER) lua_tolstring(L, 3, &lr);
  LuaVm* vm = vmOf(L, 2);
  const std::uint64_t cap = vm->instructionsLeft();
  PatternCost pc({s, ls}, {p, lp}, cap);
  const bool anchor = lp > 0 && p[0] == '^';
  std::size_t src = 0;
  long long lastMatch = -1;
  for (lua_Integer n = 0; n < maxN;) {
    const long long e = pc.matchAt(src, anchor ? 1 : 0);
    if (pc.stopped()) break;
    if (e >= 0 && e != lastMatch) {
      ++n;
      pc.add(1 + lr);
      src = std::size_t(e);
      lastMatch = e;
    } else if (src < ls) {
      ++src;
    } else {
      break;
    }
    if (anchor) break;
  }
  chargeOrRaise(L, vm, pc, cap, "gsub");
  return callOriginal(L);
}

// gmatch's iterator: upvalues 1 Lua's iterator, 2 the LuaVm, 3 the subject,
// 4 the pattern, 5 the next start offset, 6 the last match's end (-1: none),
// mirroring the state of Lua's iterator so each call counts its own search.
int budgetedGmatchStep(lua_State* L) {
  std::size_t ls = 0, lp = 0;
  const char* s = lua_tolstring(L, lua_upvalueindex(3), &ls);
  const char* p = lua_tolstring(L, lua_upvalueindex(4), &lp);
  std::size_t src = std::size_t(lua_tointeger(L, lua_upvalueindex(5)));
  LuaVm* vm = vmOf(L, 2);
  const std::uint64_t cap = vm->instructionsLeft();
  PatternCost pc({s, ls}, {p, lp}, cap);
  const long long lastMatch = lua_tointeger(L, lua_upvalueindex(6));
  for (; src <= ls; ++src) {
    const long long e = pc.matchAt(src, 0);
    if (pc.stopped()) break;
    if (e >= 0 && e != lastMatch) {
      lua_pushinteger(L, e);
      lua_replace(L, lua_upvalueindex(5));
      lua_pushinteger(L, e);
      lua_replace(L, lua_upvalueindex(6));
      break;
    }
  }
  chargeOrRaise(L, vm, pc, cap, "gmatch");
  lua_settop(L, 0);
  return callOriginal(L);
}

int budgetedGmatch(lua_State* L) {
  std::size_t ls = 0;
  luaL_checklstring(L, 1, &ls);
  luaL_checkstring(L, 2);
  std::size_t init = startOffset(luaL_optinteger(L, 3, 1), ls);
  if (init > ls) init = ls + 1;
  const bool hasInit = !lua_isnoneornil(L, 3);
  lua_pushvalue(L, lua_upvalueindex(1));  // Lua's gmatch makes its iterator
  lua_pushvalue(L, 1);
  lua_pushvalue(L, 2);
  if (hasInit) {
    lua_pushvalue(L, 3);
    lua_call(L, 3, 1);
  } else {
    lua_call(L, 2, 1);
  }
  lua_pushvalue(L, lua_upvalueindex(2));
  lua_pushvalue(L, 1);
  lua_pushvalue(L, 2);
  lua_pushinteger(L, lua_Integer(init));
  lua_pushinteger(L, -1);
  lua_pushcclosure(L, &budgetedGmatchStep, 6);
  return 1;
}

}  // namespace

void installPatternBudget(lua_State* L, LuaVm* vm) {
  lua_getglobal(L, "string");
  const struct {
    const char* name;
    lua_CFunction fn;
  } wrapped[] = {{"find", &budgetedFind}, {"match", &budgetedMatch}, {"gsub", &budgetedGsub}, {"gmatch", &budgetedGmatch}};
  for (const auto& w : wrapped) {
    lua_getfield(L, -1, w.name);
    lua_pushlightuserdata(L, vm);
    lua_pushcclosure(L, w.fn, 2);
    lua_setfield(L, -2, w.name);
  }
  lua_pop(L, 1);
}

}  // namespace tumble::script
