// Pattern matching under the instruction budget (script/internal/
// pattern_budget.h): the step counter walks the same search as Lua's own
// matcher (same matches, same errors), the wrapped functions give the same
// results as Lua's, and a match too big for the budget is refused quickly
// instead of running for ages.
#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <string>
#include <vector>

extern "C" {
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
}

#include "script/internal/pattern_cost.h"
#include "script/lua_vm.h"
#include "script_fixture.h"

namespace tumble::test {
namespace {

struct FindResult {
  bool error = false;
  long long start = -1, end = -1;  // 0-based start, end offset; -1: no match
  bool operator==(const FindResult&) const = default;
};

std::ostream& operator<<(std::ostream& os, const FindResult& r) {
  return os << (r.error ? "error" : r.start < 0 ? "no match" : std::to_string(r.start) + ".." + std::to_string(r.end));
}

// string.find(s, p) in a plain Lua state: the reference.
FindResult luaFind(lua_State* L, const std::string& s, const std::string& p) {
  lua_getglobal(L, "string");
  lua_getfield(L, -1, "find");
  lua_pushlstring(L, s.data(), s.size());
  lua_pushlstring(L, p.data(), p.size());
  FindResult r;
  if (lua_pcall(L, 2, 2, 0) != LUA_OK) {
    r.error = true;
    lua_pop(L, 2);
    return r;
  }
  if (!lua_isnil(L, -2)) {
    r.start = lua_tointeger(L, -2) - 1;
    r.end = lua_tointeger(L, -1);
  }
  lua_pop(L, 3);
  return r;
}

// The same search walked by the counter: each start position in turn. A
// pattern without special characters is a plain substring search in Lua
// (a lone ')' is not special there), so it is one here too.
FindResult counterFind(const std::string& s, const std::string& p) {
  if (script::patternHasNoSpecials(p)) {
    const std::size_t at = s.find(p);
    return at == std::string::npos ? FindResult{} : FindResult{false, (long long)at, (long long)(at + p.size())};
  }
  script::PatternCost pc(s, p, 100'000'000);
  const bool anchor = !p.empty() && p[0] == '^';
  std::size_t at = 0;
  do {
    const long long e = pc.matchAt(at, anchor ? 1 : 0);
    if (pc.stopped()) return FindResult{true};
    if (e >= 0 && pc.unfinishedCapture()) return FindResult{true};  // Lua: "unfinished capture"
    if (e >= 0) return FindResult{false, (long long)at, e};
  } while (at++ < s.size() && !anchor);
  return FindResult{};
}

TEST(PatternCost, FindsWhatLuaFindsOnHandPickedPatterns) {
  lua_State* L = luaL_newstate();
  luaL_openlibs(L);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"hello world", "o w"},          {"hello world", "^hello"},      {"hello world", "world$"},
      {"key = value", "(%w+)%s*=%s*(%w+)"},                             {"aaab", "a-b"},
      {"aaab", "a*b"},                 {"aaab", "a+b"},                {"ab", "a?b"},
      {"b", "a?b"},                    {"f(a(b)c)d", "%b()"},          {"f(a(b", "%b()"},
      {"THE (quick) fox", "%f[%a]%a+"}, {"abcabc", "(abc)%1"},         {"abab", "(a)(b)%2"},
      {"x", "%"},                      {"x", "[a"},                    {"x", "(x"},
      {"x", "x)"},                     {"x", "%1"},                    {"x", "%b"},
      {"x", "%fx"},                    {"a.b", "%."},                  {"a]b", "[]]"},
      {"a-b", "[a%-]+"},               {"a^b", "[%^b]+"},              {"abc", "[^a]+"},
      {"12ab", "%d+%a"},               {"  x", "%S"},                  {"", ""},
      {"", "a*"},                      {"abc", "()b()"},               {"$", "$"},
      {"a$b", "a$b"},                  {"aaa", "^(a-)a$"},             {"hello", "[h-l]+"},
      {"a\0b", std::string("\0", 1)},  {"xyz", ".-$"},                 {"ab", "(((((a)))))b"},
  };
  for (const auto& [s, p] : cases) EXPECT_EQ(counterFind(s, p), luaFind(L, s, p)) << "s=\"" << s << "\" p=\"" << p << "\"";
  lua_close(L);
}

// Random patterns of every kind of item over a small alphabet, so that
// matches, failures, backtracking and malformed patterns all occur.
TEST(PatternCost, FindsWhatLuaFindsOnRandomPatterns) {
  lua_State* L = luaL_newstate();
  luaL_openlibs(L);
  std::mt19937 rng(12345);
  const std::vector<std::string> items = {"a", "b", "(", ")", "%a", "%d", "%s", ".", "[ab]", "[^a]", "[a-c]", "%b()",
                                          "%f[a]", "%1", "%2", "%z", "*", "+", "-", "?", "$", "^", "()", "%", "[", "]", "1"};
  const std::string alphabet = "ab1 ()c";
  int matched = 0, errors = 0;
  for (int k = 0; k < 20000; ++k) {
    std::string p, s;
    const int np = int(rng() % 7) + 1, ns = int(rng() % 12);
    for (int i = 0; i < np; ++i) p += items[rng() % items.size()];
    for (int i = 0; i < ns; ++i) s += alphabet[rng() % alphabet.size()];
    const FindResult want = luaFind(L, s, p);
    matched += want.start >= 0;
    errors += want.error;
    ASSERT_EQ(counterFind(s, p), want) << "s=\"" << s << "\" p=\"" << p << "\"";
  }
  // The random set exercised all three outcomes.
  EXPECT_GT(matched, 1000);
  EXPECT_GT(errors, 1000);
  lua_close(L);
}

// The wrapped functions return what Lua's own return (the sandbox changes
// only when they may run, never what they compute).
TEST(PatternBudget, ResultsAreLuasOwn) {
  const char* chunk = R"lua(
    local out = {}
    local function add(...) local t = table.pack(...) for i = 1, t.n do out[#out + 1] = tostring(t[i]) end out[#out + 1] = "|" end
    local s = "key1 = value1, key2 = value2; (nested (parens)) end"
    add(s:find("(%w+)%s*=%s*(%w+)"))
    add(s:find("(%w+)%s*=%s*(%w+)", 10))
    add(s:find("(%w+)%s*=%s*(%w+)", -10))
    add(s:find("key2", 1, true))
    add(s:find(".", 1, true))
    add(s:match("%b()"))
    add(s:match("^(%w+)()"))
    add(s:gsub("%w+", "<%0>"))
    add(s:gsub("(%w+)=(%w+)", "%2=%1", 1))
    add(s:gsub("", "-"))
    add(s:gsub("%s", {[" "] = "_"}))
    add(s:gsub("%a+", function(w) return w:upper() end, 3))
    for k, v in s:gmatch("(%w+)%s*=%s*(%w+)") do add(k, v) end
    for w in s:gmatch("%a*") do add(w) end
    for w in s:gmatch("%a+", 20) do add(w) end
    add(pcall(string.find, s, "[a"))
    add(pcall(string.gsub, s, "(", "x"))
    return table.concat(out, " ")
  )lua";
  auto runIn = [&](lua_State* L) {
    EXPECT_EQ(luaL_dostring(L, chunk), LUA_OK) << lua_tostring(L, -1);
    std::string r = lua_tostring(L, -1);
    lua_pop(L, 1);
    return r;
  };
  lua_State* plain = luaL_newstate();
  luaL_openlibs(plain);
  script::LuaVm vm;
  EXPECT_EQ(runIn(vm.state()), runIn(plain));
  lua_close(plain);
}

class PatternBudgetScenario : public ScriptTest {};

// A match that would run for ages is refused in well under a second, with
// a message that names the function; the scenario goes on.
TEST_F(PatternBudgetScenario, AnExplodingMatchIsRefusedQuickly) {
  auto host = load(R"(
    local later = false
    return {
      on_start = function(ctx)
        local s = string.rep("a", 40)
        s:find(string.rep("a*", 40) .. "b")
      end,
      on_update = function(ctx) later = true end,
      on_finish = function(ctx) expect("later callbacks run", later) end,
    })");
  ASSERT_TRUE(host);
  const auto t0 = std::chrono::steady_clock::now();
  run(*host, 2);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_FALSE(host->errors().empty());
  // The refusal marks the budget as hit, so the error is the budget's.
  EXPECT_NE(host->errors().front().summary().find("exceeded"), std::string::npos) << host->errors().front().summary();
  const script::Expectation* later = expectation(*host, "later callbacks run");
  ASSERT_NE(later, nullptr);
  EXPECT_TRUE(later->ok);
  // The default budget (5e7 steps) counted, not the match run: a few
  // hundred ms at most even on a loaded machine.
  EXPECT_LT(s, 10.0);
}

// Matching is charged: a loop of ordinary matches runs out of budget like
// any loop, although each match alone is small.
TEST_F(PatternBudgetScenario, MatchesCountAgainstTheBudget) {
  script::VmLimits limits;
  limits.instructionsPerCall = 2'000'000;
  auto host = load(R"(
    return {on_start = function(ctx)
      local s = string.rep("y", 10000)
      for i = 1, 100 do s:find(".-x") end  -- each about 5e7 steps: the first one cannot run
    end})",
                   limits);
  ASSERT_TRUE(host);
  run(*host, 1);
  ASSERT_FALSE(host->errors().empty());
  EXPECT_NE(host->errors().front().summary().find("exceeded 2000000 instructions"), std::string::npos)
      << host->errors().front().summary();

  auto small = load(R"(
    return {on_start = function(ctx)
      local s = string.rep("y", 100) .. "x"
      local n = 0
      for i = 1, 10 do if s:find(".-x") then n = n + 1 end end
      expect("ten small matches fit", n == 10)
    end})",
                    limits);
  ASSERT_TRUE(small);
  run(*small, 1);
  EXPECT_TRUE(small->errors().empty()) << small->errors().front().message;
  const script::Expectation* ok = expectation(*small, "ten small matches fit");
  ASSERT_NE(ok, nullptr);
  EXPECT_TRUE(ok->ok);
}

}  // namespace
}  // namespace tumble::test
