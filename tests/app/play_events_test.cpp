// The interactive game through its real event path: `tumble play --frames N
// --events FILE --report r.json` pushes scripted keys into SDL's queue
// (docs/play-events.md), and the report says what the player saw. Each test
// here fails if the world does not step.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>

#include "tumble_process.h"

namespace tumble::test {
namespace {

// Small frames keep llvmpipe quick; the simulation does not depend on them.
constexpr const char* kSize = " --width 320 --height 180";

struct Played {
  ProcessResult process;
  nlohmann::json report;
};

// Plays `ref` for `frames` frames with the events (the text of an events
// file) and reads the report. The player's bindings file is kept out of it.
Played play(const std::string& dir, const std::string& name, const std::string& ref, int frames,
            const std::string& events, const std::string& extra = "") {
  const std::string eventsPath = dir + "/" + name + ".events", reportPath = dir + "/" + name + ".json";
  std::ofstream(eventsPath) << events;
  Played p;
  p.process = runTumble("play " + ref + " --frames " + std::to_string(frames) + " --events " + eventsPath +
                            " --report " + reportPath + kSize + " " + extra,
                        "env TUMBLE_CONFIG_DIR=" + dir + " ");
  std::ifstream in(reportPath);
  p.report = nlohmann::json::parse(in, nullptr, false);
  return p;
}

double headingChange_deg(const nlohmann::json& vehicle) {
  double d = vehicle["heading_deg"].get<double>() - vehicle["start_heading_deg"].get<double>();
  while (d > 180) d -= 360;
  while (d < -180) d += 360;
  return std::fabs(d);
}

TEST(PlayEvents, HoldingThrottleDrivesTheCarAndSteeringTurnsIt) {
  const std::string dir = outDir("play_events_drive");
  // The buggy on the hills, 300 frames = 5 s at 60 Hz, W held throughout.
  // (The default hatchback starts up a slope there: about 13 m in 5 s.)
  const std::string buggy = "base:drive --set car=base:buggy";
  auto straight = play(dir, "straight", buggy, 300, "0 down key:W\n");
  ASSERT_EQ(straight.process.exitCode, 0) << straight.process.output;
  ASSERT_FALSE(straight.report.is_discarded()) << straight.process.output;
  EXPECT_EQ(straight.report["scenario"], "base:drive");
  EXPECT_EQ(straight.report["steps"], 300);
  const auto& car = straight.report["vehicle"];
  ASSERT_TRUE(car.is_object()) << straight.report.dump(2);
  EXPECT_GE(car["distance_m"].get<double>(), 20.0) << car.dump(2);
  EXPECT_GT(car["speed_kmh"].get<double>(), 20.0) << car.dump(2);
  EXPECT_LT(headingChange_deg(car), 10.0) << "W alone keeps roughly straight: " << car.dump(2);
  EXPECT_GT(straight.report["frame_ms"]["p95"].get<double>(), 0.0);

  // The same with D (steer right) held from 1 s on.
  auto turning = play(dir, "turning", buggy, 300, "0 down key:W\n60 down key:D\n");
  ASSERT_EQ(turning.process.exitCode, 0) << turning.process.output;
  EXPECT_GT(headingChange_deg(turning.report["vehicle"]), 30.0) << turning.report["vehicle"].dump(2);

  auto idle = play(dir, "idle", buggy, 300, "");
  ASSERT_EQ(idle.process.exitCode, 0) << idle.process.output;
  // Nobody at the wheel: the car only rolls a little down the slope it stands on.
  EXPECT_LT(idle.report["vehicle"]["distance_m"].get<double>(), 5.0) << idle.report["vehicle"].dump(2);
}

// S at a standstill reverses; W then brakes the backwards roll and drives
// forward again, as in driving games. Found playing: W held in reverse gear
// drove the car backwards at 55 km/h. On the time trial's flat floor.
TEST(PlayEvents, ThrottleAfterReversingBrakesThenDrivesForward) {
  const std::string dir = outDir("play_events_reverse");
  const std::string ref = "base:time_trial --set car=base:hatchback";
  auto back = play(dir, "back", ref, 120, "0 down key:S\n");
  ASSERT_EQ(back.process.exitCode, 0) << back.process.output;
  EXPECT_LT(back.report["vehicle"]["speed_kmh"].get<double>(), -5.0) << "S held 2 s reverses: " << back.report["vehicle"].dump(2);
  EXPECT_EQ(back.report["hud"]["gear"], "R");
  auto forward = play(dir, "forward", ref, 360, "0 down key:S\n120 up key:S\n120 down key:W\n");
  ASSERT_EQ(forward.process.exitCode, 0) << forward.process.output;
  const auto& car = forward.report["vehicle"];
  EXPECT_GT(car["speed_kmh"].get<double>(), 10.0) << "4 s of W after reversing drives forward: " << car.dump(2);
  EXPECT_NE(forward.report["hud"]["gear"], "R");
}

TEST(PlayEvents, EscapeOpensThePauseMenuAndTheLoopGoesOn) {
  const std::string dir = outDir("play_events_pause");
  auto paused = play(dir, "paused", "base:drive", 120, "30 down key:Escape\n31 up key:Escape\n");
  ASSERT_EQ(paused.process.exitCode, 0) << paused.process.output;
  const auto& r = paused.report;
  EXPECT_FALSE(r["quit"].get<bool>());
  EXPECT_EQ(r["frames"], 120) << "every frame was drawn: the game did not quit";
  EXPECT_TRUE(r["pause_menu"]["open"].get<bool>());
  EXPECT_EQ(r["pause_menu"]["selected"], "Resume");
  // Resume, Restart, Change vehicle, Settings, Main menu, Quit to desktop.
  EXPECT_EQ(r["pause_menu"]["items"].size(), 6u) << r["pause_menu"].dump(2);
  EXPECT_EQ(r["steps"], 30) << "the world stepped until Escape and waits in the menu";

  // Escape again resumes: the world steps on.
  auto resumed = play(dir, "resumed", "base:drive", 120,
                      "30 down key:Escape\n31 up key:Escape\n60 down key:Escape\n61 up key:Escape\n");
  ASSERT_EQ(resumed.process.exitCode, 0) << resumed.process.output;
  EXPECT_FALSE(resumed.report["pause_menu"]["open"].get<bool>());
  EXPECT_EQ(resumed.report["steps"], 90);

  // Up (wrapping to the last item) and Return pick "Quit to desktop": the game ends there.
  auto quit = play(dir, "quit", "base:drive", 120,
                   "30 down key:Escape\n31 up key:Escape\n40 down key:Up\n41 up key:Up\n"
                   "50 down key:Return\n51 up key:Return\n");
  ASSERT_EQ(quit.process.exitCode, 0) << quit.process.output;
  EXPECT_TRUE(quit.report["quit"].get<bool>()) << quit.report.dump(2);
  EXPECT_LT(quit.report["frames"].get<int>(), 60);
}

TEST(PlayEvents, EscapeInTheBindingsMenuClosesThatMenuOnly) {
  const std::string dir = outDir("play_events_bindings");
  auto r = play(dir, "f1", "base:drive", 60, "10 down key:F1\n11 up key:F1\n30 down key:Escape\n31 up key:Escape\n");
  ASSERT_EQ(r.process.exitCode, 0) << r.process.output;
  EXPECT_FALSE(r.report["quit"].get<bool>());
  EXPECT_FALSE(r.report["bindings_menu_open"].get<bool>());
  EXPECT_FALSE(r.report["pause_menu"]["open"].get<bool>()) << "Escape closed the bindings menu, nothing more";
  EXPECT_EQ(r.report["steps"], 10 + 30) << "paused while the bindings menu was open (frames 10 to 29)";
}

TEST(PlayEvents, RestartGivesTheStartStateAgain) {
  const std::string dir = outDir("play_events_restart");
  // Drive the buggy for 50 frames, restart at frame 60, then 90 frames untouched.
  const std::string ref = "base:drive --set car=base:buggy";
  const std::string drive = "0 down key:W\n50 up key:W\n";
  auto restarted = play(dir, "restarted", ref, 150, drive + "60 down key:F5\n61 up key:F5\n");
  ASSERT_EQ(restarted.process.exitCode, 0) << restarted.process.output;
  EXPECT_EQ(restarted.report["restarts"], 1);
  EXPECT_LT(restarted.report["vehicle"]["distance_m"].get<double>(), 1.0) << "the car is back at the start";
  // A fresh start left untouched for the same 90 steps.
  auto fresh = play(dir, "fresh", ref, 90, "");
  ASSERT_EQ(fresh.process.exitCode, 0) << fresh.process.output;
  EXPECT_EQ(restarted.report["state_hash"], fresh.report["state_hash"]);
  // Without the restart the drive leaves the world elsewhere.
  auto driven = play(dir, "driven", ref, 150, drive);
  ASSERT_EQ(driven.process.exitCode, 0) << driven.process.output;
  EXPECT_NE(driven.report["state_hash"], fresh.report["state_hash"]);
  EXPECT_GT(driven.report["vehicle"]["distance_m"].get<double>(),
            fresh.report["vehicle"]["distance_m"].get<double>() + 1.0);
}

TEST(PlayEvents, ResetPutsACarOnItsRoofBackOnItsWheels) {
  const std::string dir = outDir("play_events_reset");
  const std::string ref = "good:flipped " + testMods();
  auto lying = play(dir, "lying", ref, 150, "");
  ASSERT_EQ(lying.process.exitCode, 0) << lying.process.output;
  const auto& before = lying.report["vehicle"];
  ASSERT_LT(before["up_y"].get<double>(), -0.5) << "the car came to rest on its roof: " << before.dump(2);

  auto reset = play(dir, "reset", ref, 240, "150 down key:R\n151 up key:R\n");
  ASSERT_EQ(reset.process.exitCode, 0) << reset.process.output;
  const auto& after = reset.report["vehicle"];
  EXPECT_GT(after["up_y"].get<double>(), 0.95) << after.dump(2);
  EXPECT_LT(std::fabs(after["speed_kmh"].get<double>()), 1.0) << after.dump(2);
  const double dx = after["position_m"][0].get<double>() - before["position_m"][0].get<double>();
  const double dz = after["position_m"][2].get<double>() - before["position_m"][2].get<double>();
  EXPECT_LT(std::hypot(dx, dz), 1.0) << "upright where it lay";
}

TEST(PlayEvents, ACarThatDrivesOffTheMapComesBackOntoIt) {
  const std::string dir = outDir("play_events_off_map");
  // A 128 m map (edges at +-64 m): the buggy starts at x = 60 facing +z and
  // W is held, so it leaves the map within seconds and would fall for ever
  // (nearly flat: 1 m from the lowest point to the highest).
  const std::string ref = "base:drive --set car=base:buggy --set terrain.size=129 --set terrain.height=1";
  auto off = play(dir, "off", ref, 600, "0 down key:W\n200 up key:W\n");
  ASSERT_EQ(off.process.exitCode, 0) << off.process.output;
  const auto& car = off.report["vehicle"];
  ASSERT_TRUE(car.is_object()) << off.report.dump(2);
  const double x = car["position_m"][0].get<double>(), y = car["position_m"][1].get<double>(),
               z = car["position_m"][2].get<double>();
  EXPECT_GT(car["distance_m"].get<double>(), 20.0) << "it drove: " << car.dump(2);
  EXPECT_LE(std::fabs(x), 64.0) << car.dump(2);
  EXPECT_LE(std::fabs(z), 64.0) << car.dump(2);
  EXPECT_GT(y, -5.0) << "on the map, not falling: " << car.dump(2);
  EXPECT_GT(car["up_y"].get<double>(), 0.9) << car.dump(2);
  bool told = false;
  for (const auto& m : off.report["hud"]["messages"]) told |= m["text"].get<std::string>().find("Off the map") == 0;
  EXPECT_TRUE(told) << off.report["hud"].dump(2);
}

TEST(PlayEvents, ABadEventsFileNamesTheLine) {
  const std::string dir = outDir("play_events_bad");
  const std::string path = dir + "/bad.events";
  std::ofstream(path) << "# a comment\n0 down key:W\n12 down key:Wq\n";
  auto r = runTumble("play base:drive --frames 10 --events " + path + kSize);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find(path + ":3:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("unknown key"), std::string::npos) << r.output;

  std::ofstream(path) << "40 down key:W\n10 up key:W\n";
  r = runTumble("play base:drive --frames 10 --events " + path + kSize);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find(path + ":2: frame 10 comes after frame 40"), std::string::npos) << r.output;

  std::ofstream(path) << "5 jump key:W\n";
  r = runTumble("play base:drive --frames 10 --events " + path + kSize);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find(path + ":1: unknown event \"jump\""), std::string::npos) << r.output;

  r = runTumble("play base:drive --frames 10 --events " + dir + "/missing.events" + kSize);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("missing.events"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace tumble::test
