// Snapshots of a running scene (app/scene_state.h, docs/snapshots.md),
// through the real `tumble run` as a user runs it:
//   - a run split by --save-state FILE --at T and --load-state FILE ends in
//     the same state hash, bit for bit, as the run without a split, for every
//     base scenario a snapshot can hold, at two split times; saving does not
//     change the run's own hash; the loaded run's expectations pass as the
//     unsplit run's do;
//   - scenarios with systems a snapshot does not hold are refused at save
//     time with a message naming them;
//   - a tampered, truncated, foreign or mismatched file is refused with a
//     message naming the field, never a crash;
//   - a run loaded from a snapshot draws the picture of the unsplit run
//     (colours, models, camera and sky set after on_start).
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <stb/stb_image.h>

#include "tumble_process.h"

namespace tumble::test {
namespace {

std::string scenarioName(const std::string& ref) {
  std::string n = ref;
  for (char& ch : n)
    if (ch == ':') ch = '_';
  return n;
}

std::string hashOf(const ProcessResult& r) {
  std::smatch m;
  return std::regex_search(r.output, m, std::regex("; state ([0-9a-f]{16})")) ? m[1].str() : std::string("none");
}

std::string readAll(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

void writeAll(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << text;
}

struct SplitCase {
  const char* scenario;
  double at_s;
  /// The scenario keeps what its expectations check in locals (against
  /// the rule in docs/snapshots.md): after loading they start again from
  /// on_start, so only the end state is compared, not the exit status.
  /// (bullets and effects sum statistics over the whole run, and effects
  /// keeps emitter handles, which ctx.state cannot hold.)
  bool expectationsInLocals = false;
  const char* set = "";  ///< a --set NAME=VALUE for all three runs, or empty
};
void PrintTo(const SplitCase& c, std::ostream* os) {
  *os << c.scenario << (*c.set ? std::string(" --set ") + c.set : std::string()) << " at " << c.at_s << " s";
}

// Every base scenario whose state a snapshot holds: rigid bodies (boxes,
// spheres, capsules, hulls, compounds, static meshes), stacks and piles in
// resting contact (warm starts), sleeping bodies, springs with the sdirk2
// integrator, terrain (height-field contacts), on_update and on_contact
// scripts, timers and random numbers.
// The others are in kRefused below, with why.
constexpr const char* kSplittable[] = {
    "base:bullets", "base:cradle", "base:drop",  "base:incline", "base:mass_ratio", "base:overlap", "base:pyramid",
    "base:spin",    "base:springs", "base:stack", "base:hills",   "base:island",     "base:valley",
    "base:rolling",  // a cylinder and a sphere rolling down an incline
    // joints under both solvers: a chain, rag-dolls falling, piled and hit
    "base:chain",   "base:ragdoll_hit", "base:ragdoll_pile", "base:ragdoll_stairs",
    // ropes and cloth (implicit solves warm-started), emitters and their particles
    "base:rope",    "base:cloth",   "base:effects",
    // vehicles (engines, gearboxes, wheels, differentials) with the drive
    // helpers' state in ctx.state: the player's car, autopilots in a convoy,
    // on mud, into a wall of boxes
    "base:drive",   "base:showroom", "base:convoy", "base:mud", "base:crash_test",
    // ode.system objects (state vectors and integrators, by the order made)
    "base:foucault", "base:pendulum", "base:top", "base:bead_wire", "base:pulley",
    // timers made in on_start, both random generators, ctx.state, on_contact
    "bodies:script_state",
    // balls shot after on_start (bodies made again from their saved size)
    "bodies:spawned_later",
    // vehicles spawned, re-tuned and removed after on_start (made again
    // from their saved definitions), and a car re-tuned in on_update
    "bodies:vehicles_later", "bodies:tuned_later",
};
constexpr double kSplitTimes_s[] = {0.5, 1.5};
// The joint scenes again under their other joint solver (chain, ragdoll_hit
// and ragdoll_stairs run the impulse solver, ragdoll_pile the Lagrange one),
// and the drive scene with its autopilot (waypoints, gearbox, traction).
// time_trial (trigger volumes made by on_start: the gates; the lap in
// ctx.state) needs its autopilot to finish a lap headless: split before the
// first gate and mid-lap. An empty set: only another split time.
struct WithSet {
  const char* scenario;
  const char* set;
  double at_s;
};
constexpr WithSet kWithSet[] = {
    {"base:chain", "physics.joint_solver=lagrange", 1.0},
    {"base:ragdoll_stairs", "physics.joint_solver=lagrange", 1.0},
    {"base:ragdoll_pile", "physics.joint_solver=impulse", 1.0},
    {"base:drive", "autopilot=1", 1.0},
    {"base:time_trial", "autopilot=1", 1.5},
    {"base:time_trial", "autopilot=1", 10.0},
    // after the rag-doll was spawned (bodies and joints made after on_start) and thrown
    {"base:crash_test", "", 3.0},
    // after a convex hull and a compound were dropped (made again from their saved data)
    {"bodies:spawned_later", "hull=1", 1.2},
    // after a static model was placed across the balls' path (its triangle mesh made again)
    {"bodies:spawned_later", "mesh=1", 1.2},
};

std::vector<SplitCase> splitCases() {
  std::vector<SplitCase> out;
  for (const WithSet& w : kWithSet) out.push_back({w.scenario, w.at_s, false, w.set});
  for (const char* s : kSplittable)
    for (double t : kSplitTimes_s)
      out.push_back({s, t, std::string(s) == "base:bullets" || std::string(s) == "base:effects"});
  return out;
}

class SplitRun : public testing::TestWithParam<SplitCase> {};

TEST_P(SplitRun, EndsInTheSameStateAsTheRunWithoutASplit) {
  const SplitCase& c = GetParam();
  const std::string name = scenarioName(c.scenario) + "_" + std::to_string(int(c.at_s * 10)) + (*c.set ? "_set" : "");
  const std::string dir = outDir("scene_state_" + name);
  const std::string file = dir + "/snap.json";
  const std::string run = testMods() + " run " + c.scenario + (*c.set ? std::string(" --set ") + c.set : "");
  const ProcessResult plain = runTumble(run);
  const ProcessResult saving = runTumble(run + " --save-state " + file + " --at " + std::to_string(c.at_s));
  ASSERT_TRUE(std::filesystem::exists(file)) << saving.output;
  // Without the --set: the snapshot holds the run's settings.
  const ProcessResult loaded = runTumble(testMods() + " run " + c.scenario + " --load-state " + file);
  EXPECT_NE(hashOf(plain), "none") << plain.output;
  EXPECT_EQ(hashOf(saving), hashOf(plain)) << "saving a snapshot changed the run\n" << saving.output;
  EXPECT_EQ(hashOf(loaded), hashOf(plain)) << "the run from the snapshot ends elsewhere\n" << loaded.output;
  EXPECT_EQ(plain.exitCode, 0) << plain.output;
  EXPECT_EQ(saving.exitCode, plain.exitCode) << saving.output;
  if (!c.expectationsInLocals) {
    EXPECT_EQ(loaded.exitCode, plain.exitCode) << loaded.output;
  }
}

INSTANTIATE_TEST_SUITE_P(BaseScenarios, SplitRun, testing::ValuesIn(splitCases()),
                         [](const testing::TestParamInfo<SplitCase>& info) {
                           std::string n = scenarioName(info.param.scenario) + "_at_" +
                                           std::to_string(int(info.param.at_s * 10)) + "ds";
                           // "physics.joint_solver=lagrange" -> "_lagrange", "autopilot=1" -> "_autopilot_1"
                           std::string set = info.param.set;
                           if (set.find('=') != std::string::npos && set.rfind("physics.", 0) == 0)
                             set = set.substr(set.find('=') + 1);
                           for (char& ch : set)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           if (!set.empty()) n += "_" + set;
                           return n;
                         });

// No base scenario is refused. What a snapshot cannot hold is made after
// on_start: a timer's or a trigger's function (SnapshotTimers below), an
// ode.system (SnapshotLimits).

class SnapshotFile : public testing::Test {
 protected:
  void SetUp() override {
    dir = outDir(std::string("scene_state_file_") + testing::UnitTest::GetInstance()->current_test_info()->name());
    file = dir + "/snap.json";
    const ProcessResult r = runTumble("run base:stack --seconds 2 --save-state " + file + " --at 1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    text = readAll(file);
  }
  ProcessResult loadEdited(const std::string& edited, const std::string& scenario = "base:stack") {
    const std::string f = dir + "/edited.json";
    writeAll(f, edited);
    return runTumble("run " + scenario + " --seconds 2 --load-state " + f);
  }
  std::string dir, file, text;
};

TEST_F(SnapshotFile, HoldsTheRunsSettingsAndVersions) {
  for (const char* field : {"\"format\"", "\"version\"", "\"checksum\"", "\"engine_build\"", "\"scenario\"",
                            "\"mods\"", "\"seed\"", "\"dt_s\"", "\"substeps\"", "\"sets\"", "\"world\"", "\"script\""})
    EXPECT_NE(text.find(field), std::string::npos) << field;
}

TEST_F(SnapshotFile, AnEditedFileIsRefusedByItsChecksum) {
  std::string edited = text;
  const std::size_t at = edited.find("\"world\": \"") + 20;
  edited[at] = edited[at] == '0' ? '1' : '0';
  const ProcessResult r = loadEdited(edited);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("\"checksum\""), std::string::npos) << r.output;
}

TEST_F(SnapshotFile, ATruncatedFileIsRefused) {
  const ProcessResult r = loadEdited(text.substr(0, text.size() / 2));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("not a scene snapshot"), std::string::npos) << r.output;
}

TEST_F(SnapshotFile, AnotherScenarioIsRefusedNamingTheField) {
  const ProcessResult r = loadEdited(text, "base:pyramid");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("\"scenario\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("base:stack"), std::string::npos) << r.output;
}

TEST_F(SnapshotFile, ANewerFormatIsRefusedNamingTheVersion) {
  std::string edited = text;
  const std::size_t at = edited.find("\"version\": 2");
  ASSERT_NE(at, std::string::npos);
  edited.replace(at, 12, "\"version\": 7");
  const ProcessResult r = loadEdited(edited);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("\"version\""), std::string::npos) << r.output;
}

TEST_F(SnapshotFile, NotJsonIsRefused) {
  const ProcessResult r = loadEdited(std::string("\x7f" "ELF garbage\0\1\2", 16));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("not a scene snapshot"), std::string::npos) << r.output;
}

TEST(SnapshotTimers, ATimerMadeAfterOnStartIsRefusedNamingWhereItIsDefined) {
  const std::string dir = outDir("scene_state_late_timer");
  const std::string file = dir + "/snap.json";
  const ProcessResult r =
      runTumble(testMods() + " run bodies:script_state --set late_timer=1 --save-state " + file + " --at 1");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("defined at scenarios/script_state.lua:45 "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("after on_start"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(file));
}

TEST(SnapshotTimers, ATriggerMadeAfterOnStartIsRefused) {
  const std::string dir = outDir("scene_state_late_trigger");
  const std::string file = dir + "/snap.json";
  const ProcessResult r =
      runTumble(testMods() + " run bodies:script_state --set late_trigger=1 --save-state " + file + " --at 1");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("trigger volume was made after on_start"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(file));
}

TEST_F(SnapshotFile, SavingAfterTheEndWritesNothing) {
  const std::string f = dir + "/late.json";
  const ProcessResult r = runTumble("run base:stack --seconds 1 --save-state " + f + " --at 5");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("before --at"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(f));
}

// What a snapshot cannot put back is refused when loading, naming it.
// An ode.system made after on_start: its Lua functions are not stored.
TEST(SnapshotLimits, AnOdeSystemMadeAfterOnStartRefusesTheLoad) {
  const std::string dir = outDir("scene_state_limit_ode");
  const std::string file = dir + "/snap.json";
  const std::string run = testMods() + " run bodies:script_state";
  const ProcessResult saving = runTumble(run + " --set late_ode=1 --save-state " + file + " --at 1");
  ASSERT_TRUE(std::filesystem::exists(file)) << saving.output;
  const ProcessResult loaded = runTumble(run + " --load-state " + file);
  EXPECT_EQ(loaded.exitCode, 1) << loaded.output;
  EXPECT_NE(loaded.output.find("field \"script\""), std::string::npos) << loaded.output;
  EXPECT_NE(loaded.output.find("ode.system number 1 is in the snapshot but was made after on_start"),
            std::string::npos)
      << loaded.output;
}

// What is seen is part of a snapshot: a run loaded after a coloured ball, a
// box drawn as a model, a building without collision, a follow camera and
// an evening sky were set in on_update (bodies:seen_later, at 0.5 s) draws
// the very picture of the run without a split. Before, the loaded run drew
// the ball and box in the default grey, no models, the default camera and
// the afternoon sky.
std::vector<unsigned char> pixelsOf(const std::string& path, int* w, int* h) {
  int n = 0;
  unsigned char* data = stbi_load(path.c_str(), w, h, &n, 3);
  if (!data) return {};
  std::vector<unsigned char> out(data, data + std::size_t(*w) * std::size_t(*h) * 3);
  stbi_image_free(data);
  return out;
}

TEST(SnapshotPresentation, ARunLoadedAfterColoursModelsCameraAndSkyWereSetLooksAsTheRunWithoutASplit) {
  const std::string dir = outDir("scene_state_presentation");
  const std::string run = testMods() + " run bodies:seen_later";
  const ProcessResult plain = runTumble(run + " --screenshot " + dir + "/plain.png --at 1.5");
  const ProcessResult saving = runTumble(run + " --save-state " + dir + "/snap.json --at 1");
  const ProcessResult loaded =
      runTumble(run + " --load-state " + dir + "/snap.json --screenshot " + dir + "/loaded.png --at 1.5");
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  ASSERT_EQ(saving.exitCode, 0) << saving.output;
  ASSERT_EQ(loaded.exitCode, 0) << loaded.output;
  EXPECT_EQ(hashOf(loaded), hashOf(plain)) << loaded.output;
  int w = 0, h = 0, w2 = 0, h2 = 0;
  const std::vector<unsigned char> a = pixelsOf(dir + "/plain.png", &w, &h);
  const std::vector<unsigned char> b = pixelsOf(dir + "/loaded.png", &w2, &h2);
  ASSERT_FALSE(a.empty());
  ASSERT_EQ(w, w2);
  ASSERT_EQ(h, h2);
  // The picture shows what on_update made: the red ball the camera follows
  // and the red and white barrier (720 such pixels at 1280 x 720; none in
  // the picture a loaded run drew before snapshots held what is seen).
  std::size_t red = 0, differ = 0;
  for (std::size_t i = 0; i < a.size(); i += 3) {
    if (a[i] > 2 * a[i + 1] + 20 && a[i] > 2 * a[i + 2] + 20) ++red;
    if (a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2]) ++differ;
  }
  EXPECT_GT(red, std::size_t(100)) << "no red ball or barrier in " << dir << "/plain.png";
  EXPECT_EQ(differ, 0u) << "of " << w * h << " pixels; compare " << dir << "/plain.png and loaded.png";
}

// The models of a snapshot are read as "MOD:path" and resolved inside the
// mods: a snapshot edited to point a model outside (its checksum made to
// match) is refused, naming the field, and nothing is read there.
TEST(SnapshotPresentation, AModelPathEditedToLeaveTheModIsRefused) {
  const std::string dir = outDir("scene_state_presentation_path");
  const std::string file = dir + "/snap.json";
  const std::string run = testMods() + " run bodies:seen_later";
  ASSERT_EQ(runTumble(run + " --save-state " + file + " --at 1").exitCode, 0);
  std::string text = readAll(file);
  auto hex = [](const std::string& s) {
    std::string out;
    for (unsigned char ch : s) out += "0123456789abcdef"[ch >> 4], out += "0123456789abcdef"[ch & 15];
    return out;
  };
  // The same length: the byte count before the text stays right.
  const std::string from = hex("base:assets/models/barrier.obj"), to = hex("base:../../../../../etc/passwd");
  ASSERT_EQ(from.size(), to.size());
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << "the model's reference is not in the snapshot's script bytes";
  text.replace(at, from.size(), to);
  const std::string edited = dir + "/edited.json";
  writeAll(edited, text);
  ProcessResult r = runTumble(run + " --load-state " + edited);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex("content gives ([0-9a-f]{16})"))) << r.output;
  const std::size_t sum = text.find("\"checksum\"");
  ASSERT_NE(sum, std::string::npos);
  const std::size_t q = text.find('"', text.find(':', sum) + 1);
  text.replace(q + 1, 16, m[1].str());
  writeAll(edited, text);
  r = runTumble(run + " --load-state " + edited);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("field \"script\": script state: presentation: models on bodies"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("leaves the folder of mod \"base\""), std::string::npos) << r.output;
}

}  // namespace
}  // namespace tumble::test
