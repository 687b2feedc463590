// Saving a design as a mod scenario: what is written, opening it again
// bit-identically, the backup of an earlier save, and bad input (names,
// a full disk, a model that does not load) leaving the earlier save intact.
// The saved mod is then checked and run through the real binary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "app/design_document.h"
#include "app/paths.h"
#include "app/terrain_scene.h"
#include "core/file_util.h"
#include "core/hash.h"
#include "terrain/png_io.h"
#include "tumble_process.h"

namespace tumble::app {
namespace {

namespace fs = std::filesystem;

/// path relative to `dir` -> hash of its bytes, for every file below it.
std::map<std::string, std::uint64_t> folderHashes(const fs::path& dir) {
  std::map<std::string, std::uint64_t> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    auto bytes = readBinaryFile(e.path().string());
    EXPECT_TRUE(bytes.ok());
    Hasher h;
    if (bytes.ok()) h.bytes(bytes->data(), bytes->size());
    out[fs::relative(e.path(), dir).string()] = h.digest();
  }
  return out;
}

/// A small course: a hill, a ditch, a mud patch, trees, a rock, props and three gates.
DesignDocument course() {
  NewMapOptions o;
  o.generator = "plasma";
  o.size_samples = 129;
  o.seed = 3;
  o.roughness = 0.4;
  o.minHeight_m = 0;
  o.maxHeight_m = 3;  // gentle ground a car can sit on anywhere
  auto created = DesignDocument::create(o);
  EXPECT_TRUE(created.ok());
  DesignDocument d = std::move(created.value());
  Brush hill;
  hill.radius_m = 12;
  hill.strength_m_per_s = 2;
  hill.falloff = 1;
  d.beginStroke();
  for (int k = 0; k < 20; ++k) d.dab(hill, -40 + 0.5 * k, 40, 1.0 / 60);
  d.endStroke();
  d.line(false, Vec2(30, -50), Vec2(50, 30), 6, 1);
  d.paint(*findSurface("mud"), -20, -20, 6);
  d.paint(*findSurface("asphalt"), 0, 10, 3);
  auto place = [&](PlacedKind kind, const std::string& asset, double x, double z, Vec3 scale = Vec3::Ones()) {
    PlacedObject p;
    p.kind = kind;
    p.asset = asset;
    p.position_m = Vec3(Real(x), 0, Real(z));
    p.yaw_rad = 0.25 * x;
    p.scale = scale;
    return d.addObject(p);
  };
  for (int k = 0; k < 5; ++k) place(PlacedKind::Model, "base:assets/models/tree.obj", -50 + 8 * k, -45);
  place(PlacedKind::Model, "base:assets/models/rock.obj", 45, 45, Vec3(2, 1.5, 2));
  place(PlacedKind::Box, "", -10, 30, Vec3(1, 1, 1));
  place(PlacedKind::Barrel, "", -12, 30, Vec3(0.6, 0.9, 0.6));
  place(PlacedKind::Ragdoll, "", -14, 34);
  place(PlacedKind::Emitter, "base:smoke", 40, -40);
  place(PlacedKind::Trigger, "", 20, 20, Vec3(4, 2, 4));
  for (int g = 1; g <= 3; ++g) {
    PlacedObject gate;
    gate.kind = PlacedKind::Gate;
    gate.position_m = Vec3(0, 0, Real(15 * g));
    gate.scale = Vec3(10, 1.5, 1);
    gate.order = 4 - g;  // placed last-first: the order field decides
    d.addObject(gate);
  }
  d.setStart(Vec3(0, 0, -10), 0.0);
  d.setVehicle("base:buggy");
  d.setTitle("Test course: a hill, a ditch, mud, trees and gates");
  EXPECT_TRUE(d.setSky({19.0, "cloudy", 0.7}));
  return d;
}

fs::path freshDir(const std::string& name) { return fs::path(test::outDir(name)); }

}  // namespace

TEST(DesignSave, WritesAModThatOpensBitIdentically) {
  const fs::path mods = freshDir("design_save_roundtrip");
  DesignDocument d = course();
  Status st = d.saveAsMod(mods.string(), "mymap", "course");
  ASSERT_TRUE(st.ok()) << st.error();
  const fs::path mod = mods / "mymap";
  for (const char* f : {"mod.lua", "scenarios/course.lua", "maps/course.png", "maps/course.png.json",
                        "maps/course.texture.png", "maps/course.bump.png", "maps/course.friction.png",
                        "maps/course.sound.png", "maps/course.softness.png", "designs/course.design.json"})
    EXPECT_TRUE(fs::is_regular_file(mod / f)) << f;
  EXPECT_FALSE(fs::exists(mod / "backup")) << "nothing to back up on a first save";
  auto opened = DesignDocument::open(mod.string(), "course");
  ASSERT_TRUE(opened.ok()) << opened.error();
  EXPECT_EQ(opened->contentHash(), d.contentHash());
  EXPECT_TRUE(opened->terrain().heights() == d.terrain().heights());
  EXPECT_EQ(opened->meta(), d.meta());
  EXPECT_EQ(opened->sky(), (DesignSky{19.0, "cloudy", 0.7}));
  for (int l = 0; l < terrain::kMaterialLayerCount; ++l)
    EXPECT_EQ(opened->terrain().materials()->layer(terrain::MaterialLayer(l)),
              d.terrain().materials()->layer(terrain::MaterialLayer(l)))
        << terrain::materialLayerName(terrain::MaterialLayer(l));
  // The scene a run builds from the saved files is the designed one: the
  // same heights and the painted friction under the mud patch.
  auto scene = TerrainScene::create({{"terrain.heightmap", (mod / "maps/course.png").string()}});
  ASSERT_TRUE(scene.ok()) << scene.error();
  EXPECT_TRUE((*scene)->terrain().heights() == d.terrain().heights());
  EXPECT_NEAR((*scene)->heightField().frictionAt(-20, -20), 0.3, 1e-6);
  EXPECT_NEAR((*scene)->terrain().heightAt(-30, 40), d.groundHeight_m(-30, 40), 1e-6);
}

TEST(DesignSave, SavingAgainKeepsTheEarlierSaveInBackup) {
  const fs::path mods = freshDir("design_save_backup");
  DesignDocument d = course();
  ASSERT_TRUE(d.saveAsMod(mods.string(), "mymap", "course").ok());
  const fs::path mod = mods / "mymap";
  const auto first = folderHashes(mod);
  const std::uint64_t firstHash = d.contentHash();
  Brush b;
  d.dab(b, 0, 0, 1);
  d.setTitle("Second version");
  // A staging folder left by a save that was killed is cleared; one of a
  // live process (pid 1) is not touched.
  fs::create_directories(mod / ".saving-course-999999999" / "scenarios");
  fs::create_directories(mod / ".saving-course-1");
  ASSERT_TRUE(d.saveAsMod(mods.string(), "mymap", "course").ok());
  EXPECT_FALSE(fs::exists(mod / ".saving-course-999999999"));
  EXPECT_TRUE(fs::exists(mod / ".saving-course-1"));
  fs::remove_all(mod / ".saving-course-1");
  const auto backup = folderHashes(mod / "backup" / "course");
  EXPECT_EQ(backup.size(), first.size() - 1) << "every file of the scenario (mod.lua stays: it is shared)";
  for (const auto& [rel, hash] : backup) EXPECT_EQ(hash, first.at(rel)) << rel;
  auto reopened = DesignDocument::open(mod.string(), "course");
  ASSERT_TRUE(reopened.ok()) << reopened.error();
  EXPECT_EQ(reopened->title(), "Second version");
  EXPECT_EQ(reopened->contentHash(), d.contentHash());
  // The backup opens too: it is the earlier save, whole.
  fs::copy_file(mod / "mod.lua", mod / "backup" / "course" / "mod.lua");
  auto earlier = DesignDocument::open((mod / "backup" / "course").string(), "course");
  ASSERT_TRUE(earlier.ok()) << earlier.error();
  EXPECT_EQ(earlier->contentHash(), firstHash);
}

TEST(DesignSave, BadNamesAreRefusedAndWriteNothing) {
  const fs::path mods = freshDir("design_save_names");
  DesignDocument d = course();
  for (const char* name : {"../escape", "a/b", "..", "", "has space", "x\\y"}) {
    Status st = d.saveAsMod(mods.string(), name, "course");
    ASSERT_FALSE(st.ok()) << name;
    EXPECT_NE(st.error().find("mod name"), std::string::npos) << st.error();
    st = d.saveAsMod(mods.string(), "ok", name);
    ASSERT_FALSE(st.ok()) << name;
    EXPECT_NE(st.error().find("scenario name"), std::string::npos) << st.error();
  }
  EXPECT_TRUE(fs::is_empty(mods)) << "nothing written for a refused name";
  EXPECT_FALSE(fs::exists(mods.parent_path() / "escape"));
}

// A full disk: the write of any one of the files fails. The earlier save
// must stay as it was, byte for byte, with no staging files left behind.
TEST(DesignSave, AFailedWriteLeavesTheEarlierSaveIntact) {
  const fs::path mods = freshDir("design_save_full_disk");
  DesignDocument d = course();
  ASSERT_TRUE(d.saveAsMod(mods.string(), "mymap", "course").ok());
  const fs::path mod = mods / "mymap";
  const auto before = folderHashes(mod);
  Brush b;
  d.dab(b, 10, 10, 1);
  for (int failAt = 0; failAt < 9; ++failAt) {
    int calls = 0;
    std::string failedFile;
    auto full = [&](const std::string& path, const void* data, std::size_t size) -> Status {
      if (calls++ == failAt) {
        failedFile = fs::path(path).filename().string();
        return makeError(path + ": write failed (No space left on device)");
      }
      return writeFileAtomic(path, data, size);
    };
    Status st = d.saveAsMod(mods.string(), "mymap", "course", full);
    ASSERT_FALSE(st.ok()) << "failing write " << failAt;
    EXPECT_NE(st.error().find("No space left on device"), std::string::npos) << st.error();
    EXPECT_NE(st.error().find(failedFile), std::string::npos) << st.error();
    EXPECT_NE(st.error().find("earlier save is unchanged"), std::string::npos) << st.error();
    EXPECT_EQ(folderHashes(mod), before) << "failing write " << failAt;
  }
  // A mods folder that cannot be a folder (a file is in the way).
  const fs::path blocked = mods / "blocked";
  ASSERT_TRUE(writeFileAtomic(blocked.string(), std::string("a file")).ok());
  Status st = d.saveAsMod(blocked.string(), "mymap", "course");
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().find("blocked"), std::string::npos) << st.error();
}

TEST(DesignSave, AModelThatDoesNotLoadIsNamedAndNothingIsWritten) {
  const fs::path mods = freshDir("design_save_bad_model");
  // A mod of props with a broken model file.
  fs::create_directories(mods / "props" / "assets");
  ASSERT_TRUE(writeFileAtomic((mods / "props" / "mod.lua").string(),
                              std::string("return {name = \"props\", version = \"1.0.0\", api = 1, depends = {}}\n"))
                  .ok());
  ASSERT_TRUE(writeFileAtomic((mods / "props" / "assets" / "junk.obj").string(), std::string("v 0 0\nf 1 2 x\n")).ok());
  DesignDocument d = course();
  ASSERT_TRUE(d.saveAsMod(mods.string(), "mymap", "course").ok());
  const auto before = folderHashes(mods / "mymap");
  for (const char* asset : {"props:assets/junk.obj", "base:assets/models/no_such_model.obj", "nomod:a.obj",
                            "base:../../etc/passwd"}) {
    PlacedObject p;
    p.kind = PlacedKind::Model;
    p.asset = asset;
    const std::uint32_t id = d.addObject(p);
    Status st = d.saveAsMod(mods.string(), "mymap", "course");
    ASSERT_FALSE(st.ok()) << asset;
    EXPECT_NE(st.error().find("model " + std::to_string(id)), std::string::npos) << st.error();
    EXPECT_NE(st.error().find(asset), std::string::npos) << st.error();
    EXPECT_EQ(folderHashes(mods / "mymap"), before) << asset;
    d.undo();
  }
  d.setVehicle("base:no_such_car");
  Status st = d.saveAsMod(mods.string(), "mymap", "course");
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().find("vehicle \"base:no_such_car\""), std::string::npos) << st.error();
}

TEST(DesignSave, ADamagedDesignFileIsNamedWithItsField) {
  const fs::path mods = freshDir("design_open_bad");
  DesignDocument d = course();
  ASSERT_TRUE(d.saveAsMod(mods.string(), "mymap", "course").ok());
  const fs::path file = mods / "mymap" / "designs" / "course.design.json";
  std::ifstream in(file);
  nlohmann::json j = nlohmann::json::parse(in);
  in.close();
  j["objects"][2]["kind"] = "spaceship";
  ASSERT_TRUE(writeFileAtomic(file.string(), j.dump()).ok());
  auto r = DesignDocument::open((mods / "mymap").string(), "course");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("objects[2].kind"), std::string::npos) << r.error();
  EXPECT_NE(r.error().find("course.design.json"), std::string::npos) << r.error();
  j["objects"][2]["kind"] = "box";
  for (const auto& [field, bad] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"weather", "fog"}, {"time_of_day_h", 25}, {"clouds", -0.5}, {"time_of_day_h", "noon"}}) {
    nlohmann::json broken = j;
    broken["sky"][field] = bad;
    ASSERT_TRUE(writeFileAtomic(file.string(), broken.dump()).ok());
    r = DesignDocument::open((mods / "mymap").string(), "course");
    ASSERT_FALSE(r.ok()) << field;
    EXPECT_NE(r.error().find("sky." + field), std::string::npos) << r.error();
  }
  // A design saved before the sky was kept (version 1) opens with the default sky.
  nlohmann::json older = j;
  older["version"] = 1;
  older.erase("sky");
  ASSERT_TRUE(writeFileAtomic(file.string(), older.dump()).ok());
  r = DesignDocument::open((mods / "mymap").string(), "course");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r->sky(), DesignSky{});
  j["heightmap"] = "../../outside.png";
  ASSERT_TRUE(writeFileAtomic(file.string(), j.dump()).ok());
  r = DesignDocument::open((mods / "mymap").string(), "course");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("leaves the mod's folder"), std::string::npos) << r.error();
  ASSERT_TRUE(writeFileAtomic(file.string(), std::string("{\"format\": \"tumble-design\", \"vers")).ok());
  r = DesignDocument::open((mods / "mymap").string(), "course");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("course.design.json"), std::string::npos) << r.error();
}

// ---- through the real binary ------------------------------------------------------------------

namespace {

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in, nullptr, false);
}

std::string failedExpectations(const nlohmann::json& report) {
  std::string out;
  for (const auto& e : report["expectations"])
    if (!e["ok"].get<bool>()) out += e.dump() + "\n";
  return out;
}

}  // namespace

TEST(DesignSaveCli, TheSavedModPassesCheckAndRunsTheSameTwice) {
  const fs::path mods = freshDir("design_cli");
  DesignDocument d = course();
  ASSERT_TRUE(d.saveAsMod(mods.string(), "mymap", "course").ok());
  const std::string modsArg = "--mods " + mods.string() + " ";
  auto r = test::runTumble(modsArg + "check " + (mods / "mymap").string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  // The player's car under drive.player with no input: it settles at the start.
  const std::string run = modsArg + "run mymap:course --seconds 4 --report ";
  r = test::runTumble(run + (mods / "a.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = test::runTumble(run + (mods / "b.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto a = readJson((mods / "a.json").string()), b = readJson((mods / "b.json").string());
  ASSERT_FALSE(a.is_discarded());
  EXPECT_EQ(a["state_hash"], b["state_hash"]);
  EXPECT_EQ(failedExpectations(a), "");
  EXPECT_EQ(a["expectations"].size(), 2u) << a["expectations"].dump();
  // The designed sky is set through the modders' API.
  std::ifstream lua(mods / "mymap" / "scenarios" / "course.lua");
  const std::string text((std::istreambuf_iterator<char>(lua)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("environment.set{time_of_day = 19, weather = \"cloudy\", clouds = 0.7}"), std::string::npos)
      << text.substr(0, 3000);
  // The trigger box placed at (20, 20) with yaw 5 rad is turned as it was placed.
  const auto trigger = text.find("trigger.box{center = {20, ");
  ASSERT_NE(trigger, std::string::npos) << text;
  EXPECT_NE(text.substr(trigger, text.find('\n', trigger) - trigger).find("rotation = {0, 5, 0}"), std::string::npos)
      << text.substr(trigger, 200);
  const auto subsystems = a["subsystems"].dump();
  EXPECT_NE(subsystems.find("terrain"), std::string::npos) << subsystems;
  // Without a single step the car has no wheel contact yet: the scenario's
  // expectations fail, so they do measure the stepped world.
  r = test::runTumble(modsArg + "run mymap:course --steps 0 --report " + (mods / "c.json").string());
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(failedExpectations(readJson((mods / "c.json").string())).find("wheels on the ground"), std::string::npos);
}

TEST(DesignPalette, ListsTheModelsAndEmittersOfTheLoadedMods) {
  const std::vector<std::string> folders = {dataDir() + "/mods"};
  const auto models = listModelAssets(folders);
  auto has = [](const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
  };
  EXPECT_TRUE(has(models, "base:assets/models/tree.obj"));
  EXPECT_TRUE(has(models, "base:assets/models/rock.obj"));
  EXPECT_FALSE(has(models, "base:assets/models/tree.mtl")) << "materials and textures are not models";
  EXPECT_TRUE(std::is_sorted(models.begin(), models.end()));
  const auto emitters = listEmitters(folders);
  for (const char* e : {"base:smoke", "base:fire", "base:rain"}) EXPECT_TRUE(has(emitters, e)) << e;
}

// Three gates on flat ground, in a line ahead of the start: the autopilot
// drives through them in order and the lap finishes.
TEST(DesignSaveCli, TheAutopilotDrivesTheGatesInOrder) {
  const fs::path mods = freshDir("design_cli_gates");
  NewMapOptions o;
  o.size_samples = 257;
  o.minHeight_m = 0;
  o.maxHeight_m = 10;
  o.flatHeight_m = 2;
  auto created = DesignDocument::create(o);
  ASSERT_TRUE(created.ok());
  DesignDocument& d = created.value();
  for (int g = 1; g <= 3; ++g) {
    PlacedObject gate;
    gate.kind = PlacedKind::Gate;
    gate.position_m = Vec3(0, 0, Real(25 * g));
    gate.scale = Vec3(10, 1.5, 1);
    gate.order = g;
    d.addObject(gate);
  }
  d.setStart(Vec3(0, 0, 0), 0.0);
  ASSERT_TRUE(d.saveAsMod(mods.string(), "gates", "straight").ok());
  auto r = test::runTumble("--mods " + mods.string() + " run gates:straight --set autopilot=1 --seconds 15 --report " +
                           (mods / "r.json").string());
  const auto report = readJson((mods / "r.json").string());
  ASSERT_EQ(r.exitCode, 0) << r.output << failedExpectations(report);
  bool gates = false;
  for (const auto& e : report["expectations"])
    if (e["name"] == "gates passed in order") gates = e["ok"].get<bool>() && e["value"].get<double>() == 3;
  EXPECT_TRUE(gates) << report["expectations"].dump();
}

// An image drawn elsewhere, given with --set terrain.heightmap= and no
// sidecar (512 x 512 pixels): the driving scenario's car stays on the map.
TEST(DesignSaveCli, ASidecarlessHeightMapKeepsTheCarOnTheMap) {
  const fs::path dir = freshDir("design_cli_drawn_map");
  std::vector<std::uint8_t> px(512 * 512);
  for (int j = 0; j < 512; ++j)
    for (int i = 0; i < 512; ++i)  // rolling hills, about +-3 m over 250 m
      px[std::size_t(j) * 512 + i] = std::uint8_t(std::lround(100 + 20 * std::sin(i / 40.0) * std::cos(j / 50.0)));
  auto png = terrain::encodePngGrey8(px.data(), 512, 512);
  ASSERT_TRUE(png.ok());
  ASSERT_TRUE(writeFileAtomic((dir / "drawn.png").string(), png->data(), png->size()).ok());
  auto r = test::runTumble("run base:drive --set autopilot=1 --set terrain.heightmap=" +
                           (dir / "drawn.png").string() + " --report " + (dir / "r.json").string());
  const auto report = readJson((dir / "r.json").string());
  EXPECT_EQ(r.exitCode, 0) << r.output << failedExpectations(report);
  EXPECT_EQ(failedExpectations(report), "");
}

}  // namespace tumble::app
