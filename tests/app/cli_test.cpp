// The command line's contract (ARCHITECTURE.md): exit statuses, messages
// that name file and line, check and list.
#include <gtest/gtest.h>

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
