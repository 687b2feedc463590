// mods/<mod>/bindings.lua: what a modder writes, what a mistake reports
// (file, line, action, field, what is expected), how several mods merge,
// and the base mod's own defaults.
#include <fstream>

#include "input_fixture.h"
#include "script/mod_bindings.h"

namespace tumble::test {

namespace fs = std::filesystem;

namespace {

script::ModInfo writeMod(const fs::path& root, const std::string& name, const std::string& bindings) {
  fs::create_directories(root / name);
  std::ofstream(root / name / "bindings.lua") << bindings;
  script::ModInfo m;
  m.name = name;
  m.version = "1.0.0";
  m.dir = (root / name).string();
  return m;
}

std::string allText(const std::vector<script::ModProblem>& problems) {
  std::string out;
  for (const auto& p : problems) out += p.text() + "\n";
  return out;
}

}  // namespace

TEST(BindingsFile, TheBaseModDeclaresEveryActionTheGameAndTheJointsDemosUse) {
  script::ModInfo base;
  base.name = "base";
  base.dir = std::string(TUMBLE_SOURCE_DIR) + "/mods/base";
  script::ModBindings b = script::loadModBindings(base);
  ASSERT_TRUE(b.present);
  EXPECT_TRUE(b.problems.empty()) << allText(b.problems);
  auto expect = [&](const char* name, const char* context, input::ActionType type) {
    const input::ActionDef* a = b.set.findAction(name);
    ASSERT_NE(a, nullptr) << name;
    EXPECT_EQ(a->context, context) << name;
    EXPECT_EQ(a->type, type) << name;
    bool pad = false, other = false;
    for (const auto& bind : a->bindings) {
      pad = pad || bind.source.device == input::Device::PadButton || bind.source.device == input::Device::PadAxis;
      other = other || !(bind.source.device == input::Device::PadButton || bind.source.device == input::Device::PadAxis);
    }
    EXPECT_TRUE(other) << name << " has a keyboard or mouse default";
    // On a pad, Start opens the pause menu, which pauses and restarts; the
    // plain pause toggle, restart, screenshot and the debug panel are keys.
    const std::string n = name;
    if (n != "screenshot" && n != "pause" && n != "restart" && n != "debug_panel") {
      EXPECT_TRUE(pad) << name << " has a gamepad default";
    }
  };
  using T = input::ActionType;
  for (const char* n : {"throttle", "brake", "handbrake", "gear_up", "gear_down", "reset", "camera"})
    expect(n, "vehicle", T::Button);
  expect("steer", "vehicle", T::Axis);
  for (const char* n : {"grab", "impulse", "more_links", "fewer_links", "dt_up", "dt_down"}) expect(n, "interact", T::Button);
  for (const char* n : {"pause_menu", "pause", "restart", "debug_panel", "screenshot", "menu"}) expect(n, "game", T::Button);
  for (const char* n : {"ui_up", "ui_down", "ui_select"}) expect(n, "ui", T::Button);
  EXPECT_EQ(toText(b.set.findAction("pause_menu")->bindings[0]), "key:Escape");
  EXPECT_EQ(toText(b.set.findAction("grab")->bindings[0]), "mouse:left");
  EXPECT_GT(b.set.findContext("game")->priority, b.set.findContext("vehicle")->priority);
  EXPECT_GT(b.set.findContext("ui")->priority, b.set.findContext("game")->priority) << "menu keys win while it is open";
}

TEST(BindingsFile, ATableBindingCarriesItsModifiersAndTheActionsApplyToTheRest) {
  auto mod = writeMod(testDir(), "base", R"(
return {contexts = {fly = {priority = 3, enabled = false, actions = {
  roll = {type = "axis", invert = true, bindings = {"keys:Q/E", {"pad_axis:rightx", dead_zone = 0.1, curve = 2}}},
}}}}
)");
  auto b = script::loadModBindings(mod);
  ASSERT_TRUE(b.problems.empty()) << allText(b.problems);
  const input::ContextDef* fly = b.set.findContext("fly");
  ASSERT_NE(fly, nullptr);
  EXPECT_EQ(fly->priority, 3);
  EXPECT_FALSE(fly->enabled);
  const input::ActionDef* roll = b.set.findAction("roll");
  ASSERT_NE(roll, nullptr);
  ASSERT_EQ(roll->bindings.size(), 2u);
  EXPECT_TRUE(roll->bindings[0].modifiers.invert) << "the action's invert reaches the key pair";
  EXPECT_EQ(roll->bindings[1].modifiers.deadZone, 0.1);
  EXPECT_EQ(roll->bindings[1].modifiers.curve, 2);
  EXPECT_TRUE(roll->bindings[1].modifiers.invert);
}

TEST(BindingsFile, MistakesNameTheFileLineActionFieldAndWhatIsExpected) {
  auto mod = writeMod(testDir(), "base", R"(return {
  contexts = {
    vehicle = {
      priority = "high",
      actions = {
        fire = {type = "button", bindings = {"key:Spcae"}},
        steer = {type = "button", bindings = {"keys:A/D"}},
        jump = {type = "buton", bindings = {"key:J"}},
        look = {type = "axis", bindings = {{"pad_axis:leftx", dead_zone = 2}}, invrt = true},
      },
    },
  },
})");
  auto b = script::loadModBindings(mod);
  const std::string text = allText(b.problems);
  const std::string file = mod.dir + "/bindings.lua";
  EXPECT_NE(text.find(file + ":4: contexts.vehicle.priority: expected an integer"), std::string::npos) << text;
  EXPECT_NE(text.find(file + ":6: action \"fire\".bindings[1]: \"key:Spcae\": unknown key \"Spcae\" (did you mean: Space"),
            std::string::npos) << text;
  EXPECT_NE(text.find(file + ":7: action \"steer\".bindings[1]: \"keys:A/D\" is a key pair"), std::string::npos) << text;
  EXPECT_NE(text.find(file + ":8: action \"jump\".type: expected \"button\""), std::string::npos) << text;
  EXPECT_NE(text.find("unknown field 'invrt' (did you mean: invert?)"), std::string::npos) << text;
  EXPECT_NE(text.find("action \"look\".bindings[1].dead_zone"), std::string::npos) << text;
  // Everything valid is still there.
  EXPECT_NE(b.set.findAction("fire"), nullptr);
  EXPECT_EQ(b.set.findAction("jump"), nullptr);
}

TEST(BindingsFile, ASyntaxErrorOrAWrongShapeIsOneClearProblem) {
  auto broken = writeMod(testDir(), "base", "return {contexts = {\n  x = {\n}\n");
  auto b = script::loadModBindings(broken);
  ASSERT_EQ(b.problems.size(), 1u);
  EXPECT_GT(b.problems[0].line, 0) << b.problems[0].text();
  auto notTable = writeMod(testDir() / "2", "base", "return 42");
  auto c = script::loadModBindings(notTable);
  ASSERT_EQ(c.problems.size(), 1u);
  EXPECT_NE(c.problems[0].message.find("must return a table"), std::string::npos);
}

TEST(BindingsFile, LaterModsMergeByLoadOrderUnderTheirOwnNames) {
  const fs::path root = testDir();
  auto base = writeMod(root, "base", R"(return {contexts = {vehicle = {priority = 10, actions = {
    throttle = {type = "button", bindings = {"key:W"}},
    steer = {type = "axis", bindings = {"keys:A/D"}},
  }}}})");
  auto racing = writeMod(root, "racing", R"(return {contexts = {vehicle = {priority = 20, actions = {
    throttle = {type = "button", bindings = {"key:Up"}},
    ["racing.nitro"] = {type = "button", bindings = {"key:N"}},
    boost = {type = "button", bindings = {"key:B"}},
    steer = {type = "button", bindings = {"key:X"}},
  }}}})");
  auto merged = script::loadBindings({base, racing});
  const std::string text = allText(merged.problems);
  EXPECT_EQ(toText(merged.set.findAction("throttle")->bindings.at(0)), "key:Up") << "a later mod changes defaults";
  EXPECT_NE(merged.set.findAction("racing.nitro"), nullptr);
  EXPECT_EQ(merged.set.findAction("boost"), nullptr);
  EXPECT_NE(text.find("must be named \"racing.boost\""), std::string::npos) << text;
  EXPECT_EQ(merged.set.findAction("steer")->type, input::ActionType::Axis) << "the type cannot change";
  EXPECT_NE(text.find("action \"steer\" of mod racing is a button"), std::string::npos) << text;
  EXPECT_EQ(merged.set.findContext("vehicle")->priority, 20);
}

}  // namespace tumble::test
