// Terrain in a run: a scene creates terrain memory only
// when asked for, and the report shows it in `subsystems` and `peak_rss_mb`.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tumble_process.h"

namespace tumble::test {
namespace {

nlohmann::json runReport(const std::string& args, const std::string& dir) {
  const std::string path = dir + "/report.json";
  auto r = runTumble(args + " --report " + path);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(path);
  if (!in) return {};
  return nlohmann::json::parse(in);
}

bool lists(const nlohmann::json& j, const std::string& name) {
  auto s = j["subsystems"].get<std::vector<std::string>>();
  return std::find(s.begin(), s.end(), name) != s.end();
}

}  // namespace

// 1025^2 samples: 2 MiB of heights (plus the tree) that only the terrain run pays.
TEST(Terrain, OnlyAScenarioWithTerrainCreatesIt) {
  const std::string dir = outDir("terrain_memory");
  auto without = runReport(testMods() + " run good:boxes --steps 10", dir);
  auto with = runReport(testMods() + " run good:boxes --steps 10 --set terrain.generate=5 --set terrain.size=1025", dir);
  ASSERT_FALSE(without.empty());
  ASSERT_FALSE(with.empty());
  EXPECT_FALSE(lists(without, "terrain"));
  EXPECT_TRUE(lists(with, "terrain"));
  const double a = without["peak_rss_mb"].get<double>(), b = with["peak_rss_mb"].get<double>();
  std::printf("peak_rss_mb without terrain %.2f, with a 1025^2 terrain %.2f\n", a, b);
  EXPECT_GE(b - a, 2.0);
}

TEST(Terrain, BadSettingsAndFilesGiveClearErrors) {
  auto r = runTumble(testMods() + " run good:boxes --steps 1 --set terrain.heightmap=/no/such/map.png");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("/no/such/map.png"), std::string::npos) << r.output;
  r = runTumble(testMods() + " run good:boxes --steps 1 --set terrain.generate=1 --set terrain.sise=9");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("terrain.sise"), std::string::npos) << r.output;
}

// `tumble terrain materials MAP` gives a designer the painted layers to edit
// (one pixel per block) and never overwrites their work without --force.
TEST(Terrain, MaterialsCommandWritesEditableLayersBesideTheMap) {
  const std::string dir = outDir("terrain_materials_cmd");
  const std::string map = dir + "/m.png";
  std::filesystem::remove(dir + "/m.friction.png");
  auto r = runTumble("terrain gen --width 33 --height 17 --seed 3 --out " + map);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* layer : {"texture", "bump", "friction", "sound", "softness"})
    std::filesystem::remove(dir + "/m." + layer + ".png");
  r = runTumble("terrain materials " + map);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* layer : {"texture", "bump", "friction", "sound", "softness"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/m." + layer + ".png")) << layer;
  // A second call would destroy edits: refused, naming the file.
  r = runTumble("terrain materials " + map);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("m.texture.png exists"), std::string::npos) << r.output;
  EXPECT_EQ(runTumble("terrain materials --force " + map).exitCode, 0);
  // The scene plays with them.
  r = runTumble(testMods() + " run good:boxes --steps 5 --set terrain.heightmap=" + map);
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

}  // namespace tumble::test
