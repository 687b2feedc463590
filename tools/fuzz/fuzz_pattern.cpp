// Lua patterns: the step counter (script/internal/pattern_cost.h) against
// Lua's own string.find, differentially. The input is a pattern, a 0 byte,
// then the subject. The counter must find what Lua finds (same match, same
// error), and whenever it counted at most the cap, Lua's own search must
// finish: the cap is what makes the sandbox's matches bounded.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

extern "C" {
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
}

#include "script/internal/pattern_cost.h"

namespace {
lua_State* plainLua() {
  static lua_State* L = [] {
    lua_State* s = luaL_newstate();
    luaL_openlibs(s);
    return s;
  }();
  return L;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const char* text = reinterpret_cast<const char*>(data);
  const char* zero = static_cast<const char*>(std::memchr(text, 0, size));
  if (!zero) return 0;
  const std::string pattern(text, zero), subject(zero + 1, text + size);
  // Lua's find does a plain substring search for a pattern without special
  // characters (the sandbox charges that separately): nothing to compare.
  if (tumble::script::patternHasNoSpecials(pattern)) return 0;
  constexpr std::uint64_t kCap = 200'000;
  tumble::script::PatternCost pc(subject, pattern, kCap);
  const bool anchor = !pattern.empty() && pattern[0] == '^';
  long long start = -1, end = -1;
  std::size_t at = 0;
  do {
    const long long e = pc.matchAt(at, anchor ? 1 : 0);
    if (pc.stopped()) break;
    if (e >= 0) {
      if (pc.unfinishedCapture()) {  // Lua raises "unfinished capture" on returning it
        start = -2;
        break;
      }
      start = (long long)at;
      end = e;
      break;
    }
  } while (at++ < subject.size() && !anchor);
  if (pc.stopped() && pc.cost() > kCap) return 0;  // too costly: the sandbox never runs Lua's search
  lua_State* L = plainLua();
  lua_getglobal(L, "string");
  lua_getfield(L, -1, "find");
  lua_pushlstring(L, subject.data(), subject.size());
  lua_pushlstring(L, pattern.data(), pattern.size());
  const bool error = lua_pcall(L, 2, 2, 0) != LUA_OK;
  if (error != (pc.stopped() || start == -2)) std::abort();  // the counter and Lua disagree on a malformed pattern
  if (!error) {
    const long long luaStart = lua_isnil(L, -2) ? -1 : lua_tointeger(L, -2) - 1;
    const long long luaEnd = lua_isnil(L, -2) ? -1 : lua_tointeger(L, -1);
    if (luaStart != start || luaEnd != end) std::abort();  // another match than Lua's
    lua_pop(L, 3);
  } else {
    lua_pop(L, 2);
  }
  return 0;
}
