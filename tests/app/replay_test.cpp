// Replays (docs/replays.md): a session played with scripted input through
// SDL's event queue and recorded with `play --record` is run again headless
// by `run --replay` and ends in the very state the session ended in; an
// edited or foreign file is refused with a message that says so.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>
#include <string>

#include "tumble_process.h"

namespace tumble::test {
namespace {

std::string readAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Recorded {
  std::string dir, replay, hash;
};

// base:drive for 240 frames: throttle, then steering both ways, a tap of
// the brake; the player's config folder is the test's own.
Recorded recordDrive(const std::string& name) {
  Recorded r;
  r.dir = outDir(name);
  r.replay = r.dir + "/drive.replay";
  const std::string events = r.dir + "/drive.events", report = r.dir + "/play.json";
  std::ofstream(events) << "0 down key:W\n60 down key:A\n100 up key:A\n120 down key:D\n150 up key:D\n"
                           "180 up key:W\n181 down key:S\n182 up key:S\n200 down key:W\n";
  const ProcessResult p = runTumble("play base:drive --frames 240 --width 320 --height 180 --events " + events +
                                        " --report " + report + " --record " + r.replay,
                                    "env TUMBLE_CONFIG_DIR=" + r.dir + " ");
  EXPECT_EQ(p.exitCode, 0) << p.output;
  const nlohmann::json rep = nlohmann::json::parse(readAll(report), nullptr, false);
  EXPECT_FALSE(rep.is_discarded()) << p.output;
  if (!rep.is_discarded()) r.hash = rep["state_hash"].get<std::string>();
  return r;
}

TEST(Replay, ARecordedDriveEndsInTheSameStateHeadless) {
  const Recorded r = recordDrive("replay_drive");
  ASSERT_FALSE(r.hash.empty());
  const nlohmann::json doc = nlohmann::json::parse(readAll(r.replay), nullptr, false);
  ASSERT_FALSE(doc.is_discarded());
  EXPECT_EQ(doc["scenario"], "base:drive");
  EXPECT_EQ(doc["steps"], 240);
  EXPECT_EQ(doc["state_hash"], r.hash);
  EXPECT_GT(doc["action_changes"].size(), 5u);  // the keys above changed actions
  // The car moved under the recorded input: the end state is not the start's.
  const ProcessResult still = runTumble("run base:drive --steps 240");
  ASSERT_EQ(still.exitCode, 0) << still.output;
  EXPECT_EQ(still.output.find(r.hash), std::string::npos) << "without the input the run ends in the same state";

  const ProcessResult replayed = runTumble("run --replay " + r.replay);
  EXPECT_EQ(replayed.exitCode, 0) << replayed.output;
  EXPECT_NE(replayed.output.find("reproduced the recorded state " + r.hash), std::string::npos) << replayed.output;
  EXPECT_NE(replayed.output.find("state " + r.hash), std::string::npos) << replayed.output;
  EXPECT_EQ(replayed.output.find("warning"), std::string::npos) << replayed.output;
}

TEST(Replay, AnEditedReplayIsRefusedAndADivergenceIsReported) {
  const Recorded r = recordDrive("replay_tamper");
  ASSERT_FALSE(r.hash.empty());
  nlohmann::json doc = nlohmann::json::parse(readAll(r.replay));
  // An edit to the input without fixing the checksum: refused before running.
  nlohmann::json edited = doc;
  edited["action_changes"][0][2] = 0.25;
  std::ofstream(r.dir + "/edited.replay") << edited.dump();
  const ProcessResult e = runTumble("run --replay " + r.dir + "/edited.replay");
  EXPECT_EQ(e.exitCode, 1) << e.output;
  EXPECT_NE(e.output.find("the checksum does not match the content"), std::string::npos) << e.output;
  EXPECT_NE(e.output.find("edited.replay"), std::string::npos) << e.output;

  // An edit that recomputes the checksum (as a determined cheat would) still
  // cannot pass: the run ends elsewhere and says so.
  nlohmann::json forged = doc;
  for (auto& c : forged["action_changes"]) c[2] = 0.0, c[3] = 0;  // no input at all
  forged.erase("checksum");
  // The checksum rule (docs/replays.md): FNV-1a 64 of the compact JSON without the field.
  const std::string text = forged.dump();
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char ch : text) h = (h ^ ch) * 0x100000001b3ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  forged["checksum"] = hex;
  std::ofstream(r.dir + "/forged.replay") << forged.dump();
  const ProcessResult f = runTumble("run --replay " + r.dir + "/forged.replay");
  EXPECT_EQ(f.exitCode, 4) << f.output;
  EXPECT_NE(f.output.find("DIVERGED"), std::string::npos) << f.output;

  // Another build: the run goes on with a warning that names both builds.
  nlohmann::json other = doc;
  other["engine_build"] = "0123456789abcdef";
  other["mods"]["base"] = "0.0.1-other";
  other.erase("checksum");
  const std::string otherText = other.dump();
  h = 0xcbf29ce484222325ull;
  for (unsigned char ch : otherText) h = (h ^ ch) * 0x100000001b3ull;
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  other["checksum"] = hex;
  std::ofstream(r.dir + "/other.replay") << other.dump();
  const ProcessResult o = runTumble("run --replay " + r.dir + "/other.replay");
  EXPECT_EQ(o.exitCode, 0) << o.output;
  EXPECT_NE(o.output.find("recorded by engine build 0123456789abcdef"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("mod base was version 0.0.1-other when recording"), std::string::npos) << o.output;

  // Not a replay at all, and a truncated one.
  std::ofstream(r.dir + "/foreign.replay") << R"({"format": "tumble-bindings", "version": 1})";
  const ProcessResult g = runTumble("run --replay " + r.dir + "/foreign.replay");
  EXPECT_EQ(g.exitCode, 1) << g.output;
  EXPECT_NE(g.output.find("not a replay"), std::string::npos) << g.output;
  const std::string whole = readAll(r.replay);
  std::ofstream(r.dir + "/cut.replay") << whole.substr(0, whole.size() / 2);
  const ProcessResult c = runTumble("run --replay " + r.dir + "/cut.replay");
  EXPECT_EQ(c.exitCode, 1) << c.output;
  EXPECT_NE(c.output.find("not a replay"), std::string::npos) << c.output;
}

}  // namespace
}  // namespace tumble::test
