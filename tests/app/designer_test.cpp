// The scenario designer through SDL's real event path: `tumble design
// --frames N --events FILE --report r.json` (and `play` with the main
// menu's Designer) pushes scripted keys and mouse into SDL's queue
// (docs/play-events.md); the report's "designer" object says what the
// player saw: the map, the ground under the cursor, the objects, the undo
// state, where it was saved. Every test isolates HOME, so saves land in a
// folder of its own.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/design_document.h"
#include "app/fly_camera.h"
#include "screenshot_stats.h"
#include "tumble_process.h"

namespace tumble::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSize = " --width 640 --height 360 --quality low --mute";

struct Played {
  ProcessResult process;
  nlohmann::json report;
};


Played run(const std::string& dir, const std::string& name, const std::string& command, int frames,
           const std::string& events, const std::string& size = kSize) {
  const std::string eventsPath = dir + "/" + name + ".events", reportPath = dir + "/" + name + ".json";
  std::ofstream(eventsPath) << events;
  Played p;
  p.process = runTumble(command + " --frames " + std::to_string(frames) + " --events " + eventsPath + " --report " +
                            reportPath + size,
                        isolated(dir));
  std::ifstream in(reportPath);
  p.report = nlohmann::json::parse(in, nullptr, false);
  return p;
}

std::string tap(const std::string& key, int frame) {
  return std::to_string(frame) + " down key:" + key + "\n" + std::to_string(frame + 1) + " up key:" + key + "\n";
}
std::string ctrl(const std::string& key, int frame) {
  return std::to_string(frame) + " down key:Left Ctrl\n" + tap(key, frame + 1) + std::to_string(frame + 3) +
         " up key:Left Ctrl\n";
}
// Holds the left button at window pixel (x, y) from `frame` for `frames` frames.
std::string press(int x, int y, int frame, int frames) {
  return std::to_string(frame) + " move " + std::to_string(x) + " " + std::to_string(y) + "\n" +
         std::to_string(frame + 1) + " down mouse:left\n" + std::to_string(frame + 1 + frames) + " up mouse:left\n";
}

// A new flat map (the dialog's defaults: Return creates it), then a hill
// raised at the screen's centre by holding the left button for one second.
const std::string kNewMap = tap("Return", 2);
const std::string kHill = kNewMap + press(320, 180, 8, 60);

const nlohmann::json& designer(const Played& p) { return p.report["designer"]; }
double heightAtCursor(const Played& p) { return designer(p)["document"]["height_at_cursor_m"].get<double>(); }

void expectRan(const Played& p) {
  ASSERT_EQ(p.process.exitCode, 0) << p.process.output;
  ASSERT_FALSE(p.report.is_discarded()) << p.process.output;
  ASSERT_TRUE(p.report["designer"].is_object()) << p.report.dump(2);
}

// The palette's place of an entry (its order comes from the mods found; the
// report lists it), from a short run of the designer; -1 (and a failure) if
// it is not there.
int paletteIndex(const std::string& dir, const std::string& label) {
  auto first = run(dir, "palette", "design new", 6, kNewMap);
  EXPECT_EQ(first.process.exitCode, 0) << first.process.output;
  const auto& palette = first.report["designer"]["palette"];
  for (std::size_t i = 0; i < palette.size(); ++i)
    if (palette[i] == label) return int(i);
  ADD_FAILURE() << label << " is not in the palette: " << palette.dump();
  return -1;
}

// `.` pressed `steps` times from `frame` on (the next palette entry each);
// frame ends after the last.
std::string stepThroughPalette(int steps, int& frame) {
  std::string events;
  for (int i = 0; i < steps; ++i, frame += 2) events += tap(".", frame);
  return events;
}

TEST(Designer, MainMenuDesignerOpensTheNewMapDialogAndCreatesAFlatMap) {
  const std::string dir = outDir("designer_menu");
  // Root page: Play, Designer, ... -> Down, Return; then Return: Create.
  auto p = run(dir, "menu", "play", 40, tap("Down", 3) + tap("Return", 6) + tap("Return", 14) + "20 move 320 180\n");
  expectRan(p);
  EXPECT_FALSE(p.report["menu"]["open"].get<bool>()) << p.report["menu"].dump();
  const auto& d = designer(p);
  EXPECT_TRUE(d["active"].get<bool>());
  EXPECT_FALSE(d["new_map_open"].get<bool>());
  ASSERT_TRUE(d["document"].is_object()) << d.dump(2);
  EXPECT_EQ(d["document"]["samples"][0], 513);
  EXPECT_FALSE(d["document"]["can_undo"].get<bool>());
  ASSERT_FALSE(d["document"]["cursor_m"].is_null()) << "the pointer is over the map";
  // Flat at 0 m; heights are 16-bit steps over the flat map's range (-100 .. 300 m): 6 mm.
  EXPECT_NEAR(heightAtCursor(p), 0.0, 400.0 / 65535) << "a flat map at 0 m";
}

TEST(Designer, TheMouseRaisesAHillUnderTheCursorAndUndoRedoRestoreIt) {
  const std::string dir = outDir("designer_hill");
  auto flat = run(dir, "flat", "design new", 12, kNewMap + "8 move 320 180\n");
  expectRan(flat);
  const double ground = heightAtCursor(flat);
  auto hill = run(dir, "hill", "design new", 80, kHill);
  expectRan(hill);
  const double raised = heightAtCursor(hill);
  EXPECT_GT(raised, ground + 1.0) << designer(hill).dump(2);
  EXPECT_TRUE(designer(hill)["document"]["can_undo"].get<bool>());
  // Only the chunks the strokes touched were rebuilt in the last frames.
  EXPECT_LE(designer(hill)["terrain_chunks_invalidated"].get<int>(), 4);

  auto undone = run(dir, "undo", "design new", 90, kHill + ctrl("Z", 75));
  expectRan(undone);
  EXPECT_EQ(heightAtCursor(undone), ground) << "Ctrl+Z takes the whole stroke back, to the bit";
  EXPECT_TRUE(designer(undone)["document"]["can_redo"].get<bool>());

  auto redone = run(dir, "redo", "design new", 100, kHill + ctrl("Z", 75) + ctrl("Y", 85));
  expectRan(redone);
  EXPECT_EQ(heightAtCursor(redone), raised) << "Ctrl+Y brings the same hill back";
}

// The Objects tool's palette shows a picture of every model beside its
// name, and a click on a picture picks that model.
TEST(Designer, ObjectPaletteShowsAPictureOfEachModelAndAClickOnOnePicksIt) {
  const std::string dir = outDir("designer_thumbnails");
  const std::string shot = dir + "/palette.png";
  // Pictures are drawn one a frame: 60 frames cover the shipped models.
  auto p = run(dir, "palette", "design new --screenshot " + shot, 70, kNewMap + tap("3", 6),
               " --width 1280 --height 720 --quality low --mute");
  expectRan(p);
  const auto& rows = designer(p)["palette_rows"];
  ASSERT_GE(rows.size(), 3u) << designer(p).dump(2);
  int models = 0;
  std::vector<RegionStats> pictures;
  for (const auto& row : rows) {
    if (!row.contains("picture")) continue;  // props, gates, emitters, the start: by name
    ++models;
    EXPECT_EQ(row["picture"], "drawn") << row.dump();
    const int x = int(row["x_px"].get<double>()), y = int(row["y_px"].get<double>());
    const int side = int(row["h_px"].get<double>());
    if (pictures.size() < 3) pictures.push_back(regionStats(shot, x + 2, y + 2, side - 4, side - 4));
  }
  EXPECT_GE(models, 10) << "every shipped model is in the palette: " << rows.dump();
  ASSERT_EQ(pictures.size(), 3u);
  for (const RegionStats& r : pictures) {
    ASSERT_TRUE(r.loaded) << shot;
    // A flat panel background has no spread; a lit model on it has edges and shading.
    EXPECT_GT(r.brightnessSpread, 12.0) << "a picture, not an empty square";
  }
  // Different models, different pictures (the first three are the barrier,
  // the buggy and the building in the base mod).
  auto colourDistance = [](const RegionStats& a, const RegionStats& b) {
    double d = 0;
    for (int c = 0; c < 3; ++c) d += std::abs(a.meanRgb[std::size_t(c)] - b.meanRgb[std::size_t(c)]);
    return d;
  };
  EXPECT_GT(colourDistance(pictures[0], pictures[1]), 6.0);
  EXPECT_GT(colourDistance(pictures[1], pictures[2]), 6.0);

  // A click on the second model's name picks it, also when the pointer
  // jumps there from the first row in the same frame as the press (an
  // instant click, as xdotool and fast hands make).
  const auto& second = [&]() -> const nlohmann::json& {
    int seen = 0;
    for (const auto& row : rows)
      if (row.contains("picture") && ++seen == 2) return row;
    return rows[0];
  }();
  const int cx = int(second["x_px"].get<double>()) + 70, cy = int(second["y_px"].get<double>()) + 20;
  const std::string jump = "10 move " + std::to_string(cx) + " " + std::to_string(cy - 44) + "\n14 move " +
                           std::to_string(cx) + " " + std::to_string(cy) + "\n14 down mouse:left\n16 up mouse:left\n";
  auto clicked = run(dir, "click", "design new", 30, kNewMap + tap("3", 6) + jump,
                     " --width 1280 --height 720 --quality low --mute");
  expectRan(clicked);
  EXPECT_EQ(designer(clicked)["palette_selected"], second["label"]);
  EXPECT_EQ(designer(clicked)["document"]["objects"].size(), 0u) << "a click on the panel places nothing";

  // Then a press on the ground whose pointer jumps there from the panel in
  // the same frame places that model: the press is the ground's, though at
  // the last frame the pointer was over the panel.
  const std::string place = "20 move 800 450\n20 down mouse:left\n22 up mouse:left\n";
  auto placed = run(dir, "place", "design new", 30, kNewMap + tap("3", 6) + jump + place,
                    " --width 1280 --height 720 --quality low --mute");
  expectRan(placed);
  const auto& objects = designer(placed)["document"]["objects"];
  ASSERT_EQ(objects.size(), 1u) << designer(placed)["status"];
  EXPECT_EQ(objects[0]["asset"], "base:assets/models/buggy.obj") << "the model picked in the palette";
}

// Drags the left button from window pixel `from` to `to` in 10 moves.
std::string dragMouse(double fromX, double fromY, double toX, double toY, int frame) {
  std::string e = std::to_string(frame) + " move " + std::to_string(int(fromX)) + " " + std::to_string(int(fromY)) +
                  "\n" + std::to_string(frame + 1) + " down mouse:left\n";
  for (int k = 1; k <= 10; ++k)
    e += std::to_string(frame + 1 + k) + " move " + std::to_string(int(fromX + (toX - fromX) * k / 10)) + " " +
         std::to_string(int(fromY + (toY - fromY) * k / 10)) + "\n";
  return e + std::to_string(frame + 13) + " up mouse:left\n";
}

// The selected object's gizmo, driven with the mouse as a player does:
// the red arrow moves it along X only, the ring turns it, the post's top
// scales it, and each drag is one undo step.
TEST(Designer, DraggingTheGizmosHandlesMovesTurnsAndScalesTheSelectedObject) {
  const std::string dir = outDir("designer_gizmo");
  const std::string size = " --width 1280 --height 720 --quality low --mute";
  const int rock = paletteIndex(dir, "rock (base)");
  ASSERT_GE(rock, 0);
  // Place a rock: it is selected and shows its gizmo.
  std::string placed = kNewMap + tap("3", 6);
  int frame = 10;
  placed += stepThroughPalette(rock, frame);
  placed += press(700, 420, frame, 2);
  frame += 8;
  auto shown = run(dir, "placed", "design new", frame, placed, size);
  expectRan(shown);
  const auto& gizmo = designer(shown)["gizmo"];
  ASSERT_TRUE(gizmo["handles_px"].is_object()) << gizmo.dump();
  const auto& doc0 = designer(shown)["document"];
  ASSERT_EQ(doc0["objects"].size(), 1u);
  const auto& before = doc0["objects"][0];
  const double x0 = before["position_m"][0], z0 = before["position_m"][2];
  const double yaw0 = before["yaw_rad"], scale0 = before["scale"][0];
  const auto& handles = gizmo["handles_px"];

  // The red arrow dragged 120 px along its own screen direction.
  const double ax = handles["move_x"][0], ay = handles["move_x"][1];
  const double ux = ax - 700, uy = ay - 420, ulen = std::hypot(ux, uy);
  ASSERT_GT(ulen, 10.0) << "the X arrow is seen end-on from this eye: " << gizmo.dump();
  const std::string moveDrag = dragMouse(ax, ay, ax + 120 * ux / ulen, ay + 120 * uy / ulen, frame);
  auto moved = run(dir, "moved", "design new", frame + 18, placed + moveDrag, size);
  expectRan(moved);
  const auto& after = designer(moved)["document"]["objects"][0];
  EXPECT_GT(after["position_m"][0].get<double>(), x0 + 1.0) << "moved along +X: " << after.dump();
  EXPECT_EQ(after["position_m"][2].get<double>(), z0) << "and not along Z";
  EXPECT_EQ(designer(moved)["status"], "move_x done");
  auto undone = run(dir, "move_undone", "design new", frame + 26, placed + moveDrag + ctrl("Z", frame + 18), size);
  expectRan(undone);
  EXPECT_EQ(designer(undone)["document"]["objects"][0]["position_m"], before["position_m"]) << "one Ctrl+Z undoes the drag";

  // The ring: from its handle a quarter turn around the centre on screen.
  const double rx = handles["rotate"][0], ry = handles["rotate"][1];
  auto turned = run(dir, "turned", "design new", frame + 18, placed + dragMouse(rx, ry, 700 - (ry - 420) , 420 + (rx - 700), frame), size);
  expectRan(turned);
  const double yaw = designer(turned)["document"]["objects"][0]["yaw_rad"];
  EXPECT_GT(std::abs(std::remainder(yaw - yaw0, 2 * 3.14159265358979)), 0.3) << "turned";
  EXPECT_EQ(designer(turned)["document"]["objects"][0]["position_m"], before["position_m"]) << "in place";

  // The post's top dragged up 60 px: bigger, in proportion.
  const double sx = handles["scale"][0], sy = handles["scale"][1];
  auto scaled = run(dir, "scaled", "design new", frame + 18, placed + dragMouse(sx, sy, sx, sy - 60, frame), size);
  expectRan(scaled);
  const auto& big = designer(scaled)["document"]["objects"][0]["scale"];
  EXPECT_GT(big[0].get<double>(), 1.2 * scale0) << big.dump();
  EXPECT_DOUBLE_EQ(big[1].get<double>(), big[0].get<double>());
  EXPECT_EQ(designer(scaled)["document"]["objects"].size(), 1u) << "a drag on a handle places nothing";

  // A click on a handle without a drag is a click on the ground behind it:
  // the next rock is placed there (a row of trees, each beside the last).
  auto next = run(dir, "next", "design new", frame + 10, placed + press(int(ax), int(ay), frame, 1), size);
  expectRan(next);
  const auto& two = designer(next)["document"]["objects"];
  ASSERT_EQ(two.size(), 2u) << designer(next)["status"];
  EXPECT_EQ(two[0]["position_m"], before["position_m"]) << "the first rock stays where it was";
}

// From high up the designer's fog starts further out, so the far side of
// the map shows as ground, not haze; near the ground it is the course's own.
TEST(Designer, FromHighUpTheFogStartsFurtherOutSoTheWholeMapShows) {
  const std::string dir = outDir("designer_fog");
  const std::string shot = dir + "/high.png";
  auto high = run(dir, "high", "design new --screenshot " + shot, 12, kNewMap,
                  " --width 1280 --height 720 --quality low --mute");
  expectRan(high);
  const double eyeHeight = designer(high)["camera"]["position_m"][1];  // the new flat map lies at 0 m
  ASSERT_GT(eyeHeight, 40.0) << "the designer opens a map from above it";
  EXPECT_NEAR(designer(high)["fog_distance_m"].get<double>(), 8 * eyeHeight, 0.01 * eyeHeight);
  // The band just below the far edge of the map (the opening view looks
  // at the map from over its near edge): green ground, not the bluish grey
  // of fog (with the course's 250 m fog, G - B there was -9).
  const RegionStats far = regionStats(shot, 400, 278, 800, 20);
  ASSERT_TRUE(far.loaded);
  EXPECT_GT(far.meanRgb[1], far.meanRgb[2] + 10) << "far ground RGB " << far.meanRgb[0] << " " << far.meanRgb[1]
                                                 << " " << far.meanRgb[2];
  // Down near the ground (Q held 5 s): the weather's fog, 250 m on a clear day.
  auto low = run(dir, "low", "design new", 320, kNewMap + "5 down key:Q\n305 up key:Q\n",
                 " --width 640 --height 360 --quality low --mute");
  expectRan(low);
  const double lowHeight = designer(low)["camera"]["position_m"][1];
  ASSERT_LT(lowHeight, 250.0 / 8) << "Q took the eye down";
  EXPECT_DOUBLE_EQ(designer(low)["fog_distance_m"].get<double>(), 250.0);
}

TEST(Designer, PlacesARockSnappedToTheGroundAndSavesTheModUnderHome) {
  const std::string dir = outDir("designer_rock");
  const int rock = paletteIndex(dir, "rock (base)");
  ASSERT_GE(rock, 0);

  std::string events = kHill + tap("3", 72);
  int frame = 76;
  events += stepThroughPalette(rock, frame);
  events += press(400, 200, frame, 2);
  frame += 8;
  events += ctrl("S", frame) + tap("Return", frame + 8);  // Save: the Save as dialog; Return keeps mymap:course
  auto p = run(dir, "rock", "design new", frame + 20, events);
  expectRan(p);
  const auto& doc = designer(p)["document"];
  ASSERT_EQ(doc["objects"].size(), 1u) << doc.dump(2);
  const auto& rockObject = doc["objects"][0];
  EXPECT_EQ(rockObject["asset"], "base:assets/models/rock.obj");
  EXPECT_EQ(doc["saved_as"], "mymap:course") << designer(p)["status"];
  EXPECT_FALSE(doc["unsaved"].get<bool>());
  const fs::path mod = fs::path(dir) / "home/.local/share/tumble/mods/mymap";
  EXPECT_TRUE(fs::exists(mod / "mod.lua")) << mod;
  EXPECT_TRUE(fs::exists(mod / "scenarios/course.lua")) << mod;
  // The saved scenario names the rock through the modders' API.
  std::ifstream in(mod / "scenarios/course.lua");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("rock.obj"), std::string::npos) << text;
}

TEST(Designer, F5DrivesTheMapAndF5ComesBackWithNothingLost) {
  const std::string dir = outDir("designer_drive");
  const std::string drive = kNewMap + tap("F5", 10) + "20 down key:W\n140 up key:W\n";
  auto driving = run(dir, "driving", "design new", 140, drive);
  expectRan(driving);
  EXPECT_FALSE(designer(driving)["active"].get<bool>()) << "driving, not designing";
  ASSERT_TRUE(driving.report["vehicle"].is_object()) << driving.report.dump(2);
  EXPECT_GT(driving.report["vehicle"]["distance_m"].get<double>(), 3.0) << "W drives the car forward";

  auto before = run(dir, "before", "design new", 10, kNewMap);
  expectRan(before);
  auto back = run(dir, "back", "design new", 160, drive + tap("F5", 145));
  expectRan(back);
  const auto& d = designer(back);
  EXPECT_TRUE(d["active"].get<bool>());
  EXPECT_TRUE(back.report["scenario"].is_null()) << "the drive's scene is gone";
  EXPECT_EQ(d["document"]["revision"], designer(before)["document"]["revision"]) << "driving changes nothing";
  EXPECT_EQ(d["camera"], designer(before)["camera"]) << "the camera is where it was";
}

// The designer draws the sky the course will be played in: a design saved
// at midnight opens dark, one saved at noon bright (the panel and the
// flat ground are the same in both).
TEST(Designer, ShowsTheSkyOfTheDesignItOpens) {
  const std::string dir = outDir("designer_sky");
  const std::string mods = dir + "/home/.local/share/tumble/mods";
  for (const auto& [name, sky] : {std::pair{"noon", app::DesignSky{12.0, "clear", 0.2}},
                                  std::pair{"midnight", app::DesignSky{0.0, "clear", 0.2}}}) {
    app::NewMapOptions o;
    o.size_samples = 65;
    o.minHeight_m = 0;
    o.maxHeight_m = 1;
    auto created = app::DesignDocument::create(o);
    ASSERT_TRUE(created.ok()) << created.error();
    ASSERT_TRUE(created->setSky(sky));
    const Status st = created->saveAsMod(mods, "skies", name);
    ASSERT_TRUE(st.ok()) << st.error();
  }
  double mean[2] = {-1, -1};
  int k = 0;
  for (const char* name : {"noon", "midnight"}) {
    const std::string shot = dir + "/" + name + ".png";
    auto p = run(dir, name, std::string("design skies:") + name + " --screenshot " + shot, 4, "");
    expectRan(p);
    EXPECT_EQ(designer(p)["document"]["sky"]["time_of_day_h"].get<double>(), k == 0 ? 12.0 : 0.0);
    mean[k++] = meanBrightness(shot);
  }
  ASSERT_GT(mean[0], 0);
  ASSERT_GE(mean[1], 0);
  EXPECT_LT(mean[1], 0.8 * mean[0]) << "midnight " << mean[1] << " against noon " << mean[0];
}

// A slider dragged with the mouse follows it (the HUD keeps a button held
// from its down event to its up event and the pointer from the events):
// dragging the panel's hour slider to its left end turns the afternoon into
// night, and Ctrl+Z brings the afternoon back as one step.
TEST(Designer, DraggingTheHourSliderSetsTheSkyAndCtrlZUndoesIt) {
  const std::string dir = outDir("designer_hour");
  const std::string size = " --width 1280 --height 720 --quality low --mute";
  // The panel's hour slider spans x 16..164 at y 314 (its value 16.5 h sits at x 117).
  std::string drag = kNewMap + "10 move 117 314\n12 down mouse:left\n";
  int frame = 14;
  for (int x = 100; x >= 10; x -= 15, frame += 2) drag += std::to_string(frame) + " move " + std::to_string(x) + " 314\n";
  drag += std::to_string(frame + 2) + " up mouse:left\n";
  const int released = frame + 4;
  auto dragged = run(dir, "dragged", "design new", released + 4, drag, size);
  expectRan(dragged);
  const auto& sky = designer(dragged)["document"]["sky"];
  EXPECT_LT(sky["time_of_day_h"].get<double>(), 1.0) << sky.dump();
  EXPECT_EQ(sky["clouds"].get<double>(), 0.45) << "only the hour was dragged";
  auto undone = run(dir, "undone", "design new", released + 12, drag + ctrl("Z", released + 2), size);
  expectRan(undone);
  EXPECT_EQ(designer(undone)["document"]["sky"]["time_of_day_h"].get<double>(), 16.5);
  EXPECT_TRUE(designer(undone)["document"]["can_redo"].get<bool>());
}

TEST(Designer, EscapeOpensItsMenuAndQuitWithUnsavedChangesAsks) {
  const std::string dir = outDir("designer_quit");
  // Escape, Up (wraps to Quit), Return: the unsaved-changes question.
  auto asked = run(dir, "asked", "design new", 100, kHill + tap("Escape", 72) + tap("Up", 76) + tap("Return", 80));
  expectRan(asked);
  EXPECT_FALSE(asked.report["quit"].get<bool>()) << "an unsaved hill must not be dropped silently";
  EXPECT_EQ(designer(asked)["menu"]["page"], "confirm_leave");
  // Down, Return: Leave without saving.
  auto quit = run(dir, "quit", "design new", 100,
                  kHill + tap("Escape", 72) + tap("Up", 76) + tap("Return", 80) + tap("Down", 84) + tap("Return", 88));
  expectRan(quit);
  EXPECT_TRUE(quit.report["quit"].get<bool>());
}

TEST(FlyCamera, MovesWhereItLooksAndTurnsWithTheMouse) {
  app::FlyCamera c;
  c.position_m = {0, 10, 0};
  c.yaw_rad = 0;
  c.pitch_rad = -0.5f;
  app::FlyInput in;
  in.forward = true;
  c.update(in, 1.0f);
  // Forward is along +Z in the horizontal plane at the walking speed, whatever the pitch.
  EXPECT_NEAR(c.position_m.z(), app::FlyCamera::kSpeed_mps, 1e-4);
  EXPECT_NEAR(c.position_m.y(), 10, 1e-5);
  in = app::FlyInput{};
  in.up = true;
  in.fast = true;
  c.update(in, 0.5f);
  EXPECT_NEAR(c.position_m.y(), 10 + 0.5f * app::FlyCamera::kSpeed_mps * app::FlyCamera::kFastFactor, 1e-4);
  // Dragging right turns right (clockwise from above: towards -X when looking along +Z).
  in = app::FlyInput{};
  in.lookDx_px = 100;
  c.update(in, 0.0f);
  EXPECT_LT(c.forward().x(), 0);
  c.lookAt({0, 0, 50});
  EXPECT_NEAR(c.forward().normalized().dot((Eigen::Vector3f(0, 0, 50) - c.position_m).normalized()), 1.0f, 1e-5);
}

}  // namespace
}  // namespace tumble::test
