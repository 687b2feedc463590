// Tunables (tune.number / bool / choice): the script reads the live value,
// the panel's and the command line's changes apply at the next call, and
// the overrides file round-trips.
#include <chrono>

#include "core/file_util.h"
#include "script/tunables.h"
#include <cstdlib>

#include "script_fixture.h"

namespace tumble::test {

namespace {

// A ball in zero gravity pushed along x at the tunable speed each step.
const char* kSpeedScenario = R"(
local ball
return {
  on_start = function(ctx)
    world.set_gravity{0, 0, 0}
    ball = world.sphere{radius = 0.5, position = {0, 5, 0}, mass = 1}
  end,
  on_update = function(ctx, dt)
    local v = tune.number("speed", 2, {min = 0, max = 10, unit = "m/s", description = "push speed"})
    if tune.bool("reverse", false) then v = -v end
    if tune.choice("axis", "x", {choices = {"x", "z"}}) == "z" then ball:set_velocity{0, 0, v}
    else ball:set_velocity{v, 0, 0} end
  end,
}
)";

class TuneTest : public ScriptTest {
 protected:
  // Loads mod "tuned" with --set tune.NAME=VALUE for each of `tuneSets`;
  // with `overrides` it reads <m_root>/config/tune/tuned.json as `play` does.
  LoadedScenario loadWith(const std::string& source, const std::map<std::string, std::string>& tuneSets,
                          bool overrides = false) {
    makeMod(m_root, "tuned", "", {{"scenarios/s.lua", source}});
    ::setenv("TUMBLE_CONFIG_DIR", (m_root / "config").c_str(), 1);
    app::SceneOptions options;
    options.scenarioRef = "tuned:s";
    options.modDirs = {m_root.string()};
    options.tuneOverrides = overrides;
    for (const auto& [name, value] : tuneSets) options.sets["tune." + name] = value;
    auto scene = app::Scene::create(options);
    EXPECT_TRUE(scene) << (scene ? "" : scene.error());
    if (!scene) return {};
    m_world = &scene.value()->world();
    return LoadedScenario{std::move(scene.value())};
  }
  void step(script::ScenarioHost& host) {
    stepOnce(host, m_t, m_i++);
    m_t += 1.0 / 60;
  }
  Vec3 velocity() {
    Vec3 v = Vec3::Zero();
    world().forEachBody([&](physics::BodyId, const physics::Body& b) { v = b.linearVelocity_mps; });
    return v;
  }
  double m_t = 0;
  int m_i = 0;
};

}  // namespace

TEST_F(TuneTest, APanelChangeAppliesAtTheNextStep) {
  auto host = loadWith(kSpeedScenario, {});
  ASSERT_TRUE(host);
  sceneOf(*host).start();
  step(*host);
  EXPECT_NEAR(velocity().x(), 2, 1e-5);
  const auto& items = host->tunables().items();
  ASSERT_EQ(items.size(), 3u);
  EXPECT_EQ(items[0].name, "speed");
  EXPECT_EQ(items[0].unit, "m/s");
  EXPECT_EQ(items[0].min, 0);
  EXPECT_EQ(items[0].max, 10);
  EXPECT_EQ(items[0].description, "push speed");
  EXPECT_EQ(items[2].choices, (std::vector<std::string>{"x", "z"}));

  ASSERT_TRUE(host->tunables().set("speed", 7.5));
  step(*host);
  EXPECT_NEAR(velocity().x(), 7.5, 1e-5);
  ASSERT_TRUE(host->tunables().set("reverse", 1));
  ASSERT_TRUE(host->tunables().set("axis", 1));
  step(*host);
  EXPECT_NEAR(velocity().z(), -7.5, 1e-5);
  EXPECT_NEAR(velocity().x(), 0, 1e-5);

  EXPECT_FALSE(host->tunables().set("speed", 11)) << "outside [0, 10]";
  host->tunables().resetAll();
  step(*host);
  EXPECT_NEAR(velocity().x(), 2, 1e-5);
  EXPECT_TRUE(host->errors().empty());
}

TEST_F(TuneTest, SetOnTheCommandLineAppliesFromTheFirstStep) {
  auto host = loadWith(kSpeedScenario, {{"speed", "4"}, {"axis", "z"}});
  ASSERT_TRUE(host);
  sceneOf(*host).start();
  step(*host);
  EXPECT_NEAR(velocity().z(), 4, 1e-5);
  EXPECT_TRUE(host->errors().empty());
}

TEST_F(TuneTest, ABadCommandLineValueIsAnErrorNamingIt) {
  auto host = loadWith(kSpeedScenario, {{"speed", "fast"}});
  ASSERT_TRUE(host);
  sceneOf(*host).start();
  step(*host);
  EXPECT_NEAR(velocity().x(), 2, 1e-5) << "the default stays";
  ASSERT_EQ(host->errors().size(), 1u);
  EXPECT_NE(host->errors()[0].message.find("--set tune.speed=fast: expected a number in m/s"), std::string::npos)
      << host->errors()[0].message;
}

TEST_F(TuneTest, OverridesRoundTripThroughTheFile) {
  const std::string path = (m_root / "config" / "tune" / "tuned.json").string();
  {
    auto host = loadWith(kSpeedScenario, {});
    sceneOf(*host).start();
    step(*host);
    ASSERT_TRUE(host->tunables().set("speed", 3.25));
    ASSERT_TRUE(host->tunables().set("axis", 1));
    ASSERT_TRUE(host->tunables().saveOverrides(path, "tuned"));
  }
  auto host = loadWith(kSpeedScenario, {}, true);
  sceneOf(*host).start();
  step(*host);
  EXPECT_NEAR(velocity().z(), 3.25, 1e-5);
  EXPECT_FALSE(host->tunables()[1].isUserSet()) << "only changed values are saved";
  EXPECT_TRUE(host->errors().empty());
}

TEST_F(TuneTest, ACorruptOverridesFileGivesAMessageAndTheDefaults) {
  const fs::path path = m_root / "config" / "tune" / "tuned.json";
  writeFile(path, "{\"values\": {\"speed\": 3,");
  auto host = loadWith(kSpeedScenario, {}, true);
  ASSERT_TRUE(host);
  sceneOf(*host).start();
  step(*host);
  EXPECT_NEAR(velocity().x(), 2, 1e-5);
  ASSERT_EQ(host->messages().size(), 1u);
  EXPECT_NE(host->messages()[0].text.find(path.string() + ": not valid JSON"), std::string::npos);
  EXPECT_NE(host->messages()[0].text.find("using the defaults"), std::string::npos);

  // A value of the wrong type: that value is refused, by name.
  writeFile(path, R"({"mod": "tuned", "values": {"speed": 30, "reverse": true}})");
  auto again = loadWith(kSpeedScenario, {}, true);
  sceneOf(*again).start();
  step(*again);
  EXPECT_NEAR(velocity().x(), -2, 1e-5) << "reverse applied, speed 30 refused";
  ASSERT_EQ(again->errors().size(), 1u);
  EXPECT_NE(again->errors()[0].message.find("tune.speed=30: outside [0, 10]"), std::string::npos)
      << again->errors()[0].message;
}

TEST_F(TuneTest, BadDeclarationsAreLuaErrorsNamingTheTunable) {
  auto host = load(R"(
return {on_start = function()
  local ok1, e1 = pcall(tune.number, "g", 30, {min = 0, max = 20})
  local ok2, e2 = pcall(tune.number, "g", 1, {maxx = 20})
  local ok3, e3 = pcall(function() tune.bool("g", true) end)
  tune.number("h", 1)
  local ok4, e4 = pcall(tune.bool, "h", true)
  local ok5, e5 = pcall(tune.choice, "c", "d", {choices = {"a", "b"}})
  local ok6, e6 = pcall(tune.get, "nope")
  expect("default outside limits", not ok1 and e1:find("default 30 is outside %[0, 20%]") ~= nil)
  expect("misspelt option", not ok2 and e2:find("unknown field 'maxx'") ~= nil)
  expect("unknown name is declared fresh", ok3)
  expect("one name, one kind", not ok4 and e4:find("already a number tunable") ~= nil)
  expect("default not a choice", not ok5 and e5:find("not one of the choices") ~= nil)
  expect("get undeclared", not ok6 and e6:find("not declared") ~= nil)
  expect("get declared", tune.get("h") == 1)
end})");
  ASSERT_TRUE(host);
  run(*host, 0);
  expectAllHeld(*host);
}

TEST_F(TuneTest, AReloadedDefaultAppliesUnlessTheUserSetAValue) {
  script::Tunables t;
  script::Tunable spec;
  spec.name = "g";
  spec.defaultValue = 9.81;
  spec.min = 0;
  spec.max = 20;
  ASSERT_TRUE(t.declare(spec));
  spec.defaultValue = 5;
  ASSERT_TRUE(t.declare(spec));
  EXPECT_EQ(t[0].value(), 5) << "an edited default takes effect";
  ASSERT_TRUE(t.set("g", 15));
  spec.defaultValue = 6;
  spec.max = 12;
  ASSERT_TRUE(t.declare(spec));
  EXPECT_EQ(t[0].value(), 12) << "the user's 15, clamped to the new max";
  t.reset("g");
  EXPECT_EQ(t[0].value(), 6);
}

}  // namespace tumble::test
