// The command line as a modder and CI see it: `tumble check` reports
// binding problems with file and line, `tumble list` lists actions, and a
// headless run is driven by injected actions, step by step, reproducibly.
#include <fstream>

#include "input_fixture.h"
#include "tumble_process.h"

namespace tumble::test {

namespace fs = std::filesystem;

namespace {

fs::path writeMod(const fs::path& root, const std::string& name, const std::map<std::string, std::string>& files) {
  fs::create_directories(root / name);
  std::ofstream(root / name / "mod.lua") << "return {name = \"" << name << "\", version = \"1.0.0\", api = 1}\n";
  for (const auto& [file, text] : files) {
    fs::create_directories((root / name / file).parent_path());
    std::ofstream(root / name / file) << text;
  }
  return root / name;
}

}  // namespace

TEST(InputCli, CheckReportsBindingProblemsWithFileAndLine) {
  const fs::path root = testDir();
  fs::path mod = writeMod(root, "flyer", {{"bindings.lua", R"(return {contexts = {flying = {actions = {
  ["flyer.fire"] = {type = "button", bindings = {"key:Spcae"}},
  climb = {type = "axis", bindings = {"keys:W/S"}},
}}}})"}});
  auto r = runTumble("--mods " + root.string() + " check " + mod.string());
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find(mod.string() + "/bindings.lua:2: action \"flyer.fire\".bindings[1]: \"key:Spcae\": "
                                         "unknown key \"Spcae\" (did you mean: Space?)"),
            std::string::npos) << r.output;
  EXPECT_NE(r.output.find("action \"climb\": a new action of mod flyer must be named \"flyer.climb\""),
            std::string::npos) << r.output;
}

TEST(InputCli, ListShowsEachModsActionsByContext) {
  auto r = runTumble("list");
  EXPECT_NE(r.output.find("actions    ui: ui_up, ui_down, ui_select; game: pause_menu, pause, restart, debug_panel, "
                          "screenshot, menu, console, hud; vehicle: throttle, brake, steer (axis), handbrake, "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("steer (axis)"), std::string::npos) << r.output;
}

TEST(InputCli, AHeadlessRunIsDrivenByInjectedActionsAndReproduces) {
  const fs::path root = testDir();
  writeMod(root, "drive", {{"scenarios/auto.lua", R"(
local presses, downs, steer = 0, 0, 0
local ball
return {
  duration = 0.5,
  on_start = function()
    world.plane{}
    ball = world.sphere{radius = 0.5, position = {0, 0.5, 0}, mass = 1}
    input.set_context("vehicle", true)
    input.inject("throttle", 1)      -- the base mod's actions, without depending on base
    input.inject("steer", -0.5)
  end,
  on_update = function(ctx)
    if input.pressed("throttle") then presses = presses + 1 end
    if input.down("throttle") then
      downs = downs + 1
      ball:apply_impulse({input.value("steer") * 0.1, 0, 0})
    end
    steer = input.value("steer")
    if ctx.step == 9 then input.inject("throttle", 0) end
  end,
  on_finish = function()
    expect("pressed once", presses, {min = 1, max = 1})
    expect("down for steps 0..9", downs, {min = 10, max = 10})
    expect("steer injected", steer, {min = -0.5, max = -0.5})
    expect("the ball went left", ball:position().x, {max = -0.1})
  end,
})"}});
  const std::string out = outDir("input_headless");
  auto a = runTumble("--mods " + root.string() + " run drive:auto --report " + out + "/a.json");
  EXPECT_EQ(a.exitCode, 0) << a.output;
  auto b = runTumble("--mods " + root.string() + " run drive:auto --report " + out + "/b.json");
  auto hash = [](const std::string& output) { return output.substr(output.find("state ")); };
  EXPECT_EQ(hash(a.output), hash(b.output)) << "the same injections give the same state hash";
}

}  // namespace tumble::test
