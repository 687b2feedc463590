// Sound from the command line: a headless run opens no audio device (the
// report says so); --audio-out renders the drive offline into a WAV with
// the engine in it; sound.play refuses missing, corrupt and badly described
// files with clear script errors, never a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "audio/clip.h"
#include "render/sky.h"
#include "tumble_process.h"
#include "../audio/signal.h"

namespace tumble::test {

namespace {

namespace fs = std::filesystem;

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return in ? nlohmann::json::parse(in, nullptr, false) : nlohmann::json{};
}

bool lists(const nlohmann::json& subsystems, const std::string& name) {
  if (!subsystems.is_array()) return false;
  auto v = subsystems.get<std::vector<std::string>>();
  return std::find(v.begin(), v.end(), name) != v.end();
}

}  // namespace

TEST(AudioCli, AHeadlessRunHasNoAudio) {
  const std::string dir = outDir("audio_headless");
  auto r = runTumble("run base:drive --set autopilot=1 --seconds 1 --report " + dir + "/r.json");
  // 2: the drive's distance and speed expectations need its full 40 s; only a start failure (1) or a script error (3) matters here.
  ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 2) << r.output;
  const auto j = readJson(dir + "/r.json");
  EXPECT_TRUE(lists(j["subsystems"], "vehicle")) << j["subsystems"].dump();
  EXPECT_FALSE(lists(j["subsystems"], "audio")) << j["subsystems"].dump();
}

// The autopilot drives for 3 s; the render is 3 s of 48 kHz stereo with
// sound in it, and the run (and its state hash) is the same as without sound.
TEST(AudioCli, AudioOutRendersTheDriveOffline) {
  const std::string dir = outDir("audio_out");
  auto r = runTumble("run base:drive --set autopilot=1 --seconds 3 --audio-out " + dir + "/drive.wav --report " + dir +
                     "/r.json");
  ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 2) << r.output;
  auto quiet = runTumble("run base:drive --set autopilot=1 --seconds 3 --report " + dir + "/q.json");
  ASSERT_EQ(quiet.exitCode, r.exitCode) << quiet.output;
  const auto j = readJson(dir + "/r.json");
  EXPECT_TRUE(lists(j["subsystems"], "audio")) << j["subsystems"].dump();
  EXPECT_EQ(j["state_hash"], readJson(dir + "/q.json")["state_hash"]) << "sound must not change the simulation";
  auto clip = audio::loadClip(dir + "/drive.wav");
  ASSERT_TRUE(clip) << clip.error();
  EXPECT_EQ(clip->rate_hz, 48000);
  EXPECT_NEAR(clip->seconds(), 3.0, 1.0 / 48000);
  double sum2 = 0;
  for (std::int16_t s : clip->samples) sum2 += double(s) * s;
  const double rms = std::sqrt(sum2 / double(clip->samples.size())) / 32768.0;
  EXPECT_GT(rms, 0.01) << "the engine is heard";
  EXPECT_LT(rms, 0.7);
}

// Thunder follows the lightning drawn: the storm's strike schedule
// (render::lightningStrikes) gives each flash's time and ground point; the
// listener is at the origin (no camera, no vehicle). The storm's rain hisses
// from the start (above 500 Hz), so the thunder's rumble is told by the
// band below 150 Hz: it jumps more than tenfold the first flash's distance /
// 343 m/s after it. Before that, the render is rain: a broadband hiss
// (spectral centroid above 1.5 kHz). The same scene in clear weather is
// silent throughout: no rain, no thunder.
TEST(AudioCli, ThunderArrivesTheSpeedOfSoundAfterEachFlash) {
  const std::string dir = outDir("audio_thunder");
  auto storm = runTumble("run good:storm_thunder " + testMods() + " --audio-out " + dir + "/storm.wav");
  ASSERT_EQ(storm.exitCode, 0) << storm.output;
  auto clear = runTumble("run good:storm_thunder " + testMods() + " --set weather=clear --audio-out " + dir +
                         "/clear.wav");
  ASSERT_EQ(clear.exitCode, 0) << clear.output;
  render::SkySettings sky;
  sky.weather = render::Weather::Storm;
  const auto strikes = render::lightningStrikes(sky, 0.0, 30.0);
  ASSERT_FALSE(strikes.empty()) << "the schedule has flashes in 30 s";
  auto wav = audio::loadClip(dir + "/storm.wav");
  ASSERT_TRUE(wav) << wav.error();
  // Mono floats (loadClip averages the channels), and their band below 150 Hz
  // (four one-pole low-passes: -24 dB an octave above it).
  std::vector<float> all(wav->samples.size()), low(wav->samples.size());
  double y[4] = {};
  const double a = 1 - std::exp(-2 * M_PI * 150.0 / wav->rate_hz);
  for (std::size_t i = 0; i < all.size(); ++i) {
    all[i] = float(wav->samples[i] / 32768.0);
    double x = all[i];
    for (double& yk : y) x = yk += a * (x - yk);
    low[i] = float(x);
  }
  auto slice = [&](const std::vector<float>& v, double from_s, double to_s) {
    const std::size_t i0 = std::size_t(std::max(0.0, from_s) * wav->rate_hz);
    const std::size_t i1 = std::min(v.size(), std::size_t(to_s * wav->rate_hz));
    return std::vector<float>(v.begin() + std::ptrdiff_t(std::min(i0, i1)), v.begin() + std::ptrdiff_t(i1));
  };
  const double arrival_s = strikes[0].time_s + double(strikes[0].ground_m.norm()) / 343.0;
  ASSERT_LT(arrival_s + 0.5, wav->seconds());
  ASSERT_GT(arrival_s, 2.0) << "the rain has faded in before the first thunder";
  const double before = audio::test::rms(slice(low, arrival_s - 0.5, arrival_s - 0.03));
  const double after = audio::test::rms(slice(low, arrival_s + 0.03, arrival_s + 0.5));
  std::printf("below 150 Hz: %.5f before the first thunder, %.5f after it (%.2f s in)\n", before, after, arrival_s);
  EXPECT_GT(after, 10 * before) << "the thunder, " << arrival_s << " s in";
  EXPECT_GT(after, 1e-3);
  const auto rain = slice(all, arrival_s - 1.5, arrival_s - 0.03);
  std::printf("rain before it: rms %.4f, centroid %.0f Hz\n", audio::test::rms(rain), audio::test::spectralCentroid(rain));
  EXPECT_GT(audio::test::rms(rain), 0.01) << "the storm's rain";
  EXPECT_GT(audio::test::spectralCentroid(rain), 1500) << "a hiss, not a rumble";
  // (Clear weather may make no audio at all: nothing sounds, so no file.)
  auto quiet = audio::loadClip(dir + "/clear.wav");
  if (quiet) {
    double sum2 = 0;
    for (std::int16_t v : quiet->samples) sum2 += double(v) * v;
    EXPECT_LT(std::sqrt(sum2 / double(std::max<std::size_t>(1, quiet->samples.size()))) / 32768.0, 1e-4)
        << "no storm: no rain, no thunder";
  }
}

// play opens the default audio device unless --mute. A machine without one
// plays silently and says so once (this is checked only where no device
// opens, as on the test machine); --mute opens none and says nothing.
TEST(AudioCli, PlayWithoutADeviceSaysSoOnceAndMuteSaysNothing) {
  const std::string dir = outDir("audio_play_device");
  std::ofstream(dir + "/w.events") << "0 down key:W\n";
  auto times = [](const std::string& text, const std::string& part) {
    int n = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
  };
  const std::string args = "play base:drive --frames 30 --events " + dir + "/w.events --width 320 --height 180";
  auto muted = runTumble(args + " --mute", "env TUMBLE_CONFIG_DIR=" + dir + " ");
  ASSERT_EQ(muted.exitCode, 0) << muted.output;
  EXPECT_EQ(times(muted.output, "playing silently"), 0) << muted.output;
  auto played = runTumble(args, "env TUMBLE_CONFIG_DIR=" + dir + " ");
  ASSERT_EQ(played.exitCode, 0) << played.output;
  const int said = times(played.output, "playing silently");
  if (said == 0) GTEST_SKIP() << "an audio device opened on this machine";
  EXPECT_EQ(said, 1) << played.output;
  EXPECT_NE(played.output.find("no audio output device"), std::string::npos) << played.output;
}

// A box dropped on the ground (a plane: rock) sounds as its Material.sound:
// metal rings (40 dB down only after more than five times as long as wood),
// and the sound material never changes the simulation (same state hash).
TEST(AudioCli, ImpactsSoundAsTheBodysMaterial) {
  const std::string dir = outDir("audio_struck");
  double decay[2];
  std::string hash[2];
  const char* materials[2] = {"metal", "wood"};
  for (int i = 0; i < 2; ++i) {
    const std::string name = dir + "/" + materials[i];
    auto r = runTumble("run good:struck " + testMods() + " --set sound=" + materials[i] + " --audio-out " + name +
                       ".wav --report " + name + ".json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    auto wav = audio::loadClip(name + ".wav");
    ASSERT_TRUE(wav) << wav.error();
    std::vector<float> x(wav->samples.size());
    for (std::size_t k = 0; k < x.size(); ++k) x[k] = float(wav->samples[k] / 32768.0);
    decay[i] = audio::test::decayTime(x, 40);
    hash[i] = readJson(name + ".json")["state_hash"].get<std::string>();
    std::printf("%s box on the ground: rms %.4f, 40 dB decay %.3f s\n", materials[i], audio::test::rms(x), decay[i]);
    EXPECT_GT(audio::test::rms(x), 1e-4) << materials[i] << ": the landing is heard";
  }
  EXPECT_GT(decay[0], 5 * decay[1]) << "metal rings, wood knocks";
  EXPECT_EQ(hash[0], hash[1]) << "the sound material is heard, not simulated";
}

// A mod whose scenario plays sounds: a good file, a missing one, a corrupt
// one, one outside the mod, bad fields and a NaN. Each failure must be a Lua
// error (caught by pcall) whose message names the problem; the scenario's
// expectations check the messages, so the run passes only if all are right.
TEST(AudioCli, SoundFileProblemsAreClearScriptErrors) {
  const fs::path mod = fs::path(outDir("audio_mod")) / "sounds";
  fs::create_directories(mod / "scenarios");
  fs::create_directories(mod / "assets");
  std::ofstream(mod / "mod.lua") << "return {name = \"sounds\", version = \"0.1.0\", title = \"sound test\", api = 1}\n";
  std::vector<float> beep(4800);
  for (std::size_t i = 0; i < beep.size(); ++i) beep[i] = 0.3f * float(std::sin(2 * M_PI * 440.0 * double(i) / 48000.0));
  ASSERT_TRUE(audio::writeWav((mod / "assets/beep.wav").string(), beep, 1, 48000));
  std::ofstream(mod / "assets/corrupt.wav") << "RIFF\x24\x10\x00\x00WAVEfmt garbage that is not a wave file";
  std::ofstream(mod / "assets/notes.txt") << "not a sound";
  // Vehicles with their own engine sample: a corrupt one is refused at spawn, naming the field and file.
  fs::create_directories(mod / "vehicles");
  const std::string axles =
      "axles = {{position = {0.8, -0.2, 1.3}, steered = true, driven = true}, {position = {0.8, -0.2, -1.3}}}";
  std::ofstream(mod / "vehicles/broken_sample.lua")
      << "return {" << axles << ", sound = {engine_sample = \"assets/corrupt.wav\"}}\n";
  std::ofstream(mod / "vehicles/sampled.lua")
      << "return {" << axles << ", sound = {engine_sample = \"assets/beep.wav\", sample_rpm = 2000}}\n";
  std::ofstream(mod / "scenarios/play.lua") << R"(
local function err(t)
  local ok, e = pcall(sound.play, t)
  return ok and "no error" or tostring(e)
end
local function has(s, part) return string.find(s, part, 1, true) ~= nil end
return {
  duration = 0.5,
  on_start = function()
    local box = world.box{size = {1, 1, 1}, mass = 1, position = {0, 3, 0}}
    local s = sound.play{file = "assets/beep.wav", body = box, volume = 0.5}
    expect("good file plays", s:playing())
    s:set_pitch(1.5); s:set_volume(0.2)
    s:stop()
    expect("stopped", not s:playing())
    local e = err{file = "assets/missing.wav", position = {0, 0, 0}}
    expect("missing file named", has(e, "missing.wav"))
    e = err{file = "assets/corrupt.wav"}
    expect("corrupt file named", has(e, "corrupt.wav") and has(e, "WAV"))
    e = err{file = "assets/notes.txt"}
    expect("not a sound file", has(e, "notes.txt") and has(e, "Ogg Vorbis"))
    e = err{file = "../../etc/passwd"}
    expect("outside the mod refused", not has(e, "no error"))
    e = err{file = "assets/beep.wav", volum = 1}
    expect("misspelt field named", has(e, "unknown field 'volum'"))
    e = err{file = "assets/beep.wav", pitch = 0/0}
    expect("NaN pitch refused", has(e, "pitch"))
    e = err{file = "assets/beep.wav", position = {0, 0, 0}, body = box}
    expect("position and body refused", has(e, "not both"))
    local ok, d = pcall(sound.thunder, {position = {686, 0, 0}})
    expect("thunder delay", ok and math.abs(d - 2) < 1e-9)
    local okv, ev = pcall(vehicle.spawn, "sounds:broken_sample", {position = {0, 0, 0}})
    expect("broken engine sample named", not okv and has(tostring(ev), "engine_sample") and has(tostring(ev), "corrupt.wav"))
    expect("sampled engine spawns", (pcall(vehicle.spawn, "sounds:sampled", {position = {10, 0, 0}})))
    local loops = {}
    for i = 1, 32 do loops[i] = sound.play{file = "assets/beep.wav", loop = true} end
    e = err{file = "assets/beep.wav"}
    expect("cap on sounds", has(e, "limit"))
  end,
}
)";
  const std::string dir = outDir("audio_mod_run");
  auto r = runTumble("run sounds:play --mods " + mod.parent_path().string() + " --report " + dir + "/r.json");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  const auto j = readJson(dir + "/r.json");
  ASSERT_TRUE(j["expectations"].is_array()) << r.output;
  EXPECT_EQ(j["expectations"].size(), 13u) << j["expectations"].dump(1);
  for (const auto& e : j["expectations"]) EXPECT_TRUE(e["ok"].get<bool>()) << e.dump();
  EXPECT_TRUE(j["script_errors"].empty()) << j["script_errors"].dump(1);
  EXPECT_FALSE(lists(j["subsystems"], "audio")) << "scripts' sounds in a headless run open no device";
}

}  // namespace tumble::test
