// Pictures: `run --screenshot` renders offscreen; the picture shows the
// bodies, not just the clear colour. `play` without a display plays
// offscreen, writes a screenshot and prints a summary.
#include <gtest/gtest.h>

#include <stb/stb_image.h>

#include "tumble_process.h"

namespace tumble::test {

namespace {
struct Image {
  int w = 0, h = 0;
  std::vector<unsigned char> rgb;
};
Image load(const std::string& path) {
  Image img;
  int n = 0;
  unsigned char* data = stbi_load(path.c_str(), &img.w, &img.h, &n, 3);
  if (data) {
    img.rgb.assign(data, data + std::size_t(img.w) * img.h * 3);
    stbi_image_free(data);
  }
  return img;
}
// Pixels that are clearly red (the test boxes), whatever the lighting.
int redPixels(const Image& img) {
  int n = 0;
  for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3) {
    int r = img.rgb[i], g = img.rgb[i + 1], b = img.rgb[i + 2];
    n += r > 80 && r > 2 * g && r > 2 * b;
  }
  return n;
}
}  // namespace

TEST(Screenshot, RunScreenshotShowsTheBodiesNotJustTheSky) {
  std::string dir = outDir("screenshot");
  auto sky = runTumble(testMods() + " run good:sky --screenshot " + dir + "/sky.png --width 320 --height 240");
  ASSERT_EQ(sky.exitCode, 0) << sky.output;
  auto boxes = runTumble(testMods() + " run good:boxes --screenshot " + dir + "/boxes.png --width 320 --height 240");
  ASSERT_EQ(boxes.exitCode, 0) << boxes.output;
  Image a = load(dir + "/sky.png"), b = load(dir + "/boxes.png");
  ASSERT_EQ(a.w, 320);
  ASSERT_EQ(a.h, 240);
  ASSERT_EQ(b.w, 320);
  EXPECT_EQ(redPixels(a), 0);
  EXPECT_GT(redPixels(b), 320 * 240 / 50) << "the two red boxes cover a good part of the picture";
}

// Ropes and cloth are drawn (as tubes and shaded surfaces; a scene with no
// particles too: the red flag must reach the picture).
TEST(Screenshot, ClothAndRopesAreDrawn) {
  std::string dir = outDir("screenshot_cloth");
  auto r = runTumble("run base:cloth --seconds 2.5 --screenshot " + dir + "/cloth.png --width 640 --height 360");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  Image img = load(dir + "/cloth.png");
  ASSERT_EQ(img.w, 640);
  // Count pixels clearly redder than they are green or blue (the flag).
  int reddish = 0;
  for (std::size_t i = 0; i + 2 < img.rgb.size(); i += 3)
    reddish += img.rgb[i] > img.rgb[i + 1] + 40 && img.rgb[i] > img.rgb[i + 2] + 40;
  EXPECT_GT(reddish, 150) << "the red flag";
}

TEST(Screenshot, AtPicksTheMomentOfThePicture) {
  std::string dir = outDir("screenshot_at");
  // At 1 s the bodies are still falling; whether the scenario's rest checks
  // hold then is not this test's business, only that both runs finished.
  auto r0 = runTumble("run base:drop --seconds 1 --screenshot " + dir + "/t0.png --at 0 --width 320 --height 240");
  auto r3 = runTumble("run base:drop --seconds 1 --screenshot " + dir + "/t3.png --width 320 --height 240");
  ASSERT_TRUE(r0.exitCode == 0 || r0.exitCode == 2) << r0.output;
  ASSERT_TRUE(r3.exitCode == 0 || r3.exitCode == 2) << r3.output;
  Image a = load(dir + "/t0.png"), b = load(dir + "/t3.png");
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  ASSERT_FALSE(a.rgb.empty());
  EXPECT_NE(a.rgb, b.rgb) << "bodies fell between 0 s and 1 s";
}

TEST(Screenshot, PlayWithoutADisplayPlaysOffscreenAndWritesAPicture) {
  std::string dir = outDir("play");
  // No display is visible to the child, even on a desktop.
  auto r = runTumble(testMods() + " play good:boxes --screenshot " + dir + "/play.png --width 800 --height 600",
                     "env -u DISPLAY -u WAYLAND_DISPLAY ");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("screenshot"), std::string::npos) << r.output;
  Image img = load(dir + "/play.png");
  EXPECT_EQ(img.w, 800);
  EXPECT_GT(redPixels(img), 2000) << r.output;
}

}  // namespace tumble::test
