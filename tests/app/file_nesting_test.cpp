// Files the app reads as JSON (replays, the player's settings) are refused
// with a message when nested absurdly deep, instead of overflowing the
// stack when the loader serialises or copies them (found by the fuzz
// targets tools/fuzz/fuzz_replay.cpp and fuzz_settings.cpp).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/player_settings.h"
#include "app/replay.h"

namespace fs = std::filesystem;

namespace {

std::string nested(int depth) { return std::string(std::size_t(depth), '[') + std::string(std::size_t(depth), ']'); }

std::string writeTemp(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("tumble-file-nesting-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

}  // namespace

TEST(FileNesting, AReplayNested100000DeepIsRefusedWithAMessage) {
  const std::string path = writeTemp(
      "deep.replay.json", R"({"format": "tumble-replay", "version": 1, "checksum": "0", "x": )" + nested(100000) + "}");
  auto r = tumble::app::loadReplay(path);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find(path), std::string::npos) << r.error();
  EXPECT_NE(r.error().find("nested more than"), std::string::npos) << r.error();
}

TEST(FileNesting, SettingsNested100000DeepAreRefusedWithAMessage) {
  const std::string path = writeTemp("settings.json", R"({"format": )" + nested(100000) + "}");
  auto s = tumble::app::loadPlayerSettings(path);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().find(path), std::string::npos) << s.error();
  EXPECT_NE(s.error().find("nested more than"), std::string::npos) << s.error();
}

TEST(FileNesting, ShallowSettingsStillLoad) {
  const std::string path = writeTemp("ok_settings.json", R"({"format": "tumble-settings", "width": 800, "height": 600})");
  auto s = tumble::app::loadPlayerSettings(path);
  ASSERT_TRUE(s) << s.error();
  EXPECT_EQ(s->width, 800);
  EXPECT_EQ(s->height, 600);
}
