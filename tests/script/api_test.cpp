// The scenario API beyond bodies: contact events, timers, deterministic
// random numbers, materials, removal, ray casts, game state and trigger
// volumes. Each test is a small scenario run against a real world.
#include <cmath>

#include "script_fixture.h"

namespace tumble::test {

class Api : public ScriptTest {};

TEST_F(Api, OnContactReportsTheBallLandingOnTheGround) {
  auto host = load(R"(
    local ground, ball
    local hits, impulse, point_y, time = 0, 0, nil, nil
    return {
      on_start = function()
        ground = world.plane{}
        ball = world.sphere{radius = 0.5, position = {0, 2, 0}, mass = 2}
      end,
      on_contact = function(ctx, a, b, j, point, normal)
        hits = hits + 1
        expect("the pair is ball and ground", (a == ball and b == ground) or (a == ground and b == ball))
        impulse, point_y, time = j, point.y, ctx.time
      end,
      on_finish = function()
        expect("one contact began", hits, {min = 1, max = 1})
        expect("landing impulse, N s", impulse, {min = 0.5})
        expect("contact point on the ground, m", point_y, {min = -0.05, max = 0.05})
        -- Free fall of 1.5 m: t = sqrt(2 h / g) = 0.553 s.
        expect("landing time, s", time, {min = 0.5, max = 0.62})
      end,
    })");
  ASSERT_TRUE(host->hasContact());
  run(*host, 90);
  expectAllHeld(*host);
}

TEST_F(Api, NoCallbacksMeansNoLuaCallsPerFrame) {
  auto host = load("return {on_start = function() world.plane{} world.sphere{position = {0, 1, 0}} end}");
  EXPECT_FALSE(host->hasUpdate());
  EXPECT_FALSE(host->hasContact());
  sceneOf(*host).start();
  std::uint64_t calls = host->luaCallCount();
  for (int i = 0; i < 120; ++i) stepOnce(*host, i / 60.0, i);
  EXPECT_EQ(host->luaCallCount(), calls);
}

TEST_F(Api, TimersFireInSimulatedTime) {
  auto host = load(R"(
    local once_at, every_count, stopped_count, cancelled_fired = nil, 0, 0, false
    local late
    return {
      on_start = function()
        timer.after(0.5, function(ctx) once_at = ctx.time end)
        timer.every(0.25, function() every_count = every_count + 1 end)
        timer.every(0.1, function() stopped_count = stopped_count + 1; return stopped_count < 3 end)
        local t = timer.after(0.3, function() cancelled_fired = true end)
        expect("cancel of an active timer", t:cancel())
        expect("cancelled timer is inactive", not t:active())
      end,
      on_update = function(ctx)
        if ctx.step == 30 then late = timer.after(0, function(c) late = c.time end) end
      end,
      on_finish = function()
        expect("after(0.5) fired at 0.5 s", once_at, {min = 0.5 - 1e-9, max = 0.5 + 1e-9})
        expect("every(0.25) fired 4 times in 1.2 s", every_count, {min = 4, max = 4})
        expect("returning false stops a timer", stopped_count, {min = 3, max = 3})
        expect("a cancelled timer never fires", not cancelled_fired)
        expect("after(0) made in on_update fires next step", late, {min = 31 / 60 - 1e-9, max = 31 / 60 + 1e-9})
      end,
    })");
  run(*host, 72);  // 1.2 s
  expectAllHeld(*host);
}

TEST_F(Api, TimerArgumentsAreChecked) {
  auto host = load(R"(return {on_start = function()
    local ok, e = pcall(timer.every, 0, function() end)
    expect("every(0) refused", not ok and e:find("seconds must be > 0") ~= nil)
    ok, e = pcall(timer.after, 1, "not a function")
    expect("fn checked", not ok and e:find("must be a function") ~= nil)
  end})");
  run(*host, 1);
  expectAllHeld(*host);
}

TEST_F(Api, RandomIsReproducibleAndIndependent) {
  const char* source = R"(
    local a, b, c = random.new(42), random.new(42), random.new(43)
    local same, differ = true, false
    for i = 1, 100 do
      local x, y, z = a:float(), b:float(), c:float()
      same = same and x == y
      differ = differ or x ~= z
      assert(x >= 0 and x < 1)
    end
    local lo, hi, sum, sum2, n = math.huge, -math.huge, 0, 0, 20000
    for i = 1, n do
      local k = a:int(1, 6)
      lo, hi = math.min(lo, k), math.max(hi, k)
      local g = a:normal(10, 2)
      sum, sum2 = sum + g, sum2 + g * g
    end
    local mean = sum / n
    return {
      seed_value = random.float(),
      on_start = function()
        expect("same seed, same numbers", same)
        expect("other seed, other numbers", differ)
        expect("int covers 1..6", lo == 1 and hi == 6)
        expect("normal mean", mean, {min = 9.95, max = 10.05})
        expect("normal sd", math.sqrt(sum2 / n - mean * mean), {min = 1.95, max = 2.05})
        expect("seed kept", a:seed() == 42)
        expect("pick", ({7, 8, 9})[1] == 7 and a:pick{5} == 5)
        expect("scenario stream", random.float(), {min = 0, max = 1})
        hud_text(string.format("%.17g", random.float()))
      end,
    })";
  auto one = load(source, {}, "r1", 1);
  auto again = load(source, {}, "r2", 1);
  auto other = load(source, {}, "r3", 2);
  run(*one, 1);
  run(*again, 1);
  run(*other, 1);
  expectAllHeld(*one);
  ASSERT_EQ(one->hudText().size(), 1u);
  EXPECT_EQ(one->hudText(), again->hudText()) << "same --seed, same scenario stream";
  EXPECT_NE(one->hudText(), other->hudText()) << "another --seed, another stream";
}

TEST_F(Api, SetMaterialChangesFrictionAndRestitution) {
  auto host = load(R"(return {on_start = function()
    local b = world.box{}
    b:set_material{friction = 0.1, restitution = 0.5}
    local m = b:material()
    expect("friction", m.friction, {min = 0.0999, max = 0.1001})
    expect("restitution", m.restitution, {min = 0.4999, max = 0.5001})
    b:set_material{restitution = 0.25}
    expect("friction kept", b:material().friction, {min = 0.0999, max = 0.1001})
    local ok, e = pcall(b.set_material, b, {restitution = 2})
    expect("restitution above 1 refused", not ok and e:find("0..1") ~= nil)
    ok, e = pcall(b.set_material, b, {frction = 1})
    expect("typo refused", not ok and e:find("unknown field 'frction'") ~= nil)
  end})");
  run(*host, 1);
  expectAllHeld(*host);
}

TEST_F(Api, SetMaterialSetsTheSoundOfImpacts) {
  auto host = load(R"(return {on_start = function()
    local b = world.box{}
    expect("thud unless set", b:material().sound == "thud")
    b:set_material{sound = "metal"}
    expect("metal", b:material().sound == "metal")
    b:set_material{friction = 0.2}
    expect("sound kept", b:material().sound == "metal")
    local ok, e = pcall(b.set_material, b, {sound = "jelly"})
    expect("unknown sound refused, naming the valid ones", not ok and e:find("'sound'") ~= nil and e:find("wood") ~= nil)
    ok, e = pcall(b.set_material, b, {sound = 3})
    expect("not a string refused", not ok and e:find("sound") ~= nil)
  end})");
  run(*host, 1);
  expectAllHeld(*host);
}

TEST_F(Api, RemovedBodiesAreGoneAndTheirHandlesSaySo) {
  auto host = load(R"(return {on_start = function()
    local a, b = world.box{position = {0, 1, 0}}, world.box{position = {3, 1, 0}}
    expect("two bodies", world.body_count(), {min = 2, max = 2})
    expect("remove returns true", world.remove(a))
    expect("again returns false", world.remove(a) == false)
    expect("handle invalid", not a:is_valid())
    expect("one body left", world.body_count(), {min = 1, max = 1})
    local ok, e = pcall(a.position, a)
    expect("methods refuse a removed body", not ok and e:find("was removed") ~= nil)
    b:remove()
    expect("Body:remove too", world.body_count(), {min = 0, max = 0})
  end})");
  run(*host, 1);
  expectAllHeld(*host);
}

TEST_F(Api, RaycastAllReturnsEveryHitNearestFirst) {
  auto host = load(R"(return {on_start = function()
    local far = world.box{position = {6, 1, 0}, type = "static"}
    local near = world.box{position = {0, 1, 0}, type = "static"}
    local mid = world.sphere{position = {3, 1, 0}, radius = 0.5, type = "static"}
    local hits = world.raycast_all({-10, 1, 0}, {1, 0, 0})
    expect("three hits", #hits, {min = 3, max = 3})
    expect("nearest first", hits[1].body == near and hits[2].body == mid and hits[3].body == far)
    expect("distance to the near box, m", hits[1].distance, {min = 9.49, max = 9.51})
    expect("normal faces the ray", hits[1].normal.x, {min = -1.001, max = -0.999})
    expect("max distance cuts", #world.raycast_all({-10, 1, 0}, {1, 0, 0}, 12), {min = 1, max = 1})
    expect("closest agrees", world.raycast({-10, 1, 0}, {1, 0, 0}).body == near)
  end})");
  run(*host, 1);
  expectAllHeld(*host);
}

TEST_F(Api, GameMessagesScoreAndOutcomeReachTheHost) {
  auto host = load(R"(return {
    on_start = function()
      game.message("welcome", 2)
      game.score(10)
      expect("add_score returns the total", game.add_score(5), {min = 15, max = 15})
      expect("undecided", game.outcome() == nil)
    end,
    on_update = function(ctx)
      if ctx.step == 60 then
        expect("first decides", game.win("reached the flag"))
        expect("later ignored", game.lose("too late") == false)
        local o, why = game.outcome()
        expect("outcome", o == "won" and why == "reached the flag")
      end
    end,
  })");
  run(*host, 70);
  expectAllHeld(*host);
  ASSERT_EQ(host->messages().size(), 1u);
  EXPECT_EQ(host->messages()[0].text, "welcome");
  EXPECT_EQ(host->activeMessages(1.0), std::vector<std::string>{"welcome"});
  EXPECT_TRUE(host->activeMessages(2.5).empty());
  EXPECT_TRUE(host->hasScore());
  EXPECT_EQ(host->score(), 15);
  EXPECT_EQ(host->outcome(), script::Outcome::Won);
  EXPECT_EQ(host->outcomeReason(), "reached the flag");
  EXPECT_NEAR(host->outcomeTime_s(), 1.0, 1e-9);
}

TEST_F(Api, TriggerBoxReportsEnterAndExit) {
  auto host = load(R"(
    local ball, other, zone
    local events = {}
    return {
      on_start = function()
        world.plane{}
        -- The ball falls through the zone (y 2..3) and comes to rest below it.
        ball = world.sphere{radius = 0.25, position = {0, 4, 0}}
        other = world.sphere{radius = 0.25, position = {5, 4, 0}}
        zone = trigger.box{center = {0, 2.5, 0}, size = {2, 1, 2},
          on_enter = function(body, t) events[#events + 1] = (body == ball and "enter" or "?") end,
          on_exit = function(body, t) events[#events + 1] = (body == ball and "exit" or "?") end}
      end,
      on_update = function(ctx)
        -- y = 4 - g t^2 / 2 = 2.5 m at t = 0.55 s (step 33): inside.
        if ctx.step == 33 then expect("inside at 0.55 s", zone:contains(ball) and zone:count() == 1) end
      end,
      on_finish = function()
        expect("enter then exit", table.concat(events, ",") == "enter,exit")
        expect("empty at the end", #zone:bodies() == 0)
      end,
    })");
  run(*host, 120);
  expectAllHeld(*host);
}

TEST_F(Api, TriggerExitForARemovedBodyAndRemovedTriggersGoQuiet) {
  auto host = load(R"(
    local ball, zone, quiet
    local exits, quiet_events = 0, 0
    return {
      on_start = function()
        world.set_gravity{0, 0, 0}
        ball = world.sphere{radius = 0.25, position = {0, 0, 0}}
        zone = trigger.box{center = {0, 0, 0}, size = {1, 1, 1},
          on_exit = function(body) exits = exits + 1; expect("handle of the removed body", not body:is_valid()) end}
        quiet = trigger.box{center = {0, 0, 0}, size = {1, 1, 1}, on_enter = function() quiet_events = quiet_events + 1 end}
        quiet:remove()
      end,
      on_update = function(ctx) if ctx.step == 5 then world.remove(ball) end end,
      on_finish = function()
        expect("one exit", exits, {min = 1, max = 1})
        expect("a removed trigger reports nothing", quiet_events, {min = 0, max = 0})
      end,
    })");
  run(*host, 10);
  expectAllHeld(*host);
  auto bad = load("return {on_start = function() trigger.box{center = {0, 0, 0}, size = {0, 1, 1}} end}");
  run(*bad, 1);
  ASSERT_EQ(bad->errors().size(), 1u);
  EXPECT_NE(bad->errors()[0].message.find("'size' must be > 0"), std::string::npos) << bad->errors()[0].summary();
}

// A box turned by `rotation` holds what is inside its turned shape: an
// 8 x 1 x 1 m box turned 45 degrees about +Y runs along (1, 0, -1); a body on
// that diagonal is inside, one on the world X axis (inside the same box
// unturned) and one on the other diagonal are not.
TEST_F(Api, ATurnedTriggerBoxHoldsWhatIsInsideItsTurnedShape) {
  auto host = load(R"(
    local zone, plain, along, onX, across
    return {
      on_start = function()
        world.set_gravity{0, 0, 0}
        along = world.sphere{radius = 0.1, position = {2.5, 0, -2.5}}
        onX = world.sphere{radius = 0.1, position = {3, 0, 0}}
        across = world.sphere{radius = 0.1, position = {2.5, 0, 2.5}}
        zone = trigger.box{center = {0, 0, 0}, size = {8, 1, 1}, rotation = {0, math.pi / 4, 0}}
        plain = trigger.box{center = {0, 0, 0}, size = {8, 1, 1}}
      end,
      on_update = function(ctx)
        if ctx.step == 2 then
          expect("on the turned box's axis: inside", zone:contains(along))
          expect("on world X: outside the turned box", not zone:contains(onX))
          expect("on the other diagonal: outside", not zone:contains(across))
          expect("one body inside", zone:count(), {min = 1, max = 1})
          expect("the unturned box holds the one on X only", plain:contains(onX) and plain:count() == 1)
        end
      end,
    })");
  run(*host, 3);
  expectAllHeld(*host);
  auto bad = load("return {on_start = function() trigger.box{center = {0, 0, 0}, size = {1, 1, 1}, rotation = 'up'} end}");
  run(*bad, 1);
  ASSERT_EQ(bad->errors().size(), 1u);
  EXPECT_NE(bad->errors()[0].message.find("trigger.box: field 'rotation'"), std::string::npos)
      << bad->errors()[0].summary();
}

}  // namespace tumble::test
