// The run report (ARCHITECTURE.md): every field, measured figures,
// subsystems actually created, and the state hash proving determinism.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tumble_process.h"

namespace tumble::test {

namespace {
nlohmann::json runAndRead(const std::string& args, const std::string& dir, int expectedExit = 0) {
  std::string path = dir + "/report.json";
  auto r = runTumble(args + " --report " + path);
  EXPECT_EQ(r.exitCode, expectedExit) << r.output;
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << "no report at " << path;
  if (!in) return {};
  return nlohmann::json::parse(in);
}
}  // namespace

TEST(Report, EveryFieldIsPresentAndMeasured) {
  auto j = runAndRead("run base:drop --seconds 5", outDir("report_fields"));
  for (const char* key : {"scenario", "seed", "dt", "substeps", "integrator", "steps", "simulated_seconds",
                          "wall_seconds", "step_ms", "subsystems", "peak_rss_mb", "counts", "error", "expectations",
                          "script_errors", "state_hash"})
    EXPECT_TRUE(j.contains(key)) << key;
  for (const char* key : {"total", "startup", "physics", "script", "particles", "render"})
    EXPECT_TRUE(j["wall_seconds"].contains(key)) << key;
  for (const char* key : {"median", "p99", "max"}) EXPECT_TRUE(j["step_ms"].contains(key)) << key;
  for (const char* key : {"bodies", "joints", "contacts_max", "particles_max"})
    EXPECT_TRUE(j["counts"].contains(key)) << key;
  for (const char* key :
       {"energy_rel_drift_max", "penetration_max_m", "joint_error_max_m", "momentum_rel_drift_max", "nan_events"})
    EXPECT_TRUE(j["error"].contains(key)) << key;
  EXPECT_EQ(j["scenario"], "base:drop");
  EXPECT_EQ(j["steps"], 300);
  EXPECT_DOUBLE_EQ(j["simulated_seconds"].get<double>(), 5.0);
  // Figures that exist in this scene are measured, not zero.
  EXPECT_GT(j["wall_seconds"]["total"].get<double>(), 0);
  EXPECT_GT(j["wall_seconds"]["startup"].get<double>(), 0);
  EXPECT_GT(j["wall_seconds"]["physics"].get<double>(), 0);
  EXPECT_GT(j["wall_seconds"]["script"].get<double>(), 0);
  EXPECT_GT(j["step_ms"]["median"].get<double>(), 0);
  EXPECT_GE(j["step_ms"]["max"].get<double>(), j["step_ms"]["p99"].get<double>());
  EXPECT_GT(j["peak_rss_mb"].get<double>(), 1);
  EXPECT_GT(j["counts"]["bodies"].get<int>(), 10);
  EXPECT_GT(j["counts"]["contacts_max"].get<int>(), 0);
  EXPECT_GT(j["error"]["penetration_max_m"].get<double>(), 0) << "resting contacts overlap by about the slop";
  EXPECT_LT(j["error"]["penetration_max_m"].get<double>(), 0.1);
  EXPECT_EQ(j["error"]["nan_events"], 0);
  EXPECT_EQ(j["state_hash"].get<std::string>().size(), 16u);
  ASSERT_EQ(j["expectations"].size(), 4u);
  for (const auto& e : j["expectations"]) {
    EXPECT_TRUE(e["ok"].get<bool>()) << e.dump();
    for (const char* key : {"name", "ok", "value", "limit"}) EXPECT_TRUE(e.contains(key)) << key;
  }
}

TEST(Report, HeadlessRunsCreateNoRenderer) {
  auto j = runAndRead("run base:drop", outDir("report_headless"));
  auto subsystems = j["subsystems"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(subsystems.begin(), subsystems.end(), "physics"), subsystems.end());
  EXPECT_EQ(std::find(subsystems.begin(), subsystems.end(), "render"), subsystems.end());
  EXPECT_EQ(j["wall_seconds"]["render"].get<double>(), 0);
}

TEST(Report, SameInputsGiveTheSameStateHashAndADifferentSeedDoesNot) {
  std::string dir = outDir("report_determinism");
  auto a = runAndRead("run base:drop", dir);
  auto b = runAndRead("run base:drop", dir);
  auto c = runAndRead("run base:drop --seed 2", dir);
  EXPECT_EQ(a["state_hash"], b["state_hash"]);
  EXPECT_NE(a["state_hash"], c["state_hash"]);
}

TEST(Report, TheStateHashCoversRopesAndEffectParticlesNotOnlyBodies) {
  // good:unseen_state has no moving body: only a rope and an emitter.
  std::string dir = outDir("report_unseen_state");
  auto a = runAndRead(testMods() + " run good:unseen_state", dir);
  auto b = runAndRead(testMods() + " run good:unseen_state", dir);
  auto stiffer = runAndRead(testMods() + " run good:unseen_state --set k=3000", dir);
  auto busier = runAndRead(testMods() + " run good:unseen_state --set rate=40", dir);
  EXPECT_EQ(a["state_hash"], b["state_hash"]);
  EXPECT_NE(a["state_hash"], stiffer["state_hash"]);
  EXPECT_NE(a["state_hash"], busier["state_hash"]);
}

TEST(Report, ScriptErrorsNameModFileLineAndTraceback) {
  auto j = runAndRead(testMods() + " run good:runtime_error", outDir("report_errors"), 3);
  ASSERT_FALSE(j["script_errors"].empty());
  const auto& e = j["script_errors"][0];
  EXPECT_EQ(e["mod"], "good");
  EXPECT_EQ(e["file"], "scenarios/runtime_error.lua");
  EXPECT_EQ(e["line"], 6);
  EXPECT_NE(e["message"].get<std::string>().find("nothing"), std::string::npos) << e.dump();
  EXPECT_NE(e["traceback"].get<std::string>().find("traceback"), std::string::npos) << e.dump();
  // The run still finished: on_finish ran after the errors.
  ASSERT_EQ(j["expectations"].size(), 1u);
  EXPECT_TRUE(j["expectations"][0]["ok"].get<bool>());
}

TEST(Report, ReportIsWrittenAtomicallyAndAnUnwritablePathIsAnError) {
  auto r = runTumble("run base:drop --seconds 0.1 --report /nonexistent-dir/r.json");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("/nonexistent-dir/r.json"), std::string::npos) << r.output;
}

}  // namespace tumble::test
