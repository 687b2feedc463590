// Models and cameras through the command line, as a modder meets them:
// bad model references are script errors naming the file, static models
// collide through their boxes, and the showroom scenario's chase and cockpit
// views show the car from behind and the dashboard from inside.
#include <gtest/gtest.h>

#include <stb/stb_image.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tumble_process.h"

namespace tumble::test {

namespace {

struct Picture {
  int w = 0, h = 0;
  std::vector<unsigned char> rgb;
  // Share of pixels in the rectangle (fractions of the size) that pass `test`.
  template <typename F>
  double share(double x0, double y0, double x1, double y1, F test) const {
    int hits = 0, total = 0;
    for (int y = int(y0 * h); y < int(y1 * h); ++y) {
      for (int x = int(x0 * w); x < int(x1 * w); ++x) {
        const unsigned char* p = &rgb[(std::size_t(y) * w + x) * 3];
        hits += test(p[0], p[1], p[2]);
        ++total;
      }
    }
    return total ? double(hits) / total : 0.0;
  }
};

Picture loadPicture(const std::string& path) {
  Picture pic;
  int n = 0;
  unsigned char* data = stbi_load(path.c_str(), &pic.w, &pic.h, &n, 3);
  if (data) {
    pic.rgb.assign(data, data + std::size_t(pic.w) * pic.h * 3);
    stbi_image_free(data);
  }
  return pic;
}

}  // namespace

TEST(ModelsCli, BadModelReferencesAreScriptErrorsNamingTheFile) {
  struct Case {
    const char* scenario;
    const char* expected;
  } cases[] = {
      {"missing_model", "no_such_car.obj\": no such file in mod \"base\""},
      {"broken_model", "broken.obj: not a readable model"},
      {"broken_mesh", "no_area.obj: mesh has no triangles with area"},
      {"escape", "leaves the folder of mod \"models\""},
      {"chase_no_target", "mode \"chase\" needs a body to follow"},
  };
  for (const Case& c : cases) {
    auto r = runTumble(testMods() + " run models:" + c.scenario);
    EXPECT_EQ(r.exitCode, 3) << c.scenario << ": a script error, the run still finishes\n" << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.scenario << ":\n" << r.output;
    EXPECT_NE(r.output.find(std::string("scenarios/") + c.scenario + ".lua:"), std::string::npos)
        << "names the script line: " << r.output;
  }
}

TEST(ModelsCli, MassPropertiesFromTheClosedMeshMatchTheSolidBox) {
  auto r = runTumble(testMods() + " run models:mass_properties");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST(ModelsCli, MistakesInOptionsSayWhatIsValid) {
  auto r = runTumble(testMods() + " run models:bad_options");
  EXPECT_EQ(r.exitCode, 0) << "every mistake refused with the right words:\n" << r.output;
}

// The wheels' rays hit a ramp model's triangles: the car climbs it and
// comes down (with a box around the ramp it stops at the 0.6 m step).
// The report's mesh_collision counts that work: wheel rays cast at the
// ramp's mesh and triangles tested.
TEST(ModelsCli, CarDrivesOverAMeshRamp) {
  const std::string dir = outDir("models_ramp");
  auto r = runTumble(testMods() + " run models:ramp_drive --report " + dir + "/r.json");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(dir + "/r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const auto& mesh = report["mesh_collision"];
  EXPECT_GT(mesh["rays"].get<double>(), 1000) << mesh;  // 4 wheels, 480 steps, the ramp nearby
  EXPECT_GT(mesh["triangles_tested"].get<double>(), 0) << mesh;
  EXPECT_GE(mesh["triangles_tested"].get<double>(), mesh["exact_tests"].get<double>()) << mesh;
}

// The base mod's jump ramp (the designer's palette offers it): a car at
// full throttle climbs its deck through the mesh, flies off the lip with
// every wheel in the air and lands upright (the scenario's expectations).
TEST(ModelsCli, CarJumpsOffTheBaseRamp) {
  const std::string dir = outDir("models_ramp_jump");
  auto r = runTumble(testMods() + " run models:ramp_jump --report " + dir + "/r.json");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(dir + "/r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["expectations"].size(), 6u) << report["expectations"].dump();
  EXPECT_GT(report["mesh_collision"]["rays"].get<double>(), 0) << "the wheels' rays met the ramp's mesh";
}

// A car at full throttle (13 m/s at the tree) stops at the tree model's
// trunk, not at the box around its crown, and stays upright.
TEST(ModelsCli, CarStopsAtATreeTrunkNotAtItsCrown) {
  const std::string dir = outDir("models_tree_crash");
  auto r = runTumble(testMods() + " run models:tree_crash --report " + dir + "/r.json");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(dir + "/r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["error"]["nan_events"].get<int>(), 0);
  EXPECT_LT(report["error"]["penetration_max_m"].get<double>(), 0.05);
}

TEST(ModelsCli, StaticModelsCollideThroughTheirMeshesOrBoxes) {
  const std::string dir = outDir("models_static");
  auto r = runTumble(testMods() + " run models:static_scenery --report " + dir + "/r.json");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(dir + "/r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const auto& subsystems = report["subsystems"];
  EXPECT_NE(std::find(subsystems.begin(), subsystems.end(), "models"), subsystems.end()) << subsystems;
  EXPECT_EQ(std::find(subsystems.begin(), subsystems.end(), "render"), subsystems.end()) << "headless: " << subsystems;

  // A scene without models creates no model cache.
  auto plain = runTumble(testMods() + " run good:boxes --report " + dir + "/plain.json");
  std::ifstream plainIn(dir + "/plain.json");
  const nlohmann::json plainReport = nlohmann::json::parse(plainIn);
  const auto& plainSubsystems = plainReport["subsystems"];
  EXPECT_EQ(std::find(plainSubsystems.begin(), plainSubsystems.end(), "models"), plainSubsystems.end());
  EXPECT_EQ(plainReport["mesh_collision"]["pairs"], 0) << "no meshes, no mesh work";
}

TEST(ModelsCli, ShowroomChaseAndCockpitViews) {
  const std::string dir = outDir("models_cli");
  auto chase = runTumble("run base:showroom --set autopilot=1 --screenshot " + dir + "/chase.png --width 320 --height 180");
  ASSERT_EQ(chase.exitCode, 0) << chase.output;
  const Picture behind = loadPicture(dir + "/chase.png");
  ASSERT_EQ(behind.w, 320);
  // The chase camera sits behind the red hatchback: its paint fills much of
  // the lower middle of the frame.
  auto red = [](int r, int g, int b) { return r > 90 && r > g + 50 && r > b + 50; };
  EXPECT_GT(behind.share(0.35, 0.55, 0.65, 0.95, red), 0.3);
  EXPECT_LT(behind.share(0.0, 0.0, 1.0, 0.4, red), 0.01) << "nothing red in the sky";

  auto cockpit = runTumble("run base:showroom --set autopilot=1 --set camera=cockpit --at 0.5 --screenshot " + dir +
                           "/cockpit.png --width 320 --height 180");
  ASSERT_EQ(cockpit.exitCode, 0) << cockpit.output;
  const Picture inside = loadPicture(dir + "/cockpit.png");
  // The interior is a model: dark dashboard across the bottom of the view;
  // the car's own body, which surrounds the eye, is left out, so no red
  // paint covers the view.
  auto dark = [](int r, int g, int b) { return r < 60 && g < 60 && b < 60; };
  EXPECT_GT(inside.share(0.1, 0.85, 0.9, 1.0, dark), 0.8);
  EXPECT_LT(inside.share(0.3, 0.3, 0.7, 0.6, dark), 0.1) << "the view ahead is open";
  EXPECT_LT(inside.share(0.0, 0.0, 1.0, 1.0, red), 0.01) << "the exterior is hidden in the cockpit";
}

// The player's car (a real vehicle, drive.show) gets the same cockpit: the
// interior model at the driver's eye, the car's own body hidden.
TEST(ModelsCli, DrivenCarCockpitShowsTheInterior) {
  const std::string dir = outDir("models_cli_driven");  // its own: outDir empties the folder
  auto cockpit = runTumble("run base:showroom --set camera=cockpit --at 0.5 --screenshot " + dir +
                           "/driven_cockpit.png --width 320 --height 180");
  ASSERT_EQ(cockpit.exitCode, 0) << cockpit.output;
  const Picture inside = loadPicture(dir + "/driven_cockpit.png");
  auto dark = [](int r, int g, int b) { return r < 60 && g < 60 && b < 60; };
  auto red = [](int r, int g, int b) { return r > 90 && r > g + 50 && r > b + 50; };
  EXPECT_GT(inside.share(0.1, 0.85, 0.9, 1.0, dark), 0.8) << "the dashboard across the bottom";
  EXPECT_LT(inside.share(0.3, 0.3, 0.7, 0.6, dark), 0.1) << "the view ahead is open";
  EXPECT_LT(inside.share(0.0, 0.0, 1.0, 1.0, red), 0.01) << "the exterior is hidden in the cockpit";
}

}  // namespace tumble::test
