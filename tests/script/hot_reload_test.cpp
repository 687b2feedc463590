// Hot reload (ScenarioHost::reload, HotReload): a saved scenario file takes
// effect with the old state; a broken save keeps the old code and says where
// it is broken; reloading does not leak timers, triggers or memory.
#include <chrono>

#include "script/hot_reload.h"
#include "script_fixture.h"

namespace tumble::test {

namespace {

class HotReloadTest : public ScriptTest {
 protected:
  fs::path file() const { return m_root / "escape" / "scenarios" / "s.lua"; }

  // Saves new text as an editor would; the time moves on so the watcher sees
  // the save whatever the file system's timestamp resolution.
  void save(const fs::path& path, const std::string& text) {
    writeFile(path, text);
    fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(++m_saves));
  }

  // `n` fixed steps from m_step on.
  void steps(script::ScenarioHost& host, int n) {
    for (int i = 0; i < n; ++i, ++m_step) stepOnce(host, double(m_step) / 60, m_step);
  }

  double time_s() const { return double(m_step) / 60; }

  Vec3 onlyBodyVelocity() {
    Vec3 v = Vec3::Zero();
    world().forEachBody([&](physics::BodyId, const physics::Body& b) { v = b.linearVelocity_mps; });
    return v;
  }

  int m_saves = 0;
  std::int64_t m_step = 0;
};

const char* kCounterV1 = R"(
local ball
return {
  on_start = function(ctx)
    ball = world.sphere{radius = 0.5, position = {0, 50, 0}, mass = 1}
    ctx.state.ball = ball
    ctx.state.ticks = 0
  end,
  on_update = function(ctx, dt) ctx.state.ticks = ctx.state.ticks + 1 end,
  on_finish = function(ctx) expect("ticks", ctx.state.ticks, {min = 0}) end,
}
)";

// Same state, new behaviour: counts in thousands and lifts the ball at 5 m/s.
const char* kCounterV2 = R"(
local ball
return {
  on_reload = function(ctx, state)
    ball = state.ball
    state.reloaded_at = ctx.step
  end,
  on_update = function(ctx, dt)
    ctx.state.ticks = ctx.state.ticks + 1000
    ball:set_velocity{0, 5, 0}
  end,
  on_finish = function(ctx)
    expect("ticks", ctx.state.ticks, {min = 0})
    expect("reloaded at", ctx.state.reloaded_at, {min = 0})
  end,
}
)";

}  // namespace

TEST_F(HotReloadTest, ASavedScenarioRunsTheNewCodeWithTheOldState) {
  auto host = load(kCounterV1);
  ASSERT_TRUE(host);
  script::HotReload reload(*host);
  sceneOf(*host).start();
  steps(*host, 30);
  EXPECT_LT(onlyBodyVelocity().y(), -4.0) << "falling freely for 0.5 s: v = -g t = -4.9 m/s";

  save(file(), kCounterV2);
  auto events = reload.pollNow(time_s(), m_step);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_TRUE(events[0].ok) << events[0].message;
  EXPECT_EQ(events[0].file, "scenarios/s.lua");
  EXPECT_EQ(host->reloadCount(), 1);
  steps(*host, 30);
  host->finish(time_s(), m_step);

  // The state from before the reload (30 ticks, the ball) is used by the new
  // code: 30 + 30 * 1000, and the ball now rises: 5 m/s set before each step
  // minus one step of gravity.
  auto* ticks = expectation(*host, "ticks");
  ASSERT_NE(ticks, nullptr);
  EXPECT_EQ(ticks->value, 30 + 30 * 1000);
  ASSERT_NE(expectation(*host, "reloaded at"), nullptr);
  EXPECT_EQ(expectation(*host, "reloaded at")->value, 30);
  EXPECT_NEAR(onlyBodyVelocity().y(), 5.0 - 9.81 / 60, 0.02);
  EXPECT_TRUE(host->errors().empty()) << host->errors().front().summary();
}

TEST_F(HotReloadTest, ASaveIsPickedUpWithinAQuarterSecondOfPlaying) {
  auto host = load(kCounterV1);
  ASSERT_TRUE(host);
  script::HotReload reload(*host, 0.25);
  sceneOf(*host).start();
  EXPECT_TRUE(reload.poll(100.0, 0, 0).empty());  // the first poll scans: nothing saved yet
  save(file(), kCounterV2);
  EXPECT_TRUE(reload.poll(100.1, 0, 0).empty()) << "between scans nothing is read";
  EXPECT_EQ(host->reloadCount(), 0);
  auto events = reload.poll(100.25, 0, 0);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_TRUE(events[0].ok) << events[0].message;
  EXPECT_EQ(host->reloadCount(), 1);
  EXPECT_TRUE(reload.poll(100.5, 0, 0).empty()) << "a save is applied once";
}

TEST_F(HotReloadTest, ASaveThatDoesNotCompileKeepsTheOldCodeAndNamesTheLine) {
  auto host = load(kCounterV1);
  ASSERT_TRUE(host);
  script::HotReload reload(*host);
  sceneOf(*host).start();
  steps(*host, 10);
  save(file(), "local x = 1\nreturn {\n  on_update = function(ctx, dt)\n    ctx.state.ticks = ctx.state.ticks +* 1000\n"
               "  end,\n}\n");
  auto events = reload.pollNow(time_s(), m_step);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_FALSE(events[0].ok);
  ASSERT_EQ(host->errors().size(), 1u);
  const script::ScriptError& e = host->errors().back();
  EXPECT_EQ(e.file, "scenarios/s.lua");
  EXPECT_EQ(e.line, 4);
  EXPECT_NE(e.message.find("previous code keeps running"), std::string::npos) << e.message;
  EXPECT_EQ(host->reloadCount(), 0);
  steps(*host, 10);  // still the old on_update: +1 per step

  // An error at top level is refused the same way, with its line.
  save(file(), "local x = 1\nerror(\"half-written file\")\nreturn {}\n");
  EXPECT_FALSE(reload.pollNow(time_s(), m_step).at(0).ok);
  EXPECT_EQ(host->errors().back().line, 2);
  steps(*host, 10);

  // So is a table with a callback that is not a function.
  save(file(), "return {on_update = 5}\n");
  EXPECT_FALSE(reload.pollNow(time_s(), m_step).at(0).ok);
  EXPECT_EQ(host->errors().back().message,
            "reload failed, the previous code keeps running: field 'on_update' must be a function");
  EXPECT_EQ(host->errors().back().file, "scenarios/s.lua");

  // Fixing the file makes the next save take effect.
  save(file(), kCounterV2);
  EXPECT_TRUE(reload.pollNow(time_s(), m_step).at(0).ok);
  steps(*host, 1);
  host->finish(time_s(), m_step);
  EXPECT_EQ(expectation(*host, "ticks")->value, 30 + 1000);
}

TEST_F(HotReloadTest, ReloadingAHundredTimesLeaksNoTimersTriggersOrMemory) {
  // on_start and on_reload share a setup that makes two timers and a
  // trigger; each load of the file also builds a 1000-entry table, so any
  // old chunk kept alive would show in the memory.
  const char* source = R"(
local big = {}
for i = 1, 1000 do big[i] = {i, tostring(i)} end
local fired = 0
local function setup(ctx)
  timer.every(0.5, function() fired = fired + 1 end)
  timer.after(1000, function() end)
  trigger.box{center = {0, 0, 0}, size = {1, 1, 1}, on_enter = function() end}
end
return {
  on_start = setup,
  on_reload = function(ctx, state) setup(ctx) end,
  on_update = function(ctx, dt) ctx.state.n = (ctx.state.n or 0) + #big end,
}
)";
  auto host = load(source);
  ASSERT_TRUE(host);
  sceneOf(*host).start();
  steps(*host, 5);
  EXPECT_EQ(host->timers().activeCount(), 2u);
  EXPECT_EQ(host->triggers().liveCount(), 1);
  ASSERT_TRUE(host->reload(time_s(), m_step));
  const std::size_t afterFirst = host->luaMemoryBytes();
  for (int i = 0; i < 100; ++i) {
    steps(*host, 2);
    ASSERT_TRUE(host->reload(time_s(), m_step));
  }
  EXPECT_EQ(host->reloadCount(), 101);
  EXPECT_EQ(host->timers().activeCount(), 2u) << "each reload's on_reload re-made the timers; the old ones are gone";
  EXPECT_EQ(host->triggers().liveCount(), 1);
  // One generation of the file is ~100 KiB (the table); 100 leaked ones
  // would be megabytes. Allow a few KiB for the collector's bookkeeping.
  EXPECT_LT(host->luaMemoryBytes(), afterFirst + 16 * 1024)
      << "after the first reload " << afterFirst << " bytes, after 101: " << host->luaMemoryBytes();
  EXPECT_TRUE(host->errors().empty());
}

TEST_F(HotReloadTest, WithoutOnReloadTimersKeepRunning) {
  auto host = load(R"(
local fired = 0
return {
  on_start = function(ctx) ctx.state.timer = timer.every(0.1, function(ctx) ctx.state.fired = (ctx.state.fired or 0) + 1 end) end,
  on_finish = function(ctx) expect("fired", ctx.state.fired or 0, {min = 0}) end,
}
)");
  ASSERT_TRUE(host);
  sceneOf(*host).start();
  steps(*host, 30);  // 0.5 s: fired after the steps ending at 0.1, 0.2, 0.3, 0.4, 0.5
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(host->reload(time_s(), m_step));
  EXPECT_EQ(host->timers().activeCount(), 1u);
  steps(*host, 30);  // and at 0.6 .. 1.0
  host->finish(time_s(), m_step);
  EXPECT_EQ(expectation(*host, "fired")->value, 10);
}

TEST_F(HotReloadTest, ASavedModuleIsRequiredAfresh) {
  auto host = load(R"(
local values = require "lib.values"
return {
  on_reload = function() end,
  on_finish = function(ctx) expect("speed", values.speed, {min = 0}) end,
}
)", {}, "escape", 1, {{"lib/values.lua", "return {speed = 1}"}});
  ASSERT_TRUE(host);
  script::HotReload reload(*host);
  sceneOf(*host).start();
  save(m_root / "escape" / "lib" / "values.lua", "return {speed = 7}");
  auto events = reload.pollNow(0, 0);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_TRUE(events[0].ok) << events[0].message;
  EXPECT_EQ(events[0].message, "lib/values.lua reloaded");
  host->finish(0, 0);
  EXPECT_EQ(expectation(*host, "speed")->value, 7);
}

TEST_F(HotReloadTest, EmitterAndBindingFilesGoToTheirHooks) {
  auto host = load("return {}", {}, "escape", 1,
                   {{"emitters/smoke.lua", "return {}"}, {"bindings.lua", "return {}"}, {"scenarios/other.lua", "return {}"}});
  ASSERT_TRUE(host);
  script::HotReload reload(*host);
  std::vector<std::string> seen;
  reload.addHook(script::ModFileKind::Emitter, [&](const std::string& path, const std::string& rel) {
    EXPECT_TRUE(fs::exists(path));
    seen.push_back(rel);
    return Status(Ok{});
  });
  reload.addHook(script::ModFileKind::Bindings, [&](const std::string&, const std::string& rel) {
    seen.push_back(rel);
    return Status(makeError("bindings.lua:3: action 'jump' has no key"));
  });
  save(m_root / "escape" / "emitters" / "smoke.lua", "return {rate = 10}");
  save(m_root / "escape" / "bindings.lua", "return {jump = {}}");
  save(m_root / "escape" / "scenarios" / "other.lua", "return {title = 'not running'}");
  auto events = reload.pollNow(0, 0);
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0], "bindings.lua");
  EXPECT_EQ(seen[1], "emitters/smoke.lua");
  EXPECT_EQ(events.size(), 2u) << "another scenario's file does not reload the running one";
  EXPECT_EQ(host->reloadCount(), 0);
  ASSERT_EQ(host->errors().size(), 1u);
  EXPECT_EQ(host->errors()[0].file, "bindings.lua");
  EXPECT_NE(host->errors()[0].message.find("action 'jump' has no key"), std::string::npos);
}

}  // namespace tumble::test
