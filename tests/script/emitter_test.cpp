// The `particles` Lua API: spawning from a mod's emitter files with
// overrides, Emitter handles (rate, burst, stop, remove, count, alive), stale
// handles refused with a clear error, and broken files or arguments named.
// The app steps particles after physics; here the test does it.
#include <cmath>

#include "script_fixture.h"

namespace tumble::test {

namespace {

const std::map<std::string, std::string> kEmitterFiles = {
    {"emitters/puff.lua", "return {rate = 10, lifetime = {0.5, 0.5}, speed = 1, spread = math.rad(20)}\n"},
    {"emitters/broken.lua", "return {\n  rate = 5,\n  lifetime = {2, 1},\n}\n"},
};

class Emitters : public ScriptTest {
 protected:
  // start, steps of (update, physics, afterStep, particles), finish
  void runWithParticles(script::ScenarioHost& host, int steps, double dt = 1.0 / 60) {
    host.start();
    double t = 0;
    for (int i = 0; i < steps; ++i) {
      host.update(t, dt, i);
      m_world.step(Real(dt));
      t = double(i + 1) * dt;
      host.afterStep(t, i);
      if (auto* ps = host.particlesIfAny()) ps->step(float(dt));
    }
    host.finish(t, steps);
  }
};

}  // namespace

TEST_F(Emitters, ASceneThatSpawnsNothingHasNoParticleSystem) {
  auto host = load("return {on_start = function() world.plane{} expect('none yet', particles.count() == 0) end}", {},
                   "fx", 1, kEmitterFiles);
  runWithParticles(*host, 30);
  EXPECT_EQ(host->particlesIfAny(), nullptr);
  expectAllHeld(*host);
}

TEST_F(Emitters, SpawnWithOverridesAndDriveTheRateFromLua) {
  auto host = load(R"(
    local e
    local steady
    return {
      on_start = function()
        e = particles.spawn("fx:puff", {position = {0, 1, 0}}, {rate = 0})
        expect("override rate", e:rate(), {min = 0, max = 0})
      end,
      on_update = function(ctx)
        if ctx.step == 0 then e:set_rate(120) end
        if ctx.step == 60 then steady = e:count() end
        if ctx.step == 61 then e:stop() end
      end,
      on_finish = function()
        -- 120/s x 0.5 s lifetime = 60 live particles in steady state
        expect("steady count = rate x lifetime", steady, {min = 58, max = 62})
        expect("stopped and finished: gone", e:alive() == false)
        expect("a gone emitter counts 0", e:count(), {min = 0, max = 0})
        local ok, err = pcall(e.set_rate, e, 5)
        expect("a gone emitter refuses set_rate", not ok and err:find("gone") ~= nil)
      end,
    })", {}, "fx", 1, kEmitterFiles);
  runWithParticles(*host, 120);
  expectAllHeld(*host);
  ASSERT_NE(host->particlesIfAny(), nullptr);
  EXPECT_EQ(host->particlesIfAny()->emitterCount(), 0);
}

TEST_F(Emitters, BurstRemoveAndOneShotBursts) {
  auto host = load(R"(
    local e, shot
    return {
      on_start = function()
        e = particles.spawn("puff", {position = {0, 1, 0}}, {rate = 0})  -- "puff": this mod's
        e:burst(25)
        shot = particles.burst("fx:puff", 40, {position = {2, 1, 0}})
      end,
      on_update = function(ctx)
        if ctx.step == 1 then
          expect("burst spawned", e:count(), {min = 25, max = 25})
          expect("one-shot spawned", shot:count(), {min = 40, max = 40})
          expect("all particles", particles.count(), {min = 65, max = 65})
          e:remove()
          expect("removed at once", e:alive() == false)
        end
      end,
      on_finish = function()
        expect("the one-shot freed itself after its 0.5 s", shot:alive() == false)
        local ok, err = pcall(function() e:burst(3) end)
        expect("a removed emitter refuses burst", not ok and err:find("gone") ~= nil)
      end,
    })", {}, "fx", 1, kEmitterFiles);
  runWithParticles(*host, 60);
  expectAllHeld(*host);
}

TEST_F(Emitters, BadNamesFilesAndArgumentsGiveClearErrors) {
  auto host = load(R"(
    local function err(f) local ok, e = pcall(f) return ok and "" or e end
    return {
      on_start = function()
        local b = world.sphere{position = {0, 1, 0}}
        expect("unknown emitter lists the known ones",
               err(function() particles.spawn("fx:nope", {position = {0, 0, 0}}) end):find("fx:puff") ~= nil)
        expect("broken file names file and field",
               err(function() particles.spawn("fx:broken", {position = {0, 0, 0}}) end)
                 :find("emitters/broken.lua.*field 'lifetime'") ~= nil)
        expect("bad override names the field",
               err(function() particles.spawn("fx:puff", {position = {0, 0, 0}}, {shape = "donut"}) end)
                 :find("field 'shape'") ~= nil)
        expect("misspelt override is refused",
               err(function() particles.spawn("fx:puff", {position = {0, 0, 0}}, {rtae = 3}) end)
                 :find("unknown field") ~= nil)
        expect("position and body together are refused",
               err(function() particles.spawn("fx:puff", {position = {0, 0, 0}, body = b}) end)
                 :find("not both") ~= nil)
        expect("no placement is refused",
               err(function() particles.spawn("fx:puff", {}) end):find("position") ~= nil)
        expect("a non-emitter is refused",
               err(function() local e = particles.spawn("fx:puff", {position = {0, 0, 0}}) e.stop(b) end)
                 :find("expected an Emitter") ~= nil)
      end,
    })", {}, "fx", 1, kEmitterFiles);
  runWithParticles(*host, 1);
  expectAllHeld(*host);
}

TEST_F(Emitters, EditedFilesAreReadAgainAfterForgettingTheCache) {
  auto host = load(R"(
    return {on_update = function() particles.spawn("fx:puff", {position = {0, 0, 0}}) end})", {}, "fx", 1,
                   kEmitterFiles);
  host->start();
  host->update(0, 1.0 / 60, 0);
  writeFile(m_root / "fx" / "emitters" / "puff.lua", "return {rate = 33}\n");
  host->update(1.0 / 60, 1.0 / 60, 1);  // cached: still the old file
  host->forgetEmitterDefinitions();
  host->update(2.0 / 60, 1.0 / 60, 2);
  const particles::ParticleSystem* ps = host->particlesIfAny();
  ASSERT_NE(ps, nullptr);
  std::vector<float> rates;
  ps->forEach([&](particles::EmitterId, const particles::Emitter& e) { rates.push_back(e.rate_per_s); });
  EXPECT_EQ(rates, (std::vector<float>{10, 10, 33}));
  for (const auto& e : host->errors()) ADD_FAILURE() << e.summary();
}

TEST_F(Emitters, AnEmitterFileIsDataAndCannotReachTheWorld) {
  std::map<std::string, std::string> files = {
      {"emitters/sneaky.lua", "world.sphere{position = {0, 1, 0}}\nreturn {rate = 1}\n"}};
  auto host = load(R"(
    return {on_start = function()
      local ok, e = pcall(particles.spawn, "fx:sneaky", {position = {0, 0, 0}})
      expect("the file cannot call world", not ok and e:find("sneaky.lua:1") ~= nil)
    end})", {}, "fx", 1, files);
  runWithParticles(*host, 1);
  expectAllHeld(*host);
  EXPECT_EQ(m_world.bodyCount(), 0);
}

}  // namespace tumble::test

namespace tumble::test {

// Hot reload: a saved emitter file changes the emitters
// running from it, with their spawn overrides still on top; a broken save
// changes nothing and names the file and field.
TEST_F(Emitters, ASavedEmitterFileChangesTheRunningEmitters) {
  auto host = load(R"(
    return {on_start = function()
      world.plane{}
      a = particles.spawn("fx:puff", {position = {0, 1, 0}})
      b = particles.spawn("puff", {position = {2, 1, 0}}, {speed = 3})
      c = particles.spawn("fx:broken_later", {position = {4, 1, 0}})
    end}
  )", {}, "fx", 1,
                   {{"emitters/puff.lua", "return {rate = 10, lifetime = {0.5, 0.5}, speed = 1}\n"},
                    {"emitters/broken_later.lua", "return {rate = 7, lifetime = 1, speed = 1}\n"}});
  ASSERT_TRUE(host);
  runWithParticles(*host, 5);
  particles::ParticleSystem* ps = host->particlesIfAny();
  ASSERT_NE(ps, nullptr);
  std::vector<particles::EmitterId> ids;
  ps->forEach([&](particles::EmitterId id, const particles::Emitter&) { ids.push_back(id); });
  ASSERT_EQ(ids.size(), 3u);

  writeFile(m_root / "fx/emitters/puff.lua", "return {rate = 40, lifetime = {0.5, 0.5}, speed = 2, max_count = 900}\n");
  ASSERT_TRUE(host->reloadEmitterFile("emitters/puff.lua").ok());
  EXPECT_FLOAT_EQ(ps->get(ids[0])->def.rate_per_s, 40);
  EXPECT_FLOAT_EQ(ps->get(ids[0])->rate_per_s, 40) << "no set_rate: the new rate applies";
  EXPECT_FLOAT_EQ(ps->get(ids[0])->def.speedMax_mps, 2);
  EXPECT_FLOAT_EQ(ps->get(ids[1])->def.rate_per_s, 40) << "\"puff\" is this mod's file too";
  EXPECT_FLOAT_EQ(ps->get(ids[1])->def.speedMax_mps, 3) << "the spawn's overrides stay on top";
  EXPECT_FLOAT_EQ(ps->get(ids[2])->def.rate_per_s, 7) << "another file's emitter is untouched";

  writeFile(m_root / "fx/emitters/puff.lua", "return {rate = -1, lifetime = 1}\n");
  auto st = host->reloadEmitterFile("emitters/puff.lua");
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().find("puff.lua"), std::string::npos) << st.error();
  EXPECT_NE(st.error().find("rate"), std::string::npos) << st.error();
  EXPECT_FLOAT_EQ(ps->get(ids[0])->def.rate_per_s, 40) << "a broken save keeps the running definition";
}

}  // namespace tumble::test
