// Scenario parameters a scenario declares (its `params` table): the command
// line is checked against them before the run, param() falls back to the
// declared defaults, and the report lists the values each run used.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tumble_process.h"

namespace tumble::test {

TEST(ScenarioParams, DeclaredDefaultsAndSetValuesReachTheScriptAndTheReport) {
  const std::string dir = outDir("declared_params");
  // 1.25 m: the ball lands after sqrt(2.5 / 9.81) = 0.505 s.
  auto r = runTumble(testMods() + " run good:declared_params --set height=1.25 --set bounce=true --report " + dir + "/r.json");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(dir + "/r.json");
  auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["params"]["height"], 1.25);
  EXPECT_EQ(report["params"]["label"], "ball");  // the declared default
  EXPECT_EQ(report["params"]["bounce"], true);
  r = runTumble(testMods() + " run good:declared_params");  // defaults: 5 m
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST(ScenarioParams, AnUndeclaredOrMistypedSetIsRefusedBeforeTheRun) {
  auto r = runTumble(testMods() + " run good:declared_params --set heigth=2");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("good:declared_params has no parameter 'heigth' (its parameters: bounce, height, label"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("steps"), std::string::npos) << "nothing ran: " << r.output;
  r = runTumble(testMods() + " run good:declared_params --set height=tall");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("'height' is a number in m (default 5)"), std::string::npos) << r.output;
  r = runTumble(testMods() + " run good:declared_params --set bounce=yes");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("'bounce' is true or false"), std::string::npos) << r.output;
}

TEST(ScenarioParams, AScenarioWithoutADeclarationStillTakesAnySet) {
  // good:params declares nothing: --set reaches param() as before.
  auto r = runTumble(testMods() + " run good:params --set count=7 --set flag=true");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST(ScenarioParams, DriveExposesGripAndSpringRate) {
  const std::string dir = outDir("drive_params");
  auto r = runTumble("run base:drive --steps 1 --report " + dir + "/r.json");
  ASSERT_EQ(r.exitCode, 2) << r.output;  // one step drives nowhere: distance expectations fail
  std::ifstream in(dir + "/r.json");
  auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["params"]["grip"], 1);
  EXPECT_EQ(report["params"]["spring_rate"], 1);
  // A grip of 1.5 is a different car: the run's state differs after 2 s.
  const std::string base = runTumble("run base:drive --seconds 2").output;
  const std::string grippy = runTumble("run base:drive --seconds 2 --set grip=1.5").output;
  auto hashOf = [](const std::string& s) { return s.substr(s.find("state ") + 6, 16); };
  EXPECT_NE(hashOf(base), hashOf(grippy));
}

}  // namespace tumble::test
