// Particles from the command line: a scene without emitters creates no
// particle system (the report says so), one with emitters reports it with its
// counts and time, and `tumble check` names every bad emitter field and line.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stb/stb_image.h>

#include "tumble_process.h"

namespace tumble::test {

namespace {
nlohmann::json report(const std::string& args, const std::string& name) {
  const std::string path = outDir(name) + "/report.json";
  auto r = runTumble(args + " --report " + path);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(path);
  return in ? nlohmann::json::parse(in) : nlohmann::json{};
}
bool has(const nlohmann::json& list, const std::string& name) {
  auto v = list.get<std::vector<std::string>>();
  return std::find(v.begin(), v.end(), name) != v.end();
}
// Fire-coloured pixels: bright, red >= green > blue by a margin. Nothing else
// in base:effects (sky, grey ground, brown logs, tan crate, blue sled) is.
int firePixels(const std::string& path) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
  EXPECT_NE(data, nullptr) << path;
  if (!data) return 0;
  int count = 0;
  for (int i = 0; i < w * h; ++i) {
    int r = data[3 * i], g = data[3 * i + 1], b = data[3 * i + 2];
    count += r > 200 && g > 110 && r >= g && b + 70 < g;
  }
  stbi_image_free(data);
  return count;
}
}  // namespace

TEST(ParticlesCli, TheEffectsScenarioShowsItsParticlesInAScreenshot) {
  const std::string dir = outDir("particles_screenshot");
  // At t = 0 no step has run: emitters exist, particles not yet.
  auto r = runTumble("run base:effects --screenshot " + dir + "/t0.png --at 0 --width 960 --height 540");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = runTumble("run base:effects --screenshot " + dir + "/t2.png --at 2 --width 960 --height 540");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_LT(firePixels(dir + "/t0.png"), 5);
  EXPECT_GT(firePixels(dir + "/t2.png"), 30) << "the fire shows; pictures in " << dir;
}

TEST(ParticlesCli, ASceneWithoutEmittersCreatesNoParticleSystem) {
  auto j = report("run base:drop", "particles_none");
  EXPECT_FALSE(has(j["subsystems"], "particles")) << j["subsystems"].dump();
  EXPECT_EQ(j["counts"]["particles_max"], 0);
  EXPECT_EQ(j["wall_seconds"]["particles"].get<double>(), 0);
}

TEST(ParticlesCli, ASceneWithEmittersReportsThemAndStaysHeadless) {
  auto j = report(testMods() + " run good:puffs", "particles_some");
  EXPECT_TRUE(has(j["subsystems"], "particles")) << j["subsystems"].dump();
  EXPECT_FALSE(has(j["subsystems"], "render")) << "headless: no GL";
  // 50/s x 1 s mean life: about 50 live puffs after the first 1.5 s.
  EXPECT_GT(j["counts"]["particles_max"].get<int>(), 35);
  EXPECT_LT(j["counts"]["particles_max"].get<int>(), 80);
  EXPECT_GT(j["wall_seconds"]["particles"].get<double>(), 0);
}

TEST(ParticlesCli, CheckNamesEveryBadEmitterFieldWithItsLine) {
  auto r = runTumble(std::string("check ") + TUMBLE_TEST_MODS + "/broken");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("bad_fields.lua:3: field 'rate': expected"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bad_fields.lua:5: field 'shape': \"donut\" is not one of"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bad_fields.lua:6: unknown field 'colour'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("not_a_table.lua: must return a table"), std::string::npos) << r.output;
  // The good mod's emitter passes.
  r = runTumble(std::string("check ") + TUMBLE_TEST_MODS + "/good");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST(ParticlesCli, ListShowsEmittersByReference) {
  auto r = runTumble(testMods() + " list");
  EXPECT_NE(r.output.find("base:dust"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("base:sparks"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("good:puff"), std::string::npos) << r.output;
}

}  // namespace tumble::test
