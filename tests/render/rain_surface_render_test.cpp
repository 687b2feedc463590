// Rain in a storm and two-sided surfaces (cloth), by pixel statistics of
// offscreen frames and by the CPU side of each (no GL).
#include <gtest/gtest.h>

#include <cmath>

#include "render/internal/rain.h"
#include "render/internal/surface_pass.h"
#include "render/renderer.h"
#include "render_test_util.h"

namespace tumble::render {
namespace {

SkySettings storm() {
  SkySettings sky;
  sky.weather = Weather::Storm;
  sky.cloudCover = 1;
  return sky;
}

TEST(Rain, StreaksFillTheBoxAroundTheEyeAndFallWithTheRain) {
  const RainShape shape;
  const Eigen::Vector3f eye(100.5f, 3, -40);
  std::vector<DrawParticle> now, later;
  appendRain(storm(), 20.0, eye, 3000, now);
  appendRain(storm(), 20.05, eye, 3000, later);
  // Only the drops inside the clear radius are left out: the box's share of
  // that ball's volume (4/3 pi 1.5^3 of 36 x 36 x 16 m^3 ~ 0.07 %).
  EXPECT_GT(now.size(), 2980u);
  EXPECT_LE(now.size(), 3000u);
  const Eigen::Vector3f v = rainVelocity(storm());
  EXPECT_LT(v.y(), -5.0f) << "rain falls";
  int moved = 0, compared = 0;
  for (std::size_t i = 0; i < std::min(now.size(), later.size()); ++i) {
    const DrawParticle& p = now[i];
    EXPECT_LE(std::abs(p.position.x() - eye.x()), shape.halfWidth_m);
    EXPECT_LE(std::abs(p.position.z() - eye.z()), shape.halfWidth_m);
    EXPECT_GE(p.position.y(), eye.y() - shape.below_m);
    EXPECT_LE(p.position.y(), eye.y() + shape.above_m);
    EXPECT_TRUE(p.stretch_m.isApprox(v * shape.exposure_s)) << "a streak along the rain's velocity";
    // Same drop 0.05 s later (unless it wrapped around the box, or one of
    // the two was inside the clear radius and shifted the indices).
    const Eigen::Vector3f step = later[i].position - p.position;
    ++compared;
    if (step.isApprox(v * 0.05f, 1e-3f)) ++moved;
  }
  EXPECT_GT(moved, compared * 9 / 10) << "drops move with the rain between frames";
  std::vector<DrawParticle> clear;
  appendRain(SkySettings{}, 20.0, eye, 3000, clear);
  EXPECT_TRUE(clear.empty()) << "no rain without a storm";
  appendRain(storm(), 20.0, eye, 0, clear);
  EXPECT_TRUE(clear.empty()) << "no rain with no drops to spend";
}

TEST(SurfaceTriangles, EachTriangleTwiceWithOppositeNormalsAndWindings) {
  DrawSurface s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  s.indices = {0, 1, 2, 0, 2, 3, 0, 1, 9, 0, 0, 1};  // the last two: an index past the end, no area
  std::vector<MeshVertex> out;
  ASSERT_EQ(appendTwoSided(s, out), 12u) << "two valid triangles, 6 vertices each";
  for (std::size_t t = 0; t < out.size(); t += 3) {
    const Eigen::Vector3f a(out[t].position), b(out[t + 1].position), c(out[t + 2].position);
    const Eigen::Vector3f face = (b - a).cross(c - a).normalized();
    const Eigen::Vector3f n(out[t].normal);
    EXPECT_NEAR(n.dot(face), 1.0f, 1e-5f) << "each copy wound to face along its own normal";
    EXPECT_NEAR(std::abs(n.z()), 1.0f, 1e-5f);
    EXPECT_EQ(n.z() > 0, (t / 3) % 2 == 0) << "front (+Z here), then back";
  }
}

constexpr int kWidth = 320, kHeight = 240;
class RainRender : public test::OffscreenRenderTest<kWidth, kHeight> {};

// Pixels whose brightness differs by more than 6 of 255 between two frames.
int changedPixels(const test::Image& a, const test::Image& b) {
  int n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const int da = a.at(x, y)[0] + a.at(x, y)[1] + a.at(x, y)[2];
      const int db = b.at(x, y)[0] + b.at(x, y)[1] + b.at(x, y)[2];
      n += std::abs(da - db) > 3 * 6;
    }
  return n;
}

TEST_F(RainRender, AStormFrameHasRainStreaksAClearOneHasNone) {
  FrameSnapshot frame;
  DrawShape ground;
  ground.kind = ShapeKind::Plane;
  ground.color = {0.4f, 0.45f, 0.35f};
  frame.shapes.push_back(ground);
  frame.simTime_s = 1.0;  // before the storm's first lightning (3 s slots): no flash in either frame
  Camera& camera = m_renderer->camera();
  camera.target = {0, 1.5f, 0};
  camera.pitch_rad = 0.1f;
  camera.distance_m = 4;
  RenderQuality quality = m_renderer->quality();
  auto shot = [&](Weather weather, int drops, const std::string& name) {
    frame.sky = weather == Weather::Storm ? storm() : SkySettings{};
    quality.rainDrops = drops;
    m_renderer->setQuality(quality);
    return render(frame, name);
  };
  const test::Image stormDry = shot(Weather::Storm, 0, "storm_dry.png");
  const test::Image stormWet = shot(Weather::Storm, 4000, "storm_wet.png");
  const test::Image clearDry = shot(Weather::Clear, 0, "clear_dry.png");
  const test::Image clearWet = shot(Weather::Clear, 4000, "clear_wet.png");
  const int streaks = changedPixels(stormDry, stormWet);
  // Dozens of streaks of several pixels each (about 480 changed pixels when
  // this was written; a few drops near the eye cover more).
  EXPECT_GT(streaks, 200) << "rain streaks over the storm's picture";
  EXPECT_EQ(changedPixels(clearDry, clearWet), 0) << "no rain in clear weather";
  // Streaks are long and thin: of the changed pixels, more have a changed
  // pixel above or below than beside them.
  int vertical = 0, horizontal = 0;
  auto changed = [&](int x, int y) {
    const int da = stormDry.at(x, y)[0] + stormDry.at(x, y)[1] + stormDry.at(x, y)[2];
    const int db = stormWet.at(x, y)[0] + stormWet.at(x, y)[1] + stormWet.at(x, y)[2];
    return std::abs(da - db) > 3 * 6;
  };
  for (int y = 1; y + 1 < kHeight; ++y)
    for (int x = 1; x + 1 < kWidth; ++x) {
      if (!changed(x, y)) continue;
      vertical += changed(x, y - 1) || changed(x, y + 1);
      horizontal += changed(x - 1, y) || changed(x + 1, y);
    }
  EXPECT_GT(vertical, horizontal) << "streaks, not dots (" << vertical << " vs " << horizontal << ")";
}

// Cloth surfaces share the shapes' shader with the planes' ground textures
// but never set those: they keep their own colour beside a grass plane and
// a checker plane alike (a default texture setting once drew them black).
TEST_F(RainRender, ASurfaceKeepsItsColourBesideAGroundTexturedPlane) {
  Camera& camera = m_renderer->camera();
  camera.target = {0, 1, 0};
  camera.yaw_rad = 0;
  camera.pitch_rad = 0.3f;
  camera.distance_m = 5;
  for (int texture : {-1, 0}) {
    FrameSnapshot frame;
    DrawShape ground;
    ground.kind = ShapeKind::Plane;
    ground.groundTexture = texture;
    frame.shapes.push_back(ground);
    DrawSurface flag;  // a 2 x 2 m red sheet standing up in front of the eye
    flag.positions = {{-1, 0.2f, 0}, {1, 0.2f, 0}, {1, 2.2f, 0}, {-1, 2.2f, 0}};
    flag.indices = {0, 1, 2, 0, 2, 3};
    flag.color = {0.9f, 0.08f, 0.06f};
    frame.surfaces.push_back(flag);
    const test::Image shot = render(frame, "flag_" + std::to_string(texture + 1) + ".png");
    EXPECT_GT(test::countPixels(shot, test::isReddish), 3000) << "ground texture " << texture;
  }
}

}  // namespace
}  // namespace tumble::render
