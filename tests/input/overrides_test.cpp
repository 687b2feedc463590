// The player's rebinding survives a restart: overrides round-trip through
// bindings.json, only differences are written, the write is atomic, and a
// corrupt file is reported, ignored and kept until the player saves.
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/bindings_menu.h"
#include "core/file_util.h"
#include "input/overrides_file.h"
#include "input_fixture.h"

namespace tumble::test {

namespace fs = std::filesystem;
using input::ActionType;
using input::InputSystem;

namespace {

input::BindingSet defaults() {
  input::BindingSet s;
  s.contexts = {{"vehicle", 10, true}, {"game", 100, true}};
  s.actions = {actionDef("throttle", ActionType::Button, "vehicle", {"key:W", "pad_axis:righttrigger"}),
               actionDef("steer", ActionType::Axis, "vehicle", {"keys:A/D", "pad_axis:leftx;dead_zone=0.15;curve=1.5"}),
               actionDef("reset", ActionType::Button, "vehicle", {"key:R"}),
               actionDef("pause", ActionType::Button, "game", {"key:P"})};
  return s;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST(InputText, EveryBindingFormSurvivesTextAndBack) {
  for (const char* text : {"key:W", "key:ctrl+shift+R", "key:Space", "key:Keypad 8", "key:;", "key:[", "keys:A/D",
                           "keys:Left/Right", "mouse:left", "mouse:x2", "mouse_axis:y;scale=0.002", "wheel:y",
                           "pad:a", "pad:dpup", "pad_axis:leftx;dead_zone=0.15;curve=1.5", "pad_axis:lefty-;invert",
                           "pad_axis:righttrigger"}) {
    auto b = input::parseBinding(text);
    ASSERT_TRUE(b) << text << ": " << b.error();
    auto again = input::parseBinding(input::toText(*b));
    ASSERT_TRUE(again) << input::toText(*b);
    EXPECT_EQ(*again, *b) << text << " -> " << input::toText(*b);
  }
  EXPECT_EQ(input::toText(*input::parseBinding("KEYS:a/d")), "keys:A/D") << "names are not case sensitive";
}

TEST(InputText, BadTextSaysWhatIsWrongAndSuggestsNames) {
  auto key = input::parseBinding("key:Spcae");
  ASSERT_FALSE(key);
  EXPECT_NE(key.error().find("unknown key \"Spcae\""), std::string::npos) << key.error();
  EXPECT_NE(key.error().find("did you mean: Space"), std::string::npos) << key.error();
  auto kind = input::parseBinding("keyboard:W");
  ASSERT_FALSE(kind);
  EXPECT_NE(kind.error().find("did you mean: key"), std::string::npos) << kind.error();
  auto pad = input::parseBinding("pad_axis:leftz");
  ASSERT_FALSE(pad);
  EXPECT_NE(pad.error().find("leftx"), std::string::npos) << pad.error();
  auto mod = input::parseBinding("key:W;deadzone=0.1");
  ASSERT_FALSE(mod);
  EXPECT_NE(mod.error().find("dead_zone"), std::string::npos) << mod.error();
  EXPECT_FALSE(input::parseBinding("W")) << "the kind is required";
  EXPECT_FALSE(input::parseBinding("pad_axis:leftx;dead_zone=1.5")) << "dead zone past 0.95";
}

TEST(InputOverrides, SaveThenLoadGivesTheSameBindingsAndWritesOnlyDifferences) {
  const fs::path path = testDir() / "cfg" / "bindings.json";  // the folder does not exist yet
  {
    InputSystem in(defaults());
    in.setBindings(in.find("throttle"), {bind("key:I"), bind("pad_axis:righttrigger")});
    in.setBindings(in.find("reset"), {});  // unbound on purpose
    in.setBindings(in.find("pause"), {bind("key:P")});  // same as the default: not a difference
    ASSERT_TRUE(input::saveOverrides(path.string(), in.overrides()));
  }
  auto written = nlohmann::json::parse(slurp(path));
  EXPECT_EQ(written["format"], "tumble-bindings");
  ASSERT_EQ(written["overrides"].size(), 2u) << written.dump();
  EXPECT_EQ(written["overrides"]["throttle"], nlohmann::json({"key:I", "pad_axis:righttrigger"}));
  EXPECT_EQ(written["overrides"]["reset"], nlohmann::json::array());
  for (const auto& entry : fs::directory_iterator(path.parent_path()))
    EXPECT_EQ(entry.path().filename(), "bindings.json") << "a temporary file was left behind";

  InputSystem next(defaults());  // the next start
  auto loaded = input::loadOverrides(path.string());
  ASSERT_TRUE(loaded) << loaded.error();
  EXPECT_TRUE(next.applyOverrides(*loaded).empty());
  EXPECT_EQ(next.bindings(next.find("throttle")), (std::vector<input::Binding>{bind("key:I"), bind("pad_axis:righttrigger")}));
  EXPECT_TRUE(next.bindings(next.find("reset")).empty());
  EXPECT_EQ(next.bindings(next.find("steer")), defaults().actions[1].bindings) << "untouched actions keep defaults";
  EXPECT_EQ(next.overrides(), *loaded) << "saving again writes the same differences";

  // The new key drives the action; the old one no longer does.
  next.handleEvent(keyEvent(SDL_SCANCODE_W, true));
  next.step();
  EXPECT_FALSE(next.down(next.find("throttle")));
  next.handleEvent(keyEvent(SDL_SCANCODE_I, true));
  next.step();
  EXPECT_TRUE(next.pressed(next.find("throttle")));

  next.resetAllBindings();
  EXPECT_TRUE(next.overrides().empty()) << "defaults again: nothing to save";
}

TEST(InputOverrides, OverridesOfActionsNotLoadedAreKeptWhenSaving) {
  InputSystem in(defaults());
  input::Overrides o{{"racing.nitro", {"key:N"}}, {"throttle", {"key:T"}}};
  in.applyOverrides(o);
  EXPECT_EQ(in.overrides(), o) << "racing.nitro belongs to a mod not loaded now; it must not be lost";
}

TEST(InputOverrides, AnUnparsableEntryIsSkippedWithAMessage) {
  InputSystem in(defaults());
  auto problems = in.applyOverrides({{"throttle", {"key:Nope", "key:T"}}, {"reset", {"keys:A/D"}}});
  ASSERT_EQ(problems.size(), 2u);
  const std::string all = problems[0] + "\n" + problems[1];
  EXPECT_NE(all.find("action \"throttle\": \"key:Nope\": unknown key"), std::string::npos) << all;
  EXPECT_NE(all.find("action \"reset\": \"keys:A/D\" is a key pair, which only an axis takes"), std::string::npos) << all;
  EXPECT_EQ(in.bindings(in.find("throttle")), std::vector<input::Binding>{bind("key:T")});
}

TEST(InputOverrides, AMissingFileMeansNoOverrides) {
  auto loaded = input::loadOverrides((testDir() / "none.json").string());
  ASSERT_TRUE(loaded);
  EXPECT_TRUE(loaded->empty());
}

TEST(InputOverrides, ACorruptFileIsReportedFallsBackToDefaultsAndIsKeptUntilSave) {
  const fs::path path = testDir() / "bindings.json";
  const std::string corrupt = "{\n  \"format\": \"tumble-bindings\",\n  \"version\": 1,\n  \"overrides\": {\"throttle\": [\"key:I\",]}\n}\n";
  std::ofstream(path) << corrupt;
  auto loaded = input::loadOverrides(path.string());
  ASSERT_FALSE(loaded);
  EXPECT_NE(loaded.error().find(path.string() + ":4:"), std::string::npos) << "file and line: " << loaded.error();

  InputSystem in(defaults());
  app::BindingsMenu menu(in, path.string());
  EXPECT_NE(menu.status().find("using the default bindings"), std::string::npos) << menu.status();
  EXPECT_EQ(in.bindings(in.find("throttle")), defaults().actions[0].bindings);
  EXPECT_EQ(slurp(path), corrupt) << "not deleted, not overwritten";

  in.setBindings(in.find("throttle"), {bind("key:I")});
  ASSERT_TRUE(menu.save());  // the player saves: now it is replaced
  auto reloaded = input::loadOverrides(path.string());
  ASSERT_TRUE(reloaded) << reloaded.error();
  EXPECT_EQ(reloaded->at("throttle"), std::vector<std::string>{"key:I"});
}

TEST(InputOverrides, WrongShapesNameTheField) {
  const fs::path dir = testDir();
  auto check = [&](const std::string& text, const std::string& expected) {
    std::ofstream(dir / "b.json") << text;
    auto r = input::loadOverrides((dir / "b.json").string());
    ASSERT_FALSE(r) << text;
    EXPECT_NE(r.error().find(expected), std::string::npos) << r.error();
  };
  check("[]", "not an object");
  check(R"({"format": "other", "version": 1})", "\"format\"");
  check(R"({"format": "tumble-bindings", "version": 1, "overrides": {"throttle": "key:W"}})", "overrides.throttle");
  check(R"({"format": "tumble-bindings", "version": 1, "overrides": {"throttle": [3]}})", "overrides.throttle[1]");
}

TEST(InputOverrides, TheConfigFolderComesFromTheEnvironment) {
  setenv("TUMBLE_CONFIG_DIR", "/tmp/tumble-cfg-test", 1);
  EXPECT_EQ(input::bindingsConfigPath(), "/tmp/tumble-cfg-test/bindings.json");
  unsetenv("TUMBLE_CONFIG_DIR");
  setenv("XDG_CONFIG_HOME", "/tmp/xdg", 1);
  EXPECT_EQ(input::bindingsConfigPath(), "/tmp/xdg/tumble/bindings.json");
  unsetenv("XDG_CONFIG_HOME");
}

}  // namespace tumble::test
