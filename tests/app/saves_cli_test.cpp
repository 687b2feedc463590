// Headless runs leave the player's files alone: `run` keeps the scenario's
// save.write files in a throw-away folder unless given --save-dir, so the
// player's save folder never changes and two identical runs report the same.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "tumble_process.h"

namespace tumble::test {
namespace {

namespace fs = std::filesystem;

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in, nullptr, false);
}

// Every save location the player's game would read: $TUMBLE_SAVE_DIR and
// the XDG / HOME fallbacks, all pointed into one folder for the test.
std::string playerEnv(const std::string& home) {
  return "env TUMBLE_SAVE_DIR=" + home + "/saves XDG_DATA_HOME=" + home + "/xdg HOME=" + home + " ";
}

TEST(SavesCli, RunLeavesThePlayersSavesAloneAndRepeats) {
  const std::string dir = outDir("saves_cli_throwaway");
  // The throw-away folder goes under $TMPDIR: a folder of the test's own.
  fs::create_directories(dir + "/tmp");
  const std::string env = playerEnv(dir + "/home") + "TMPDIR=" + dir + "/tmp ";
  const std::string args = "run base:time_trial --set autopilot=1 --report ";
  auto first = runTumble(args + dir + "/first.json", env);
  ASSERT_EQ(first.exitCode, 0) << first.output;
  auto second = runTumble(args + dir + "/second.json", env);
  ASSERT_EQ(second.exitCode, 0) << second.output;
  // The lap was saved and read back inside each run (its expectations), yet
  // nothing reached any folder the player's game reads.
  EXPECT_FALSE(fs::exists(dir + "/home")) << "a headless run wrote into the player's folders";
  const auto a = readJson(dir + "/first.json"), b = readJson(dir + "/second.json");
  ASSERT_FALSE(a.is_discarded());
  ASSERT_FALSE(b.is_discarded());
  EXPECT_EQ(a["expectations"], b["expectations"]);
  EXPECT_EQ(a["state_hash"], b["state_hash"]);
  bool readBack = false;
  for (const auto& e : a["expectations"]) readBack = readBack || e["name"] == "saved value round-trips";
  EXPECT_TRUE(readBack) << "the first run saved a new best lap (nothing was there before)";
  EXPECT_TRUE(fs::is_empty(dir + "/tmp")) << "the throw-away folder is removed at exit";
}

TEST(SavesCli, SaveDirKeepsTheSavesThere) {
  const std::string dir = outDir("saves_cli_dir");
  auto r = runTumble("run base:time_trial --set autopilot=1 --save-dir " + dir + "/saves");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto saved = readJson(dir + "/saves/base/time_trial.json");
  ASSERT_FALSE(saved.is_discarded()) << "the best lap is in the folder given";
  EXPECT_GT(saved["best_s"].get<double>(), 0);
}

}  // namespace
}  // namespace tumble::test
