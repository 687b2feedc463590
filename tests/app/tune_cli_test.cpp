// Tunables from the command line: `--set tune.NAME=VALUE` changes what a
// headless run does, the report lists the values used, a bad value is a
// script error naming it, and `run` ignores a player's saved overrides.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tumble_process.h"

namespace tumble::test {

namespace {
nlohmann::json report(const std::string& args, const std::string& dir, int expectedExit, const std::string& env = "") {
  std::string path = dir + "/report.json";
  auto r = runTumble(testMods() + " " + args + " --report " + path, env);
  EXPECT_EQ(r.exitCode, expectedExit) << r.output;
  std::ifstream in(path);
  if (!in) return {};
  return nlohmann::json::parse(in);
}

double distance(const nlohmann::json& j) {
  for (const auto& e : j["expectations"])
    if (e["name"] == "distance") return e["value"].get<double>();
  ADD_FAILURE() << "no distance expectation";
  return 0;
}
}  // namespace

TEST(TuneCli, SetChangesTheRunAndTheReportListsIt) {
  std::string dir = outDir("tune_set");
  auto base = report("run good:tuned", dir, 0);
  EXPECT_NEAR(distance(base), 1.0 * 2.0, 1e-3) << "1 m/s for 2 s";
  EXPECT_EQ(base["tunables"]["speed"], 1.0);
  auto fast = report("run good:tuned --set tune.speed=4", dir, 0);
  EXPECT_NEAR(distance(fast), 4.0 * 2.0, 1e-3);
  EXPECT_EQ(fast["tunables"]["speed"], 4.0);
  auto qualified = report("run good:tuned --set tune.good.speed=2.5", dir, 0);
  EXPECT_NEAR(distance(qualified), 2.5 * 2.0, 1e-3);
}

TEST(TuneCli, ABadValueIsAScriptErrorThatNamesIt) {
  std::string dir = outDir("tune_bad");
  auto j = report("run good:tuned --set tune.speed=11", dir, 3);
  ASSERT_EQ(j["script_errors"].size(), 1u);
  EXPECT_NE(j["script_errors"][0]["message"].get<std::string>().find("--set tune.speed=11: outside [0, 10]"),
            std::string::npos)
      << j["script_errors"][0];
  EXPECT_NEAR(distance(j), 2.0, 1e-3) << "the default applies";
}

TEST(TuneCli, AMisspeltNameIsAnErrorListingTheDeclaredOnes) {
  std::string dir = outDir("tune_misspelt");
  auto j = report("run good:tuned --set tune.sped=4", dir, 3);
  ASSERT_EQ(j["script_errors"].size(), 1u);
  EXPECT_EQ(j["script_errors"][0]["message"],
            "--set tune.sped: the scenario declared no tunable \"sped\" (declared: speed)");
}

TEST(TuneCli, RunIgnoresSavedOverridesSoItDependsOnlyOnItsCommandLine) {
  std::string dir = outDir("tune_overrides");
  std::filesystem::create_directories(dir + "/config/tune");
  std::ofstream(dir + "/config/tune/good.json") << R"({"mod": "good", "values": {"speed": 9}})";
  auto j = report("run good:tuned", dir, 0, "TUMBLE_CONFIG_DIR=" + dir + "/config ");
  EXPECT_NEAR(distance(j), 2.0, 1e-3);
}

}  // namespace tumble::test
