// The player's HUD through the real event path (`tumble play --frames N
// --events FILE --report r.json`, docs/play-events.md): what the report says
// the HUD showed (speed, rpm, gear, lap and gates, minimap, messages and
// their kinds, the script-error console), and pictures with the HUD on and
// off. Also a throttle key rebound in the bindings menu, then driven.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "tumble_process.h"

namespace tumble::test {
namespace {

struct Played {
  ProcessResult process;
  nlohmann::json report;
};

// Plays `ref` for `frames` frames with the events and reads the report. The
// player's bindings and saves are kept out of it (TUMBLE_CONFIG_DIR,
// TUMBLE_SAVE_DIR point into the test's folder).
Played play(const std::string& dir, const std::string& name, const std::string& ref, int frames,
            const std::string& events, const std::string& size = "--width 320 --height 180",
            const std::string& extra = "") {
  const std::string eventsPath = dir + "/" + name + ".events", reportPath = dir + "/" + name + ".json";
  std::ofstream(eventsPath) << events;
  Played p;
  p.process = runTumble("play " + ref + " --frames " + std::to_string(frames) + " --events " + eventsPath +
                            " --report " + reportPath + " " + size + " " + extra,
                        "env TUMBLE_CONFIG_DIR=" + dir + " TUMBLE_SAVE_DIR=" + dir + "/saves ");
  std::ifstream in(reportPath);
  p.report = nlohmann::json::parse(in, nullptr, false);
  return p;
}

const nlohmann::json* findMessage(const nlohmann::json& hud, const std::string& text) {
  for (const auto& m : hud["messages"])
    if (m["text"] == text) return &m;
  return nullptr;
}

TEST(HudPlay, TheSpeedometerShowsTheCarsSpeedGearAndRpm) {
  const std::string dir = outDir("hud_play_speed");
  // The buggy on the hills with W held for 5 s (300 frames at 60 Hz).
  auto r = play(dir, "drive", "base:drive --set car=base:buggy", 300, "0 down key:W\n");
  ASSERT_EQ(r.process.exitCode, 0) << r.process.output;
  ASSERT_FALSE(r.report.is_discarded()) << r.process.output;
  const auto& hud = r.report["hud"];
  const auto& car = r.report["vehicle"];
  ASSERT_TRUE(hud["vehicle"].get<bool>()) << hud.dump(2);
  const double speed = car["speed_kmh"].get<double>();
  ASSERT_GT(speed, 20.0) << car.dump(2);
  EXPECT_NEAR(hud["speed_kmh"].get<double>(), speed, 1e-6);
  EXPECT_EQ(hud["speed_text"], std::to_string(std::lround(speed))) << "the digits the player reads";
  const std::string gear = hud["gear"];
  ASSERT_FALSE(gear.empty());
  EXPECT_TRUE(gear != "R" && gear != "N" && std::stoi(gear) >= 1) << gear;
  // mods/base/vehicles/buggy.lua: engine max_rpm 8500, idle 1000.
  EXPECT_EQ(hud["redline_rpm"].get<double>(), 8500.0);
  EXPECT_GT(hud["rpm"].get<double>(), 1000.0);
  EXPECT_LE(hud["rpm"].get<double>(), 8500.0 * 1.02);
  EXPECT_EQ(hud["rpm_text"], std::to_string(std::lround(hud["rpm"].get<double>())));
  // drive has a terrain: the minimap shows it, built once in 300 frames.
  EXPECT_TRUE(hud["minimap"]["shown"].get<bool>());
  EXPECT_EQ(hud["minimap"]["source"], "terrain");
  EXPECT_EQ(hud["minimap"]["builds"], 1);
  EXPECT_FALSE(hud.contains("lap")) << "drive has no lap: no lap widget";
}

TEST(HudPlay, PassingAGateInTheTimeTrialMovesTheGateCounter) {
  const std::string dir = outDir("hud_play_gates");
  // A best lap saved before, as a player's earlier run would have left it.
  std::filesystem::create_directories(dir + "/saves/base");
  std::ofstream(dir + "/saves/base/time_trial.json") << R"({"best_s": 99.5, "car": "Hatchback"})";
  const std::string ref = "base:time_trial --set autopilot=1";
  auto start = play(dir, "start", ref, 60, "");
  ASSERT_EQ(start.process.exitCode, 0) << start.process.output;
  const auto& lap0 = start.report["hud"]["lap"];
  ASSERT_TRUE(lap0.is_object()) << start.report["hud"].dump(2);
  EXPECT_EQ(lap0["gate_text"], "1 / 7");
  EXPECT_EQ(lap0["time_text"], "0:01.00") << "60 steps of 1/60 s";
  EXPECT_EQ(lap0["best_text"], "1:39.50") << "the best lap read from the scenario's save";
  EXPECT_EQ(start.report["hud"]["minimap"]["source"], "plan") << "no terrain: a plan of the gates";
  EXPECT_EQ(start.report["hud"]["minimap"]["gates"], 7);

  // Gate 1 is 42 m from the start; the autopilot drives at up to 22 m/s.
  auto later = play(dir, "later", ref, 600, "");
  ASSERT_EQ(later.process.exitCode, 0) << later.process.output;
  const auto& lap1 = later.report["hud"]["lap"];
  EXPECT_GE(lap1["gate"].get<int>(), 2) << lap1.dump(2);
  EXPECT_EQ(lap1["gate_text"], std::to_string(lap1["gate"].get<int>()) + " / 7");
  EXPECT_EQ(lap1["time_text"], "0:10.00");
}

TEST(HudPlay, MessagesHaveTheirKindsAndFadeOut) {
  const std::string dir = outDir("hud_play_messages");
  const std::string ref = "good:hud_messages " + testMods();
  // good/scenarios/hud_messages.lua: "welcome" (info, 1 s), "mind the gap"
  // (warning, 2 s), "engine on fire" (error, 2 s) at 0 s; fading over the last second.
  auto early = play(dir, "early", ref, 15, "");
  ASSERT_EQ(early.process.exitCode, 0) << early.process.output;
  const auto& hud = early.report["hud"];
  const auto* welcome = findMessage(hud, "welcome");
  const auto* gap = findMessage(hud, "mind the gap");
  const auto* fire = findMessage(hud, "engine on fire");
  ASSERT_TRUE(welcome && gap && fire) << hud["messages"].dump(2);
  EXPECT_EQ((*welcome)["kind"], "info");
  EXPECT_EQ((*gap)["kind"], "warning");
  EXPECT_EQ((*fire)["kind"], "error");
  EXPECT_NEAR((*welcome)["alpha"].get<double>(), 0.75, 1e-3) << "0.25 s into its last second";
  EXPECT_NEAR((*gap)["alpha"].get<double>(), 1.0, 1e-6);

  auto later = play(dir, "later", ref, 90, "");  // 1.5 s
  ASSERT_EQ(later.process.exitCode, 0) << later.process.output;
  EXPECT_EQ(findMessage(later.report["hud"], "welcome"), nullptr) << "gone after its second";
  const auto* gapLater = findMessage(later.report["hud"], "mind the gap");
  ASSERT_NE(gapLater, nullptr);
  EXPECT_NEAR((*gapLater)["alpha"].get<double>(), 0.5, 1e-3) << "half faded";
  // The script error (at 0.5 s) shows in red too.
  bool errorShown = false;
  for (const auto& m : later.report["hud"]["messages"])
    if (m["kind"] == "error" && m["text"].get<std::string>().find("hud_messages.lua:13:") != std::string::npos)
      errorShown = true;
  EXPECT_TRUE(errorShown) << later.report["hud"]["messages"].dump(2);
}

TEST(HudPlay, AScriptErrorIsInTheConsoleWithFileAndLineAndClearEmptiesIt) {
  const std::string dir = outDir("hud_play_console");
  const std::string ref = "good:hud_messages " + testMods();
  // Closed: a badge counts the error.
  auto closed = play(dir, "closed", ref, 60, "");
  ASSERT_EQ(closed.process.exitCode, 0) << closed.process.output;
  const auto& c0 = closed.report["hud"]["console"];
  EXPECT_FALSE(c0["open"].get<bool>());
  EXPECT_EQ(c0["badge"], 1) << c0.dump(2);

  // ` opens it: the error with file:line.
  const std::string open = "40 down key:`\n41 up key:`\n";
  auto opened = play(dir, "opened", ref, 60, open);
  ASSERT_EQ(opened.process.exitCode, 0) << opened.process.output;
  const auto& c1 = opened.report["hud"]["console"];
  ASSERT_TRUE(c1["open"].get<bool>()) << c1.dump(2);
  ASSERT_EQ(c1["entries"].size(), 1u) << c1.dump(2);
  EXPECT_EQ(c1["entries"][0]["where"], "scenarios/hud_messages.lua:13");
  EXPECT_NE(c1["entries"][0]["message"].get<std::string>().find("nil value"), std::string::npos);
  EXPECT_EQ(c1["badge"], 0);
  const auto& b = c1["clear_button"];
  ASSERT_GT(b["w_px"].get<double>(), 0.0) << c1.dump(2);

  // Clicking Clear (where the report says it is) empties it.
  const double x = b["x_px"].get<double>() + b["w_px"].get<double>() / 2;
  const double y = b["y_px"].get<double>() + b["h_px"].get<double>() / 2;
  auto cleared = play(dir, "cleared", ref, 60,
                      open + "45 move " + std::to_string(x) + " " + std::to_string(y) +
                          "\n46 down mouse:left\n47 up mouse:left\n");
  ASSERT_EQ(cleared.process.exitCode, 0) << cleared.process.output;
  EXPECT_TRUE(cleared.report["hud"]["console"]["entries"].empty()) << cleared.report["hud"]["console"].dump(2);
  EXPECT_EQ(cleared.report["script_errors"].size(), 1u) << "the report still lists what happened";
}

TEST(HudPlay, AThrottleKeyReboundInTheBindingsMenuDrivesTheCar) {
  const std::string dir = outDir("hud_play_rebind");
  const std::string ref = "base:drive --set car=base:buggy";
  const std::string size = "--width 800 --height 600";  // the menu shows the vehicle actions without scrolling
  const std::string f1 = "0 down key:F1\n1 up key:F1\n";
  auto layout = play(dir, "layout", ref, 4, f1, size);
  ASSERT_EQ(layout.process.exitCode, 0) << layout.process.output;
  const nlohmann::json* button = nullptr;
  for (const auto& bt : layout.report["bindings_menu_buttons"])
    if (bt["action"] == "throttle" && bt["slot"] == 0) button = &bt;
  ASSERT_NE(button, nullptr) << layout.report["bindings_menu_buttons"].dump(2);
  ASSERT_EQ((*button)["label"], "W");
  const double x = (*button)["x_px"].get<double>() + (*button)["w_px"].get<double>() / 2;
  const double y = (*button)["y_px"].get<double>() + (*button)["h_px"].get<double>() / 2;
  // Click W's binding, press I, close the menu, hold I for 5 s.
  const std::string events = f1 + "5 move " + std::to_string(x) + " " + std::to_string(y) +
                             "\n6 down mouse:left\n7 up mouse:left\n10 down key:I\n11 up key:I\n"
                             "15 down key:F1\n16 up key:F1\n20 down key:I\n";
  auto driven = play(dir, "driven", ref, 320, events, size);
  ASSERT_EQ(driven.process.exitCode, 0) << driven.process.output;
  const auto& r = driven.report;
  EXPECT_FALSE(r["bindings_menu_open"].get<bool>());
  bool rebound = false;
  for (const auto& bt : r["bindings_menu_buttons"])
    if (bt["action"] == "throttle" && bt["slot"] == 0) rebound = bt["label"] == "I";
  EXPECT_TRUE(rebound) << r["bindings_menu_buttons"].dump(2);
  EXPECT_EQ(r["steps"], 320 - 15) << "paused while the menu was open (frames 0 to 14)";
  EXPECT_GE(r["vehicle"]["distance_m"].get<double>(), 20.0) << r["vehicle"].dump(2);
}

// Pixels of an RGB PNG; empty on failure (with a test failure).
struct Picture {
  int w = 0, h = 0;
  std::vector<unsigned char> rgb;
};
Picture load(const std::string& path) {
  Picture p;
  int n = 0;
  unsigned char* data = stbi_load(path.c_str(), &p.w, &p.h, &n, 3);
  if (!data) {
    ADD_FAILURE() << path << ": " << stbi_failure_reason();
    return p;
  }
  p.rgb.assign(data, data + std::size_t(p.w) * std::size_t(p.h) * 3);
  stbi_image_free(data);
  return p;
}
// Share of pixels in the region (fractions of the picture) that differ by more than 24 in a channel.
double differing(const Picture& a, const Picture& b, double x0, double y0, double x1, double y1) {
  int n = 0, diff = 0;
  for (int y = int(y0 * a.h); y < int(y1 * a.h); ++y)
    for (int x = int(x0 * a.w); x < int(x1 * a.w); ++x) {
      const std::size_t i = (std::size_t(y) * std::size_t(a.w) + std::size_t(x)) * 3;
      ++n;
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(a.rgb[i + c]) - int(b.rgb[i + c])) > 4) {
          ++diff;
          break;
        }
    }
  return n ? double(diff) / n : 0;
}

TEST(HudPlay, TheHudIsDrawnInTheCornersAndHKeyHidesIt) {
  const std::string dir = outDir("hud_play_pixels");
  const std::string ref = "base:drive --set car=base:buggy";
  const std::string size = "--width 640 --height 360";
  auto on = play(dir, "on", ref, 30, "0 down key:W\n", size, "--screenshot " + dir + "/on.png");
  auto off = play(dir, "off", ref, 30, "0 down key:W\n1 down key:H\n2 up key:H\n", size,
                  "--screenshot " + dir + "/off.png");
  ASSERT_EQ(on.process.exitCode, 0) << on.process.output;
  ASSERT_EQ(off.process.exitCode, 0) << off.process.output;
  EXPECT_TRUE(on.report["hud"]["visible"].get<bool>());
  EXPECT_FALSE(off.report["hud"]["visible"].get<bool>());
  EXPECT_FALSE(off.report["hud"]["minimap"]["shown"].get<bool>());
  EXPECT_EQ(on.report["state_hash"], off.report["state_hash"]) << "the HUD changes no simulation";
  const Picture a = load(dir + "/on.png"), b = load(dir + "/off.png");
  ASSERT_EQ(a.w, 640);
  ASSERT_EQ(b.w, 640);
  // The speedometer panel (330 x 236 px at 1280 x 720, scaled) in the bottom
  // right, the minimap (210 px) in the bottom left: most of their pixels change.
  // A change is more than 4 of 255 in a channel: the same state draws the same
  // 3D picture (the middle below), and a minimap of grassy terrain over grass
  // can be close to the grass it covers.
  EXPECT_GT(differing(a, b, 0.78, 0.72, 0.98, 0.97), 0.5);
  EXPECT_GT(differing(a, b, 0.03, 0.72, 0.16, 0.97), 0.5);
  // The middle of the road has no HUD: the same picture.
  EXPECT_LT(differing(a, b, 0.3, 0.45, 0.7, 0.65), 0.001);
}

TEST(HudPlay, AMenuPageOverTheGameHidesTheHud) {
  // Escape, then Change vehicle from the pause menu: the vehicle picker
  // covers the game. Its title sits where the scenario's HUD line is, so the
  // HUD must not be drawn under it: the picture equals the one where H had
  // hidden the HUD before (the pause menu stops the simulation, so the same
  // state is drawn under the same page).
  const std::string dir = outDir("hud_play_menu_page");
  const std::string ref = "base:drive --set car=base:buggy";
  const std::string size = "--width 640 --height 360";
  const std::string toPicker =
      "20 down key:Escape\n21 up key:Escape\n30 down key:Down\n31 up key:Down\n34 down key:Down\n35 up key:Down\n"
      "40 down key:Return\n41 up key:Return\n";
  auto shown = play(dir, "shown", ref, 60, toPicker, size, "--screenshot " + dir + "/shown.png");
  auto hidden = play(dir, "hidden", ref, 60, "5 down key:H\n6 up key:H\n" + toPicker, size,
                     "--screenshot " + dir + "/hidden.png");
  ASSERT_EQ(shown.process.exitCode, 0) << shown.process.output;
  ASSERT_EQ(hidden.process.exitCode, 0) << hidden.process.output;
  EXPECT_EQ(shown.report["menu"]["page"], "vehicles") << shown.report["menu"].dump();
  EXPECT_TRUE(shown.report["hud"]["visible"].get<bool>()) << "H was not pressed in this run";
  EXPECT_FALSE(shown.report["hud"]["drawn"].get<bool>());
  EXPECT_EQ(shown.report["state_hash"], hidden.report["state_hash"]);
  const Picture a = load(dir + "/shown.png"), b = load(dir + "/hidden.png");
  ASSERT_EQ(a.w, 640);
  EXPECT_LT(differing(a, b, 0.0, 0.0, 1.0, 1.0), 0.001) << "the HUD shows through the page";
  // Back in the game (Escape leaves the picker, Escape again resumes): drawn again.
  auto back = play(dir, "back", ref, 80, toPicker + "60 down key:Escape\n61 up key:Escape\n"
                   "70 down key:Escape\n71 up key:Escape\n", size);
  ASSERT_EQ(back.process.exitCode, 0) << back.process.output;
  EXPECT_FALSE(back.report["menu"]["open"].get<bool>()) << back.report["menu"].dump();
  EXPECT_TRUE(back.report["hud"]["drawn"].get<bool>()) << back.report["pause_menu"].dump();
}

}  // namespace
}  // namespace tumble::test

namespace tumble::test {
namespace {

// Share of the region's pixels (fractions of the picture) that `paint` accepts.
template <class F>
double shareOf(const Picture& p, double x0, double y0, double x1, double y1, F paint) {
  int n = 0, hit = 0;
  for (int y = int(y0 * p.h); y < int(y1 * p.h); ++y)
    for (int x = int(x0 * p.w); x < int(x1 * p.w); ++x, ++n) {
      const unsigned char* c = &p.rgb[(std::size_t(y) * std::size_t(p.w) + std::size_t(x)) * 3];
      hit += paint(c[0], c[1], c[2]) ? 1 : 0;
    }
  return n ? double(hit) / n : 0;
}

// The camera key (C) steps chase -> hood -> cockpit on the player's car, and
// each car's own view (its definition's `view`) is where a player expects
// it: the hood view looks over the car's own bonnet, which fills the bottom
// of the picture; the cockpit of a closed car draws the interior and hides
// the body; the open buggy's cockpit shows its own roll cage. Played in the
// showroom on its grey checker floor (--set ground=checker: on the default
// grass the truck's green paint could not be told from the ground) with the
// HUD hidden by H.
TEST(HudPlay, TheCameraKeyGivesEachCarItsHoodAndCockpitViews) {
  const std::string dir = outDir("hud_play_car_views");
  const std::string size = "--width 640 --height 360";
  struct Car {
    const char* name;
    bool (*paint)(int r, int g, int b);
    bool open;
  };
  const Car cars[] = {
      {"hatchback", [](int r, int g, int b) { return r > 90 && r > g + 50 && r > b + 50; }, false},
      {"truck", [](int r, int g, int b) { return g > r + 15 && g > b + 30 && r < 110; }, false},
      {"buggy", [](int r, int g, int b) { return r > 90 && g > 0.6 * r && b < 0.4 * g; }, true},
  };
  const std::string hideHud = "2 down key:H\n3 up key:H\n";
  const std::string cameraKey = "10 down key:C\n11 up key:C\n";
  const std::string cameraKeyAgain = "14 down key:C\n15 up key:C\n";
  for (const Car& car : cars) {
    SCOPED_TRACE(car.name);
    const std::string ref = std::string("base:showroom --set ground=checker --set car=base:") + car.name;
    auto hood = play(dir, std::string(car.name) + "_hood", ref, 40, hideHud + cameraKey, size,
                     "--screenshot " + dir + "/" + car.name + "_hood.png");
    ASSERT_EQ(hood.process.exitCode, 0) << hood.process.output;
    EXPECT_EQ(hood.report["camera"], "hood");
    const Picture h = load(dir + "/" + car.name + "_hood.png");
    ASSERT_EQ(h.w, 640);
    // The bottom fifth: measured 1.0 of it is the hatchback's bonnet, 0.68
    // the truck's, 0.50 the buggy's front tube and rails. Without the car in
    // view (an eye ahead of its front, or inside its body), none.
    const double bonnet = shareOf(h, 0.0, 0.8, 1.0, 1.0, car.paint);
    const double ahead = shareOf(h, 0.0, 0.0, 1.0, 0.6, car.paint);
    RecordProperty(std::string(car.name) + "_hood_bottom_paint_share", std::to_string(bonnet));
    EXPECT_GT(bonnet, 0.25) << "the car's front is at the bottom of the hood view";
    EXPECT_LT(ahead, 0.03) << "above it the road ahead is open";

    auto cockpit = play(dir, std::string(car.name) + "_cockpit", ref, 40, hideHud + cameraKey + cameraKeyAgain, size,
                        "--screenshot " + dir + "/" + car.name + "_cockpit.png");
    ASSERT_EQ(cockpit.process.exitCode, 0) << cockpit.process.output;
    EXPECT_EQ(cockpit.report["camera"], "cockpit");
    const Picture c = load(dir + "/" + car.name + "_cockpit.png");
    ASSERT_EQ(c.w, 640);
    auto dark = [](int r, int g, int b) { return r < 60 && g < 60 && b < 60; };
    if (car.open) {
      EXPECT_GT(shareOf(c, 0.0, 0.0, 1.0, 1.0, car.paint), 0.05) << "the buggy's own cage frames the view";
    } else {
      EXPECT_GT(shareOf(c, 0.1, 0.85, 0.9, 1.0, dark), 0.8) << "the dashboard across the bottom";
      EXPECT_LT(shareOf(c, 0.0, 0.5, 1.0, 1.0, car.paint), 0.01) << "the body is hidden in the cockpit";
    }
    EXPECT_LT(shareOf(c, 0.3, 0.3, 0.7, 0.6, dark), 0.1) << "the view ahead is open";
  }
}

}  // namespace
}  // namespace tumble::test

namespace tumble::test {
namespace {

// The orange needle's pixels in a region: their centroid and main direction.
struct Needle {
  int pixels = 0;
  double cx = 0, cy = 0;  // centroid, px
  double dx = 0, dy = 0;  // unit direction of the pixel cloud's long axis
};
Needle needleIn(const Picture& p, double x0, double y0, double x1, double y1) {
  std::vector<std::pair<double, double>> pts;
  for (int y = int(y0 * p.h); y < int(y1 * p.h); ++y)
    for (int x = int(x0 * p.w); x < int(x1 * p.w); ++x) {
      const unsigned char* c = &p.rgb[(std::size_t(y) * std::size_t(p.w) + std::size_t(x)) * 3];
      // The lit orange needle (measured about 133, 92, 38 in the showroom's light).
      if (c[0] > 90 && c[0] > c[1] + 20 && c[1] > c[2] + 25 && c[2] < 80) pts.emplace_back(x, y);
    }
  Needle n;
  n.pixels = int(pts.size());
  if (pts.empty()) return n;
  for (auto [x, y] : pts) n.cx += x, n.cy += y;
  n.cx /= n.pixels, n.cy /= n.pixels;
  double sxx = 0, sxy = 0, syy = 0;
  for (auto [x, y] : pts) sxx += (x - n.cx) * (x - n.cx), sxy += (x - n.cx) * (y - n.cy), syy += (y - n.cy) * (y - n.cy);
  const double a = 0.5 * std::atan2(2 * sxy, sxx - syy);
  n.dx = std::cos(a), n.dy = std::sin(a);
  return n;
}

// The cockpit's speedometer needle turns with the car's speed, as the player
// sees it: at rest it points to the lower left (zero); after driving it has
// turned clockwise by the speed's share of the dial's 270 degrees for
// 200 km/h. The needle's pivot is where the two pictures' needle lines cross.
TEST(HudPlay, TheCockpitSpeedometerNeedleFollowsTheSpeed) {
  const std::string dir = outDir("hud_play_gauges");
  const std::string size = "--width 640 --height 360";
  const std::string ref = "base:showroom";
  const std::string cockpit = "2 down key:H\n3 up key:H\n10 down key:C\n11 up key:C\n14 down key:C\n15 up key:C\n";
  auto rest = play(dir, "rest", ref, 40, cockpit, size, "--screenshot " + dir + "/rest.png");
  auto moving = play(dir, "moving", ref, 200, cockpit + "20 down key:W\n", size, "--screenshot " + dir + "/moving.png");
  ASSERT_EQ(rest.process.exitCode, 0) << rest.process.output;
  ASSERT_EQ(moving.process.exitCode, 0) << moving.process.output;
  ASSERT_EQ(moving.report["camera"], "cockpit");
  const double speed_kmh = moving.report["vehicle"]["speed_kmh"].get<double>();
  ASSERT_GT(speed_kmh, 20.0) << moving.report["vehicle"].dump(2);
  ASSERT_LT(std::fabs(rest.report["vehicle"]["speed_kmh"].get<double>()), 1.0);
  const Picture a = load(dir + "/rest.png"), b = load(dir + "/moving.png");
  ASSERT_EQ(a.w, 640);
  // The speedometer is the dial on the driver's left (screen left of centre).
  const Needle n0 = needleIn(a, 0.3, 0.6, 0.5, 1.0), n1 = needleIn(b, 0.3, 0.6, 0.5, 1.0);
  ASSERT_GT(n0.pixels, 10) << "a needle is drawn at rest";
  ASSERT_GT(n1.pixels, 10) << "a needle is drawn while driving";
  // Pivot: where the lines through the two needles cross.
  const double det = n0.dx * (-n1.dy) - n0.dy * (-n1.dx);
  ASSERT_GT(std::fabs(det), 0.3) << "the needle turned";
  const double s = ((n1.cx - n0.cx) * (-n1.dy) - (n1.cy - n0.cy) * (-n1.dx)) / det;
  const double px = n0.cx + s * n0.dx, py = n0.cy + s * n0.dy;
  // Angles on screen (x right, y down), clockwise positive as the driver sees it.
  const double a0 = std::atan2(n0.cy - py, n0.cx - px), a1 = std::atan2(n1.cy - py, n1.cx - px);
  EXPECT_LT(n0.cx - px, 0) << "at rest the needle points left of its pivot";
  EXPECT_GT(n0.cy - py, 0) << "and down: zero is at the lower left";
  double turned = (a1 - a0) * 180 / 3.14159265358979;
  while (turned < 0) turned += 360;
  const double expected = 270.0 * speed_kmh / 200.0;
  RecordProperty("needle_turned_deg", std::to_string(turned));
  RecordProperty("speed_kmh", std::to_string(speed_kmh));
  EXPECT_NEAR(turned, expected, 8.0) << "speed " << speed_kmh << " km/h";
  // The dial has a scale: 11 light marks, 27 degrees apart, around the
  // pivot from zero (lower left, 45 degrees clockwise from straight down)
  // over the top to full scale (lower right, 315): light pixels in at least
  // 8 different 15-degree sectors, the first near zero and the last near
  // full scale, and none in the gap at the dial's bottom.
  std::set<int> sectors;
  int below = 0;
  for (int y = std::max(0, int(py) - 40); y < std::min(a.h, int(py) + 40); ++y)
    for (int x = std::max(0, int(px) - 40); x < std::min(a.w, int(px) + 40); ++x) {
      const unsigned char* c = &a.rgb[(std::size_t(y) * std::size_t(a.w) + std::size_t(x)) * 3];
      const int lo = std::min({c[0], c[1], c[2]}), hi = std::max({c[0], c[1], c[2]});
      if (lo < 100 || hi - lo > 30 || std::hypot(x - px, y - py) > 40) continue;
      // Clockwise from straight down, as the driver sees it (screen y is down).
      double deg = std::atan2(-(x - px), y - py) * 180 / 3.14159265358979;
      if (deg < 0) deg += 360;
      if (deg < 40 || deg > 320) ++below;
      else sectors.insert(int(deg / 15));
    }
  RecordProperty("scale_sectors", std::to_string(sectors.size()));
  EXPECT_GE(sectors.size(), 8u) << "marks around the speedometer";
  EXPECT_TRUE(!sectors.empty() && *sectors.begin() <= 4) << "a mark near zero, at the lower left";
  EXPECT_TRUE(!sectors.empty() && *sectors.rbegin() >= 19) << "a mark near full scale, at the lower right";
  EXPECT_EQ(below, 0) << "nothing light in the gap at the dial's bottom";
}

}  // namespace
}  // namespace tumble::test
