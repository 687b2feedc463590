// Sandbox escapes: each attempt fails with an error that says what
// is not allowed, names the mod, file and line, and the host keeps working —
// a later callback still runs.
#include <cstdio>

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

#include "script_fixture.h"

namespace tumble::test {

namespace {

// The attempt runs in on_start; on_update and on_finish prove the host goes on.
std::string attempt(const std::string& code) {
  return "local updates = 0\n"
         "return {\n"
         "  on_start = function(ctx)\n" +
         code +
         "\n  end,\n"
         "  on_update = function(ctx, dt) updates = updates + 1 end,\n"
         "  on_finish = function(ctx) expect(\"later callbacks still run\", updates == 5) end,\n"
         "}\n";
}

class Sandbox : public ScriptTest {
 protected:
  /// Runs `code` in on_start and checks the first error contains `message`.
  void expectRefused(const std::string& code, const std::string& message, const script::VmLimits& limits = {}) {
    auto host = load(attempt(code), limits);
    ASSERT_TRUE(host);
    run(*host, 5);
    ASSERT_FALSE(host->errors().empty()) << "the attempt did not fail:\n" << code;
    const script::ScriptError& e = host->errors().front();
    EXPECT_NE(e.summary().find(message), std::string::npos) << e.summary();
    EXPECT_EQ(e.mod, "escape");
    EXPECT_EQ(e.file, "scenarios/s.lua") << e.summary();
    EXPECT_EQ(host->errors().size(), 1u) << host->errors().back().summary();
    const script::Expectation* later = expectation(*host, "later callbacks still run");
    ASSERT_NE(later, nullptr);
    EXPECT_TRUE(later->ok);
  }
};

// Lua bytecode for `return 42`, written as a Lua string literal of \ddd escapes.
std::string precompiledChunkLiteral() {
  lua_State* L = luaL_newstate();
  luaL_loadstring(L, "return 42");
  std::string bytes;
  lua_dump(
      L,
      [](lua_State*, const void* p, size_t n, void* ud) {
        static_cast<std::string*>(ud)->append(static_cast<const char*>(p), n);
        return 0;
      },
      &bytes, 0);
  lua_close(L);
  std::string literal = "\"";
  char buf[8];
  for (unsigned char c : bytes) {
    std::snprintf(buf, sizeof buf, "\\%03u", unsigned(c));
    literal += buf;
  }
  return literal + "\"";
}

}  // namespace

TEST_F(Sandbox, IoOpenIsRefused) { expectRefused("io.open('/etc/passwd')", "io is not available to mods"); }

TEST_F(Sandbox, OsExecuteAndExitAreRefusedButClockWorks) {
  expectRefused("assert(os.clock() >= 0 and os.time() > 0)\nos.execute('echo hacked')",
                "os.execute is not available to mods");
  expectRefused("os.exit(1)", "os.exit is not available to mods");
  expectRefused("os.getenv('HOME')", "os.getenv is not available");
}

TEST_F(Sandbox, RequireOfACModuleOrAPathIsRefused) {
  expectRefused("require 'socket.core'", "C modules are not allowed");
  expectRefused("require '../../etc/passwd'", "is not a module name");
  expectRefused("package.loadlib('libc.so.6', 'system')", "package is not available to mods");
}

TEST_F(Sandbox, BinaryChunksAreRefused) {
  expectRefused("local f, msg = load(" + precompiledChunkLiteral() + ")\nassert(f == nil)\nerror(msg)",
                "binary chunks are not allowed in mods");
  expectRefused("load('return 1', 'x', 'b')", "binary chunks are not allowed in mods");
  expectRefused("load('return 1', 'x', 'bt')", "binary chunks are not allowed in mods");
  expectRefused("local f = load(function() return nil end, 'x', 'b')", "binary chunks are not allowed");
  // Text chunks still load, into the mod's own environment.
  auto host = load(attempt("expect('text chunk', load('return world ~= nil')())"));
  run(*host, 5);
  expectAllHeld(*host);
}

TEST_F(Sandbox, StringDumpIsNotReachable) {
  expectRefused("string.dump(function() end)", "string.dump is not available to mods");
  expectRefused("assert(('').dump == nil, 'dump via the string metatable')\nerror('no dump')", "no dump");
}

TEST_F(Sandbox, DebugLibraryIsRefused) {
  expectRefused("debug.sethook()", "debug is not available to mods");
  expectRefused("local info = debug.getinfo(1)", "debug is not available to mods");
}

TEST_F(Sandbox, StringRepMemoryBombHitsTheMemoryBudget) {
  script::VmLimits limits;
  limits.memoryBytes = 32u << 20;
  expectRefused("local s = string.rep('x', 1 << 30)", "on_start exceeded the memory budget of 32 MiB", limits);
  expectRefused("local t = {}\nfor i = 1, 1e9 do t[i] = tostring(i) end", "on_start exceeded the memory budget",
                limits);
  // A bomb caught by pcall and raised again is still reported as one.
  expectRefused("local ok, e = pcall(string.rep, 'x', 1 << 30)\nerror(e, 0)", "exceeded the memory budget",
                limits);
}

TEST_F(Sandbox, InfiniteLoopHitsTheInstructionBudgetWithModFileAndCallback) {
  script::VmLimits limits;
  limits.instructionsPerCall = 1'000'000;
  auto host = load(
      "local n = 0\n"
      "return {\n"
      "  on_update = function(ctx, dt)\n"
      "    n = n + 1\n"
      "    if n == 2 then while true do end end\n"
      "  end,\n"
      "  on_finish = function() expect('updates after the loop', n, {min = 5, max = 5}) end,\n"
      "}\n",
      limits);
  run(*host, 5);
  ASSERT_EQ(host->errors().size(), 1u);
  const script::ScriptError& e = host->errors()[0];
  EXPECT_EQ(e.summary().rfind("mod escape: scenarios/s.lua: on_update exceeded 1000000 instructions", 0), 0u)
      << e.summary();
  EXPECT_EQ(e.line, 5);
  EXPECT_NE(e.message.find("stopped at scenarios/s.lua:5"), std::string::npos) << e.message;
  const script::Expectation* after = expectation(*host, "updates after the loop");
  ASSERT_NE(after, nullptr) << "on_finish did not run";
  EXPECT_TRUE(after->ok) << after->value;
}

TEST_F(Sandbox, ALoopCannotCatchItsOwnBudgetError) {
  script::VmLimits limits;
  limits.instructionsPerCall = 1'000'000;
  expectRefused("while true do pcall(function() while true do end end) end", "on_start exceeded 1000000 instructions",
                limits);
  expectRefused("while true do xpcall(function() while true do end end, function() while true do end end) end",
                "on_start exceeded 1000000 instructions", limits);
  expectRefused("while true do coroutine.resume(coroutine.create(function() while true do end end)) end",
                "on_start exceeded 1000000 instructions", limits);
}

TEST_F(Sandbox, FinalizersAreRefusedBecauseTheyRunWithoutTheBudget) {
  // Lua runs __gc with hooks off: an endless finalizer could not be stopped.
  expectRefused("setmetatable({}, {__gc = function() while true do end end})", "__gc is not available to mods");
  expectRefused("setmetatable({}, {__gc = false})", "__gc is not available to mods");
}

TEST_F(Sandbox, DeepRecursionIsAClearStackOverflow) {
  expectRefused("local function f(n) return f(n + 1) + 1 end\nf(1)", "stack overflow");
  expectRefused("local t = setmetatable({}, {__index = function(t, k) return t[k .. 'x'] end})\nlocal _ = t.a",
                "stack overflow");
}

TEST_F(Sandbox, StringMetatableCannotBeTamperedWith) {
  expectRefused("getmetatable('').__index = {upper = function() return 'evil' end}", "attempt to index a boolean");
  expectRefused("setmetatable('', {})", "table expected");
  // A mod replacing its own string.upper changes neither s:upper() for it nor
  // anything for another mod.
  auto a = load(
      "string.upper = function() return 'evil' end\n"
      "return {on_start = function() expect('method unchanged', ('a'):upper() == 'A') end}",
      {}, "mod_a");
  auto b = load("return {on_start = function() expect('other mod unchanged', string.upper('a') == 'A') end}", {},
                "mod_b");
  run(*a, 1);
  run(*b, 1);
  expectAllHeld(*a);
  expectAllHeld(*b);
}

TEST_F(Sandbox, BodyMetatableIsProtected) {
  expectRefused("setmetatable(world.box{}, {})", "table expected, got tumble.Body");
  expectRefused("assert(getmetatable(world.box{}) == false)\nerror('protected')", "protected");
}

TEST_F(Sandbox, EachModHasItsOwnTables) {
  auto a = load(
      "rawset(world, 'box', function() error('hijacked') end)\n"
      "rawset(_G, 'expect', nil)\n"
      "math.pi = 3\n"
      "return {}",
      {}, "mod_a");
  auto b = load(
      "return {on_start = function()\n"
      "  local box = world.box{position = {0, 5, 0}}\n"
      "  expect('world.box is the real one', box:is_valid())\n"
      "  expect('math.pi untouched', math.pi > 3.14)\n"
      "end}",
      {}, "mod_b");
  run(*a, 1);
  run(*b, 1);
  expectAllHeld(*b);
}

TEST_F(Sandbox, GlobalsTableIsProtectedAndReadsOfUnknownGlobalsAreNil) {
  expectRefused("setmetatable(_G, {})", "cannot change a protected metatable");
  auto host = load(attempt("expect('unknown global is nil', some_global_nobody_set == nil)"));
  run(*host, 5);
  expectAllHeld(*host);
}

TEST_F(Sandbox, CollectGarbageOnlyLooksAndNudges) {
  expectRefused("collectgarbage('stop')", "collectgarbage(\"stop\") is not available to mods");
  expectRefused("collectgarbage('generational')", "is not available to mods");
  auto host = load(attempt(
      "expect('count', collectgarbage('count') > 0)\n"
      "collectgarbage('step')\ncollectgarbage('collect')\n"
      "expect('running', collectgarbage('isrunning'))"));
  run(*host, 5);
  expectAllHeld(*host);
}

TEST_F(Sandbox, RequireFindsModFilesAndRefusesCycles) {
  auto host = load(attempt("expect('lib', require('lib.util').answer == 42)\nrequire 'lib.loop'"), {}, "escape", 1,
                   {{"lib/util.lua", "return {answer = 42}"},
                    {"lib/loop.lua", "return require 'lib.loop2'"},
                    {"lib/loop2.lua", "return require 'lib.loop'"}});
  run(*host, 5);
  ASSERT_EQ(host->errors().size(), 1u);
  EXPECT_NE(host->errors()[0].summary().find("circular require"), std::string::npos) << host->errors()[0].summary();
  EXPECT_TRUE(expectation(*host, "lib")->ok);
}

TEST_F(Sandbox, AFailingUpdateIsPausedAfterThreeErrorsAndTheRestGoesOn) {
  auto host = load(
      "local finished = false\n"
      "return {\n"
      "  on_update = function(ctx, dt) error('broken') end,\n"
      "  on_finish = function() expect('finish still runs', true) end,\n"
      "}\n");
  run(*host, 10);
  EXPECT_FALSE(host->hasUpdate());
  ASSERT_EQ(host->errors().size(), 4u);  // three errors and the pause notice
  EXPECT_NE(host->errors()[3].message.find("paused"), std::string::npos);
  EXPECT_TRUE(expectation(*host, "finish still runs")->ok);
}

}  // namespace tumble::test
