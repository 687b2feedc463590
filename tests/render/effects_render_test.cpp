// Lens flare and lightning, judged by pixel statistics of offscreen frames:
// the flare shows only when the camera faces the sun and goes when a hill
// hides the sun; storm frames differ where a bolt strikes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/internal/camera_math.h"
#include "render/internal/effects_pass.h"
#include "render/renderer.h"
#include "render_test_util.h"
#include "terrain_test_util.h"

namespace tumble::render {
namespace {

using test::Image;
using test::loadPng;

constexpr int kWidth = 320, kHeight = 240;

// Pixels whose colour differs by more than `threshold` in some channel,
// within columns [x0, x1).
int changedPixels(const Image& a, const Image& b, int threshold, int x0 = 0, int x1 = kWidth) {
  int n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = std::max(0, x0); x < std::min(a.width, x1); ++x)
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])) > threshold) {
          ++n;
          break;
        }
  return n;
}

class EffectsRender : public test::OffscreenRenderTest<kWidth, kHeight> {
 protected:
  // The same frame with the flare on and off: pixels it changed.
  int flarePixels(const FrameSnapshot& frame, const std::string& name) {
    m_renderer->settings().lensFlare = false;
    const Image off = render(frame, name + "_off.png");
    m_renderer->settings().lensFlare = true;
    const Image on = render(frame, name + "_on.png");
    return changedPixels(off, on, 4);
  }
};

TEST(FlareSprites, GlowRingHexagonAndStreakAreDistinctSoftShapes) {
  const int n = 32;
  const std::vector<std::uint8_t> s = buildFlareSprites(n, 4);
  ASSERT_EQ(s.size(), std::size_t(n * n * 4));
  auto at = [&](int sprite, int x, int y) { return int(s[std::size_t(y) * n * 4 + sprite * n + x]); };
  EXPECT_GT(at(0, n / 2, n / 2), 200) << "the glow is brightest in the middle";
  EXPECT_EQ(at(0, 0, 0), 0) << "and dark in the corner";
  EXPECT_LT(at(1, n / 2, n / 2), 10) << "a ring is dark inside";
  // The streak is a Gaussian 0.04 sprite-widths wide about the middle
  // line; the two middle rows lie 1/n off it: exp(-(1/32 / 0.04)^2) = 0.54.
  EXPECT_GT(at(3, n / 2, n / 2), 120) << "the streak crosses the middle";
  EXPECT_LT(at(3, n / 2, 2), 10) << "and is thin";
}

TEST_F(EffectsRender, TheFlareShowsOnlyFacingTheSunAndNotBehindAHill) {
  // A low sun (14 degrees) over flat ground; the camera looks towards it.
  test::TestTerrain flat(257, 257);
  FrameSnapshot frame;
  frame.sky.sunDirection = Eigen::Vector3f(0.0f, 0.25f, -1.0f).normalized();
  frame.terrain = &flat.surface;
  Camera& camera = m_renderer->camera();
  camera.target = flat.centre() + Eigen::Vector3f(0, 3, 0);
  camera.distance_m = 6.0f;
  camera.yaw_rad = 0.25f;     // eye at +Z, a little off the sun's bearing
  camera.pitch_rad = -0.12f;  // looking slightly up: the sun is in view
  const int facing = flarePixels(frame, "facing");
  EXPECT_GT(facing, kWidth * kHeight / 20) << "the flare crosses the picture";

  camera.yaw_rad = 0.25f + 3.14159f;  // turned round: the sun is behind the camera
  EXPECT_EQ(flarePixels(frame, "away"), 0);

  // A 60 m hill 100 m towards the sun: 31 degrees high from the eye, above the sun.
  test::TestTerrain hill(257, 257);
  for (int j = 0; j < hill.nz; ++j)
    for (int i = 0; i < hill.nx; ++i) {
      const double dz = j - (128 - 100), dx = i - 128;
      hill.setHeight_m(i, j, 60.0 * std::exp(-(dx * dx / (2.0 * 60 * 60) + dz * dz / (2.0 * 15 * 15))));
    }
  frame.terrain = &hill.surface;
  camera.yaw_rad = 0.25f;
  EXPECT_EQ(flarePixels(frame, "hill"), 0) << "the depth test finds the sun hidden";
}

TEST_F(EffectsRender, StormFramesDifferWhereLightningStrikes) {
  FrameSnapshot frame;
  frame.sky.weather = Weather::Storm;
  frame.sky.timeOfDay_h = 14.0f;
  // No rain: its streaks move between any two frames (rain_surface_render_test.cpp);
  // here only the lightning may change the picture.
  RenderQuality quality = m_renderer->quality();
  quality.rainDrops = 0;
  m_renderer->setQuality(quality);
  const std::vector<LightningStrike> strikes = lightningStrikes(frame.sky, 0.0, 60.0);
  ASSERT_FALSE(strikes.empty()) << "a minute of storm has strikes";
  const LightningStrike& s = strikes.front();
  EXPECT_EQ(lightningStrikes(frame.sky, 0.0, 60.0).size(), strikes.size()) << "the same schedule every time";
  // Look at the strike's ground point from the storm centre, from above the ground.
  Camera& camera = m_renderer->camera();
  camera.target = Eigen::Vector3f(0, 60, 0);
  const Eigen::Vector3f to = (s.ground_m - camera.target).normalized();
  camera.yaw_rad = std::atan2(-to.x(), -to.z());
  camera.pitch_rad = 0.0f;
  camera.distance_m = 1.0f;
  frame.simTime_s = s.time_s - 1.0 / 60.0;
  const Image before = render(frame, "before.png");
  frame.simTime_s = s.time_s + 1.0 / 60.0;
  const Image during = render(frame, "during.png");
  // The bolt's column on screen: where its ground point lands.
  const FrameView view = makeFrameView(camera, float(kWidth) / kHeight);
  const Eigen::Vector4f c = view.viewProjection * s.ground_m.homogeneous();
  const int x = int((c.x() / c.w() * 0.5f + 0.5f) * kWidth);
  ASSERT_TRUE(x > 0 && x < kWidth) << x;
  // The flash brightens the whole sky; the bolt itself turns pixels near white.
  auto whiteNew = [&](int x0, int x1) {
    int n = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int px = std::max(0, x0); px < std::min(kWidth, x1); ++px)
        n += *std::min_element(during.at(px, y), during.at(px, y) + 3) > 225 &&
             *std::min_element(before.at(px, y), before.at(px, y) + 3) <= 225;
    return n;
  };
  const int band = whiteNew(x - 40, x + 40);
  EXPECT_GT(band, 100) << "near-white bolt pixels around its column";
  EXPECT_GT(band, 4 * (whiteNew(0, 40) + whiteNew(kWidth - 40, kWidth)))
      << "far more at the bolt than at the picture's edges";
  EXPECT_GT(changedPixels(before, during, 20, 0, 40), 0) << "the flash brightens the sky everywhere";
  m_renderer->settings().lightning = false;
  const Image quiet = render(frame, "quiet.png");
  EXPECT_LT(changedPixels(before, quiet, 60), 10) << "lightning off: no flash, no bolt";
}

}  // namespace
}  // namespace tumble::render
