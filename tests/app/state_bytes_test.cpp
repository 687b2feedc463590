// Damaged snapshot bytes (docs/snapshots.md): each system's restoreState
// reads bytes a file may hand it after its checksum was forged, so every
// cut and every flipped byte must either be refused with a message or be
// accepted as a state the next step can run from, never crash, hang or
// read outside an array (the sanitizer build checks the last).
//
// One scene with every system (bodies, joints, a vehicle, a rope, particle
// emitters; tests/app/mods/bodies/scenarios/world_snapshot_systems.lua)
// runs 20 steps and is saved. Then, for each part (world, joints, vehicles,
// ropes and cloth, particles, the scenario's Lua state): the part cut at 48
// lengths and with 150 single bytes changed is restored; an accepted one is
// stepped once; the good state goes back before the next try. (Run with
// 20 000 changed bytes per part and other seeds while writing this, it
// found a joint state whose two impulse arrays differed in length, world
// settings with a billion substeps and an emitter carrying 1e300 particles
// into its next step; each is refused now.) At the end the
// good state is restored and the scene steps on to the same state hash as
// the same steps from the first restore.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <random>
#include <string>

#include "app/fixed_step.h"
#include "app/run_report.h"
#include "app/scene.h"
#include "script/presentation.h"
#include "script/systems_state.h"

namespace tumble::app {
namespace {

std::unique_ptr<Scene> startScene(const std::string& ref) {
  const char* source = std::getenv("TUMBLE_SOURCE_DIR");
  const std::string root = source ? source : ".";
  SceneOptions options;
  options.scenarioRef = ref;
  options.modDirs = {root + "/mods", root + "/tests/app/mods"};
  auto scene = Scene::create(options);
  EXPECT_TRUE(scene) << (scene ? "" : scene.error());
  if (!scene) return nullptr;
  (*scene)->start();
  return std::move(scene.value());
}

// Step indices stay below the scenario's own snapshot step (30), so its
// on_update only records.
void step(Scene& scene, int index) {
  RunTimings t;
  stepScene(scene, StepTime{index * scene.dt_s(), index}, t);
}

struct Saved {
  script::SystemsState systems;
  std::string script;
};

Status restore(Scene& scene, const Saved& s) {
  const auto& modDirs = scene.host().options().modDirs;
  auto inMods = [&](const std::string& file) { return script::isFileInMods(file, modDirs); };
  if (Status st = script::restoreSystems(scene, s.systems, inMods); !st) return st;
  return scene.host().restoreState(s.script, 0, 0);
}

/// The scene's state after its first 20 steps (all its parts).
Result<Saved> saveAfterTwentySteps(Scene& scene) {
  for (int i = 0; i < 20; ++i) step(scene, i);
  auto script = scene.host().saveState();
  if (!script) return makeError(script.error());
  return Saved{script::saveSystems(scene), *script};
}

/// The state hash 10 steps after restoring `good` (empty when refused).
std::string hashTenStepsAfter(Scene& scene, const Saved& good) {
  if (!restore(scene, good)) return {};
  for (int i = 0; i < 10; ++i) step(scene, 20 + i);
  return stateHashText(scene);
}

TEST(SnapshotBytes, CutOrChangedBytesAreRefusedOrRunNeverCrash) {
  auto scene = startScene("bodies:world_snapshot_systems");
  ASSERT_TRUE(scene);
  auto saved = saveAfterTwentySteps(*scene);
  ASSERT_TRUE(saved) << saved.error();
  const Saved& good = *saved;
  ASSERT_FALSE(good.systems.joints.empty());
  ASSERT_FALSE(good.systems.vehicles.empty());
  ASSERT_FALSE(good.systems.ropesAndCloth.empty());
  ASSERT_FALSE(good.systems.particles.empty());

  // The reference: 10 steps from the good state.
  const std::string expected = hashTenStepsAfter(*scene, good);
  ASSERT_FALSE(expected.empty());

  std::mt19937 rng(7);
  struct Part {
    const char* name;
    std::string* bytes;
  };
  Saved trial = good;
  const Part parts[] = {{"world", &trial.systems.world},          {"joints", &trial.systems.joints},
                        {"vehicles", &trial.systems.vehicles},    {"ropes_and_cloth", &trial.systems.ropesAndCloth},
                        {"particles", &trial.systems.particles},  {"script", &trial.script}};
  for (const Part& part : parts) {
    const std::string original = *part.bytes;
    int refused = 0, accepted = 0;
    auto attempt = [&](const std::string& damaged) {
      *part.bytes = damaged;
      if (restore(*scene, trial)) {
        ++accepted;
        step(*scene, 21);  // must not crash whatever it accepted
      } else {
        ++refused;
      }
      ASSERT_TRUE(restore(*scene, good)) << part.name;
    };
    for (int k = 0; k < 48; ++k) attempt(original.substr(0, original.size() * std::size_t(k) / 48));
    for (int k = 0; k < 150; ++k) {
      std::string damaged = original;
      const std::size_t at = std::uniform_int_distribution<std::size_t>(0, damaged.size() - 1)(rng);
      damaged[at] = char(std::uniform_int_distribution<int>(0, 255)(rng));
      attempt(damaged);
    }
    *part.bytes = original;
    std::printf("[snapshot bytes] %-16s %6zu bytes: %d refused, %d accepted and stepped\n", part.name,
                original.size(), refused, accepted);
    // Every cut shorter than the whole is refused.
    EXPECT_GE(refused, 48) << part.name;
  }

  // The good state still gives the reference.
  EXPECT_EQ(hashTenStepsAfter(*scene, good), expected);
}

// A refused script state changes nothing. The scenario's Lua state holds
// a trigger made in on_start, a timer, both generators and ctx.state
// (tests/app/mods/bodies/scenarios/script_state.lua). Eight bytes (zeros,
// then 0xff) are inserted at every offset, so each part reads a shifted
// tail and the state is refused somewhere after it. Each time the good state
// must go back, and at the end it must give the reference hash. Before, the
// trigger part was applied as soon as it was read: a shifted trigger id of
// 0 removed the trigger, the state was then refused for its trailing bytes,
// and the scene could not go back even to its own saved state ("trigger 1
// is in the snapshot but on_start did not make it here"; found by the
// snapshot fuzzer).
TEST(SnapshotBytes, ARefusedScriptStateLeavesTheSceneAsItWas) {
  auto scene = startScene("bodies:script_state");
  ASSERT_TRUE(scene);
  auto saved = saveAfterTwentySteps(*scene);
  ASSERT_TRUE(saved) << saved.error();
  const Saved& good = *saved;
  const std::string expected = hashTenStepsAfter(*scene, good);
  ASSERT_FALSE(expected.empty());

  int refused = 0;
  for (const char fill : {'\0', '\xff'})
    for (std::size_t at = 0; at <= good.script.size(); ++at) {
      Saved trial = good;
      trial.script.insert(at, 8, fill);
      if (!restore(*scene, trial)) ++refused;
      const Status back = restore(*scene, good);
      ASSERT_TRUE(back) << "after 8 bytes inserted at " << at << ": " << back.error();
    }
  std::printf("[snapshot bytes] script state %zu bytes: %d of %zu insertions refused\n", good.script.size(), refused,
              2 * (good.script.size() + 1));
  EXPECT_GT(refused, 0);
  EXPECT_EQ(hashTenStepsAfter(*scene, good), expected);
}

}  // namespace
}  // namespace tumble::app
