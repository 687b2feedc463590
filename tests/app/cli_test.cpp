// The command line's contract (ARCHITECTURE.md): exit statuses, messages
// that name file and line, check and list.
#include <gtest/gtest.h>

#include <fstream>

#include "tumble_process.h"

namespace tumble::test {

TEST(Cli, DefaultScenarioRunsAndItsExpectationsHold) {
  auto r = runTumble("run base:drop --seconds 6");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST(Cli, FailedExpectationExitsTwo) {
  auto r = runTumble(testMods() + " run good:fails_expectation");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("still at 10 m"), std::string::npos) << r.output;
}

TEST(Cli, ScriptErrorExitsThreeNamesFileAndLineAndTheRunFinishes) {
  auto r = runTumble(testMods() + " run good:runtime_error");
  EXPECT_EQ(r.exitCode, 3) << r.output;
  EXPECT_NE(r.output.find("scenarios/runtime_error.lua:6"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("paused"), std::string::npos) << "a callback failing every step is paused: " << r.output;
}

TEST(Cli, RunawayLoopIsStoppedByTheInstructionBudget) {
  auto r = runTumble(testMods() + " run good:runaway");
  EXPECT_EQ(r.exitCode, 3) << r.output;
  EXPECT_NE(r.output.find("exceeded"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("scenarios/runaway.lua"), std::string::npos) << r.output;
}

TEST(Cli, BadArgumentFromLuaIsAClearScriptError) {
  auto r = runTumble(testMods() + " run good:bad_argument");
  EXPECT_EQ(r.exitCode, 3) << r.output;
  EXPECT_NE(r.output.find("world.box"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mass"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bad_argument.lua:5"), std::string::npos) << r.output;
}

TEST(Cli, SyntaxErrorInAScenarioGivesFileAndLineAndExitsOne) {
  auto r = runTumble(testMods() + " run syntax:syntax_error");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("scenarios/syntax_error.lua:3"), std::string::npos) << r.output;
}

TEST(Cli, UnknownScenarioListsWhatTheModHas) {
  auto r = runTumble(testMods() + " run good:nope");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("boxes"), std::string::npos) << r.output;
  r = runTumble("run nomod:drop");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("base"), std::string::npos) << "lists the mods it found: " << r.output;
}

TEST(Cli, SetPassesParametersToTheScriptAndPhysicsSettingsAreChecked) {
  auto r = runTumble(testMods() + " run good:params --set count=7 --set flag=true");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  r = runTumble(testMods() + " run good:params --set count=seven");
  EXPECT_EQ(r.exitCode, 3) << "a bad --set value is a script error in param(): " << r.output;
  r = runTumble("run base:drop --set physics.nonsense=1");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("physics.substeps"), std::string::npos) << "lists the known settings: " << r.output;
  r = runTumble("run base:drop --integrator nonsense");
  EXPECT_EQ(r.exitCode, 1) << r.output;
}

TEST(Cli, CheckListsEveryProblemOfABrokenMod) {
  auto r = runTumble(std::string("check ") + TUMBLE_TEST_MODS + "/broken");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("version"), std::string::npos) << "manifest: " << r.output;
  EXPECT_NE(r.output.find("syntax_error.lua:3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("also_broken.lua"), std::string::npos) << r.output;
  r = runTumble(std::string("check ") + TUMBLE_TEST_MODS + "/good");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST(Cli, ListShowsModsAndScenarios) {
  auto r = runTumble(testMods() + " list");
  EXPECT_NE(r.output.find("base:drop"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("good:boxes"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("broken"), std::string::npos) << "the broken mod is reported: " << r.output;
}

}  // namespace tumble::test

namespace tumble::test {

// `tumble check` finds references by literal name to things that do not
// exist: emitters, vehicles, input actions, assets; each
// with its file and line; comments are not read. A trailing slash on the
// folder (a shell's completion) is fine.
TEST(Cli, CheckFindsMissingEmittersVehiclesActionsAndAssets) {
  const std::string dir = outDir("check_refs");
  std::filesystem::create_directories(dir + "/refs/scenarios");
  std::ofstream(dir + "/refs/mod.lua") << "return {name = \"refs\", version = \"1.0.0\", title = \"refs\", api = 1}\n";
  std::ofstream(dir + "/refs/scenarios/s.lua") << R"(return {
  terrain = {heightmap = "assets/none.png"},
  on_start = function()
    particles.spawn("base:dustt", {position = {0, 0, 0}})
    particles.burst("sparks", 3, {position = {0, 0, 0}})
    local car = vehicle.spawn("base:hatchbak", {position = {0, 1, 0}})
    world.add_static_model("base:assets/models/rok.obj", {position = {0, 0, 0}})
    -- particles.spawn("commented:out") is not read
    if input.pressed("jump") or input.value("throttle") > 0 then end
  end,
}
)";
  auto r = runTumble("check " + dir + "/refs/");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  for (const char* expected : {"s.lua:2: heightmap \"assets/none.png\": no such file",
                               "s.lua:4: particles.spawn(\"base:dustt\"): no such emitter",
                               "s.lua:6: vehicle.spawn(\"base:hatchbak\"): no such vehicle",
                               "s.lua:7: add_static_model \"base:assets/models/rok.obj\": no such file",
                               "s.lua:9: input.pressed(\"jump\"): no such action"})
    EXPECT_NE(r.output.find(expected), std::string::npos) << expected << "\n" << r.output;
  EXPECT_EQ(r.output.find("particles.burst(\"sparks\")"), std::string::npos) << "base's sparks exists\n" << r.output;
  EXPECT_EQ(r.output.find("commented"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("but the folder is"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("5 problems"), std::string::npos) << r.output;
}

}  // namespace tumble::test
