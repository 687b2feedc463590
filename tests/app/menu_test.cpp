// The main menu, the vehicle picker, the pause menu's pages and the settings
// through the real event path: `tumble play --frames N --events FILE
// --report r.json` with no scenario opens the main menu; scripted keys go
// into SDL's queue (docs/play-events.md) and the report says which menu page
// the player saw, what was started and with which vehicle.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tumble_process.h"

namespace tumble::test {
namespace {

constexpr const char* kSize = " --width 640 --height 360";

struct Played {
  ProcessResult process;
  nlohmann::json report;
};


Played play(const std::string& dir, const std::string& name, const std::string& args, int frames,
            const std::string& events) {
  const std::string eventsPath = dir + "/" + name + ".events", reportPath = dir + "/" + name + ".json";
  std::ofstream(eventsPath) << events;
  Played p;
  p.process = runTumble("play " + args + " --frames " + std::to_string(frames) + " --events " + eventsPath +
                            " --report " + reportPath + kSize,
                        isolated(dir));
  std::ifstream in(reportPath);
  p.report = nlohmann::json::parse(in, nullptr, false);
  return p;
}

// A key pressed at frame f and let go at f + 1.
std::string tap(const std::string& key, int frame) {
  return std::to_string(frame) + " down key:" + key + "\n" + std::to_string(frame + 1) + " up key:" + key + "\n";
}

// Taps `key` n times from frame f on, two frames apart; returns the next free frame.
int taps(std::string& events, const std::string& key, int n, int frame) {
  for (int i = 0; i < n; ++i, frame += 2) events += tap(key, frame);
  return frame;
}

int indexOf(const nlohmann::json& menu, const std::string& label) {
  const auto& items = menu["items"];
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i]["label"] == label) return int(i);
  return -1;
}

// Main menu -> Play -> base -> the scenarios page.
int toScenarios(std::string& events) {
  events += tap("Return", 5) + tap("Return", 10);
  return 14;
}

TEST(MainMenu, PlayWithoutAScenarioOpensTheMainMenu) {
  const std::string dir = outDir("menu_root");
  auto r = play(dir, "root", "", 20, "");
  ASSERT_EQ(r.process.exitCode, 0) << r.process.output;
  ASSERT_FALSE(r.report.is_discarded()) << r.process.output;
  const auto& menu = r.report["menu"];
  EXPECT_EQ(menu["page"], "main");
  EXPECT_TRUE(menu["open"].get<bool>());
  EXPECT_EQ(menu["selected"], "Play");
  ASSERT_EQ(menu["items"].size(), 4u) << menu.dump(2);
  EXPECT_EQ(menu["items"][1]["label"], "Designer");
  EXPECT_TRUE(r.report["scenario"].is_null()) << "no scene runs behind the main menu";
  EXPECT_EQ(r.report["steps"], 0);
}

TEST(MainMenu, EscapeOnTheRootAsksBeforeQuitting) {
  const std::string dir = outDir("menu_escape");
  auto asked = play(dir, "asked", "", 40, tap("Escape", 5));
  ASSERT_EQ(asked.process.exitCode, 0) << asked.process.output;
  EXPECT_FALSE(asked.report["quit"].get<bool>());
  EXPECT_EQ(asked.report["frames"], 40) << "the game went on";
  EXPECT_EQ(asked.report["menu"]["page"], "confirm_quit");
  // Escape again goes back; Return on "Quit to desktop" quits.
  auto back = play(dir, "back", "", 40, tap("Escape", 5) + tap("Escape", 10));
  EXPECT_EQ(back.report["menu"]["page"], "main") << back.report["menu"].dump(2);
  EXPECT_FALSE(back.report["quit"].get<bool>());
  // Closing the window quits from any menu page.
  auto closed = play(dir, "closed", "", 40, tap("Return", 5) + "12 quit\n");
  EXPECT_TRUE(closed.report["quit"].get<bool>()) << closed.report["menu"].dump(2);
  EXPECT_LT(closed.report["frames"].get<int>(), 20);
  auto quit = play(dir, "quit", "", 40, tap("Escape", 5) + tap("Return", 10));
  EXPECT_TRUE(quit.report["quit"].get<bool>()) << quit.report["menu"].dump(2);
  EXPECT_LT(quit.report["frames"].get<int>(), 20);
}

TEST(MainMenu, ChoosingDriveAndTheBuggyStartsItAndTheThrottleDrivesIt) {
  const std::string dir = outDir("menu_drive");
  // Where drive is in base's list (the list grows as scenarios are added).
  std::string events;
  toScenarios(events);
  auto list = play(dir, "list", "", 20, events);
  ASSERT_EQ(list.process.exitCode, 0) << list.process.output;
  ASSERT_EQ(list.report["menu"]["page"], "scenarios") << list.report["menu"].dump(2);
  const int drive = indexOf(list.report["menu"], "drive");
  ASSERT_GE(drive, 0) << list.report["menu"].dump(2);

  // Down to drive, Return: the vehicle picker, starting on drive's default car.
  events.clear();
  int frame = toScenarios(events);
  frame = taps(events, "Down", drive, frame);
  events += tap("Return", frame);
  auto picker = play(dir, "picker", "", frame + 6, events);
  ASSERT_EQ(picker.report["menu"]["page"], "vehicles") << picker.report["menu"].dump(2);
  EXPECT_EQ(picker.report["menu"]["selected"], "Hatchback");
  const int buggy = indexOf(picker.report["menu"], "Buggy"), at = indexOf(picker.report["menu"], "Hatchback");
  ASSERT_GE(buggy, 0) << picker.report["menu"].dump(2);
  EXPECT_GE(indexOf(picker.report["menu"], "Off-road truck"), 0) << "every vehicle definition of base is offered";

  // Up to the buggy, Return: drive starts with it; then W for 5 s.
  frame = taps(events, buggy < at ? "Up" : "Down", std::abs(buggy - at), frame + 4);
  events += tap("Return", frame);
  const int throttleFrom = frame + 5;
  events += std::to_string(throttleFrom) + " down key:W\n";
  auto driven = play(dir, "driven", "", throttleFrom + 300, events);
  ASSERT_EQ(driven.process.exitCode, 0) << driven.process.output;
  const auto& r = driven.report;
  EXPECT_EQ(r["scenario"], "base:drive") << r.dump(2);
  EXPECT_EQ(r["vehicle_definition"], "base:buggy");
  EXPECT_EQ(r["menu"]["page"], "closed");
  ASSERT_TRUE(r["vehicle"].is_object()) << r.dump(2);
  EXPECT_EQ(r["vehicle"]["name"], "Buggy");
  EXPECT_GE(r["steps"].get<int>(), 300);
  EXPECT_GE(r["vehicle"]["distance_m"].get<double>(), 20.0) << r["vehicle"].dump(2);
}

// The pause menu of drive: Resume, Restart, Change vehicle, Settings, Main menu, Quit to desktop.
std::string pauseAndPick(int downs, int frame) {
  std::string events = tap("Escape", frame);
  frame = taps(events, "Down", downs, frame + 4);
  events += tap("Return", frame);
  return events;
}

TEST(PauseMenu, ChangeVehicleRestartsTheScenarioWithTheTruck) {
  const std::string dir = outDir("menu_change_vehicle");
  const std::string ref = "base:drive --set car=base:buggy";
  auto paused = play(dir, "paused", ref, 40, tap("Escape", 20));
  ASSERT_EQ(paused.process.exitCode, 0) << paused.process.output;
  const auto& items = paused.report["pause_menu"]["items"];
  ASSERT_EQ(items.size(), 6u) << paused.report["pause_menu"].dump(2);
  EXPECT_EQ(items[2]["label"], "Change vehicle");
  EXPECT_EQ(items[4]["label"], "Main menu");

  std::string events = pauseAndPick(2, 20);  // frame 28: Return on Change vehicle
  auto picker = play(dir, "picker", ref, 40, events);
  ASSERT_EQ(picker.report["menu"]["page"], "vehicles") << picker.report.dump(2);
  EXPECT_EQ(picker.report["steps"], 20) << "the game waits while the picker is open";
  EXPECT_EQ(picker.report["menu"]["selected"], "Buggy") << "the picker starts on the car being driven";
  const int truck = indexOf(picker.report["menu"], "Off-road truck");
  const int at = indexOf(picker.report["menu"], picker.report["menu"]["selected"].get<std::string>());
  ASSERT_GE(truck, 0);
  int frame = taps(events, truck < at ? "Up" : "Down", std::abs(truck - at), 40);
  events += tap("Return", frame);
  auto changed = play(dir, "changed", ref, frame + 60, events);
  ASSERT_EQ(changed.process.exitCode, 0) << changed.process.output;
  const auto& r = changed.report;
  EXPECT_EQ(r["scenario"], "base:drive");
  EXPECT_EQ(r["vehicle_definition"], "base:truck");
  EXPECT_EQ(r["vehicle"]["name"], "Off-road truck") << r["vehicle"].dump(2);
  EXPECT_FALSE(r["pause_menu"]["open"].get<bool>());
  EXPECT_EQ(r["menu"]["page"], "closed");
  EXPECT_FALSE(r["paused"].get<bool>());
  EXPECT_GE(r["steps"].get<int>(), 55) << "the new scene runs from its start";
  EXPECT_LE(r["steps"].get<int>(), 60);
}

TEST(PauseMenu, MainMenuTearsTheSceneDownAndShowsTheMenu) {
  const std::string dir = outDir("menu_back_to_main");
  auto r = play(dir, "main", "base:drive", 60, pauseAndPick(4, 20));
  ASSERT_EQ(r.process.exitCode, 0) << r.process.output;
  EXPECT_EQ(r.report["menu"]["page"], "main") << r.report.dump(2);
  EXPECT_TRUE(r.report["scenario"].is_null()) << "the scene is gone";
  EXPECT_FALSE(r.report["quit"].get<bool>());
  EXPECT_EQ(r.report["frames"], 60);
  // Settings from the pause menu, then Escape: back in the pause menu, still paused.
  auto settings = play(dir, "settings", "base:drive", 60, pauseAndPick(3, 20) + tap("Escape", 40));
  EXPECT_EQ(settings.report["menu"]["page"], "closed") << settings.report.dump(2);
  EXPECT_TRUE(settings.report["pause_menu"]["open"].get<bool>());
  EXPECT_EQ(settings.report["steps"], 20);
}

TEST(Settings, AQualityChangeIsSavedAndLoadedAtTheNextStart) {
  const std::string dir = outDir("menu_settings");
  // Root: Down x2 passes Designer to Settings; Return; Down x2 to
  // Quality (medium by default); Right makes it high.
  std::string events = tap("Down", 3) + tap("Down", 5) + tap("Return", 8);
  int frame = taps(events, "Down", 2, 12);
  events += tap("Right", frame);
  auto changed = play(dir, "changed", "", frame + 6, events);
  ASSERT_EQ(changed.process.exitCode, 0) << changed.process.output;
  EXPECT_EQ(changed.report["menu"]["page"], "settings");
  EXPECT_EQ(changed.report["menu"]["selected"], "Quality");
  EXPECT_EQ(changed.report["settings"]["quality"], "high");
  EXPECT_EQ(changed.report["quality"]["preset"], "high");
  std::ifstream file(dir + "/config/settings.json");
  ASSERT_TRUE(file.good()) << "the settings file was written";
  nlohmann::json saved = nlohmann::json::parse(file, nullptr, false);
  EXPECT_EQ(saved["quality"], "high") << saved.dump(2);
  EXPECT_EQ(saved["volume_master"], 1.0);

  auto next = play(dir, "next", "", 5, "");
  EXPECT_EQ(next.report["quality"]["preset"], "high") << "loaded at the next start";
  EXPECT_EQ(next.report["quality"]["msaa_samples"], 4);
  auto overridden = play(dir, "overridden", "--quality low", 5, "");
  EXPECT_EQ(overridden.report["quality"]["preset"], "low") << "--quality wins for the session";
  EXPECT_FALSE(overridden.report["quality"]["shadows"].get<bool>());
  EXPECT_EQ(overridden.report["settings"]["quality"], "high") << "and does not change the saved setting";
}

TEST(Settings, ABrokenSettingsFileIsReportedAndTheDefaultsUsed) {
  const std::string dir = outDir("menu_settings_broken");
  std::filesystem::create_directories(dir + "/config");
  for (const char* text : {"{ not json", R"({"quality": "ultra"})", R"({"volume_master": 3})", R"([1, 2])"}) {
    std::ofstream(dir + "/config/settings.json") << text;
    auto r = play(dir, "broken", "", 5, "");
    ASSERT_EQ(r.process.exitCode, 0) << text << "\n" << r.process.output;
    const auto& problem = r.report["settings"]["problem"];
    ASSERT_TRUE(problem.is_string()) << text;
    EXPECT_NE(problem.get<std::string>().find("settings.json"), std::string::npos) << problem;
    EXPECT_EQ(r.report["quality"]["preset"], "medium") << text;
    EXPECT_EQ(r.report["menu"]["page"], "main");
  }
}

TEST(MainMenu, TheHighlightedScenarioGetsAThumbnailInTheCacheFolder) {
  const std::string dir = outDir("menu_thumbnail");
  std::string events;
  toScenarios(events);
  auto r = play(dir, "thumb", "", 30, events);
  ASSERT_EQ(r.process.exitCode, 0) << r.process.output;
  const std::string first = r.report["menu"]["selected"].get<std::string>();
  const std::string png = dir + "/cache/thumbnails/base/" + first + ".png";
  ASSERT_TRUE(std::filesystem::exists(png)) << png << "\n" << r.process.output;
  std::ifstream in(png, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  // A second visit finds it cached (no new run).
  auto again = play(dir, "again", "", 30, events);
  EXPECT_EQ(again.report["menu"]["thumbnail"], "cached") << again.report["menu"].dump(2);
}

// A player with only a gamepad: A twice (Play, base), the d-pad down to
// drive, A (the picker, on drive's default car), A (start), then the right
// trigger held as throttle for 5 s.
std::string pad(const std::string& button, int frame) {
  return std::to_string(frame) + " down pad:" + button + "\n" + std::to_string(frame + 1) + " up pad:" + button + "\n";
}

TEST(MainMenu, APadAloneGetsFromTheMenuIntoTheCarAndDrivesIt) {
  const std::string dir = outDir("menu_pad");
  std::string keys;
  toScenarios(keys);
  auto list = play(dir, "list", "", 20, keys);
  ASSERT_EQ(list.process.exitCode, 0) << list.process.output;
  const int drive = indexOf(list.report["menu"], "drive");
  ASSERT_GE(drive, 0) << list.report["menu"].dump(2);

  std::string events = pad("a", 5) + pad("a", 10);
  int frame = 14;
  for (int i = 0; i < drive; ++i, frame += 2) events += pad("dpdown", frame);
  events += pad("a", frame);
  auto picker = play(dir, "picker", "", frame + 6, events);
  ASSERT_EQ(picker.report["menu"]["page"], "vehicles") << picker.report["menu"].dump(2);
  EXPECT_EQ(picker.report["menu"]["selected"], "Hatchback");

  events += pad("a", frame + 6);
  const int throttleFrom = frame + 12;
  events += std::to_string(throttleFrom) + " axis pad_axis:righttrigger 1\n";
  auto driven = play(dir, "driven", "", throttleFrom + 300, events);
  ASSERT_EQ(driven.process.exitCode, 0) << driven.process.output;
  const auto& r = driven.report;
  EXPECT_EQ(r["scenario"], "base:drive") << r.dump(2);
  EXPECT_EQ(r["vehicle_definition"], "base:hatchback");
  ASSERT_TRUE(r["vehicle"].is_object()) << r.dump(2);
  EXPECT_GE(r["vehicle"]["distance_m"].get<double>(), 5.0) << "the trigger drives the car: " << r["vehicle"].dump(2);
  // The trigger pressed fully is the throttle pressed fully: the same drive
  // as W held from the same frame (the simulation is deterministic).
  const std::string withKey = events.substr(0, events.rfind(std::to_string(throttleFrom) + " axis")) +
                              std::to_string(throttleFrom) + " down key:W\n";
  auto keyed = play(dir, "keyed", "", throttleFrom + 300, withKey);
  ASSERT_TRUE(keyed.report["vehicle"].is_object()) << keyed.report.dump(2);
  EXPECT_NEAR(r["vehicle"]["distance_m"].get<double>(), keyed.report["vehicle"]["distance_m"].get<double>(), 1e-6);
}

// A player with a mouse: the pointer onto an item where the menu drew it
// (the report's item rectangles) and a click chooses it.
TEST(MainMenu, AClickOnSettingsOpensTheSettingsPage) {
  const std::string dir = outDir("menu_mouse");
  auto root = play(dir, "root", "", 10, "");
  ASSERT_EQ(root.process.exitCode, 0) << root.process.output;
  const int settings = indexOf(root.report["menu"], "Settings");
  ASSERT_GE(settings, 0) << root.report["menu"].dump(2);
  const auto& item = root.report["menu"]["items"][std::size_t(settings)];
  const int x = int(item["x_px"].get<double>() + item["w_px"].get<double>() / 2);
  const int y = int(item["y_px"].get<double>() + item["h_px"].get<double>() / 2);
  const std::string events = "10 move " + std::to_string(x) + " " + std::to_string(y) +
                             "\n12 down mouse:left\n13 up mouse:left\n";
  auto clicked = play(dir, "clicked", "", 20, events);
  ASSERT_EQ(clicked.process.exitCode, 0) << clicked.process.output;
  EXPECT_EQ(clicked.report["menu"]["page"], "settings") << clicked.report["menu"].dump(2);
  // A click beside every item changes nothing.
  auto beside = play(dir, "beside", "", 20, "10 move 5 5\n12 down mouse:left\n13 up mouse:left\n");
  EXPECT_EQ(beside.report["menu"]["page"], "main") << beside.report["menu"].dump(2);
}

// Settings -> Resolution: Left picks the next smaller offered size; the
// window takes it at once and the setting is saved.
TEST(Settings, AResolutionChangeResizesTheWindowAndIsSaved) {
  const std::string dir = outDir("menu_resolution");
  auto paused = play(dir, "paused", "base:drop", 26, tap("Escape", 20));
  ASSERT_EQ(paused.process.exitCode, 0) << paused.process.output;
  const int settings = indexOf(paused.report["pause_menu"], "Settings");
  ASSERT_GE(settings, 0) << paused.report["pause_menu"].dump(2);
  auto before = play(dir, "before", "base:drop", 36, pauseAndPick(settings, 20));
  ASSERT_EQ(before.process.exitCode, 0) << before.process.output;
  ASSERT_EQ(before.report["menu"]["page"], "settings") << before.report.dump(2);
  EXPECT_EQ(before.report["menu"]["selected"], "Resolution");
  EXPECT_EQ(before.report["window"]["width_px"], 640) << "scripted play keeps --width until the resolution changes";
  const int width = before.report["settings"]["width"].get<int>();
  auto after = play(dir, "after", "base:drop", 44, pauseAndPick(settings, 20) + tap("Left", 36));
  ASSERT_EQ(after.process.exitCode, 0) << after.process.output;
  const int newWidth = after.report["settings"]["width"].get<int>(), newHeight = after.report["settings"]["height"].get<int>();
  EXPECT_LT(newWidth, width) << after.report["settings"].dump(2);
  EXPECT_EQ(after.report["window"]["width_px"], newWidth) << after.report["window"].dump(2);
  EXPECT_EQ(after.report["window"]["height_px"], newHeight);
  std::ifstream file(dir + "/config/settings.json");
  nlohmann::json saved = nlohmann::json::parse(file, nullptr, false);
  EXPECT_EQ(saved["width"], newWidth) << saved.dump(2);
}

}  // namespace
}  // namespace tumble::test
