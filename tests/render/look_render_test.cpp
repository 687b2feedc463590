// The look, judged by pixel statistics of offscreen frames (Mesa llvmpipe),
// not golden images: shadows darken the ground under a box, the sky's
// horizon has the fog's colour, the time of day and the weather change
// the sky.
#include <gtest/gtest.h>

#include <cmath>

#include "render/internal/camera_math.h"
#include "render/internal/sky_model.h"
#include "render/renderer.h"
#include "render_test_util.h"

namespace tumble::render {
namespace {

using test::Image;
using test::loadPng;

constexpr int kWidth = 320, kHeight = 240;

Eigen::Vector2i toPixel(const Camera& camera, const Eigen::Vector3f& p) {
  const Eigen::Vector4f c = makeFrameView(camera, float(kWidth) / float(kHeight)).viewProjection * p.homogeneous();
  return {int((c.x() / c.w() * 0.5f + 0.5f) * kWidth), int((1.0f - (c.y() / c.w() * 0.5f + 0.5f)) * kHeight)};
}

// Mean colour (0..255) of a square of pixels around (x, y).
Eigen::Vector3f meanColor(const Image& image, int cx, int cy, int half) {
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  int n = 0;
  for (int y = std::max(0, cy - half); y <= std::min(image.height - 1, cy + half); ++y)
    for (int x = std::max(0, cx - half); x <= std::min(image.width - 1, cx + half); ++x) {
      const std::uint8_t* p = image.at(x, y);
      sum += Eigen::Vector3f(p[0], p[1], p[2]);
      ++n;
    }
  return n > 0 ? Eigen::Vector3f(sum / float(n)) : sum;
}

// Linear RGB 0..1 as the shaders write it (gamma 2.2), 0..255.
Eigen::Vector3f toScreen(const Eigen::Vector3f& linear) {
  return linear.unaryExpr([](float c) { return 255.0f * std::pow(std::clamp(c, 0.0f, 1.0f), 1.0f / 2.2f); });
}

class LookRender : public test::OffscreenRenderTest<kWidth, kHeight> {};

// A plain grey ground plane and a box floating above it.
FrameSnapshot boxOverGround(const Eigen::Vector3f& boxCentre) {
  FrameSnapshot frame;
  DrawShape ground;
  ground.kind = ShapeKind::Plane;
  ground.color = {0.6f, 0.6f, 0.6f};
  frame.shapes.push_back(ground);
  DrawShape box;
  box.kind = ShapeKind::Box;
  box.position = boxCentre;
  box.halfExtents = {0.7f, 0.7f, 0.7f};
  box.color = {0.7f, 0.2f, 0.2f};
  frame.shapes.push_back(box);
  frame.sky.cloudCover = 0;
  return frame;
}

TEST_F(LookRender, TheGroundUnderABoxIsDarkerWithShadowsOn) {
  const Eigen::Vector3f centre(0, 2.5f, 0);
  const FrameSnapshot frame = boxOverGround(centre);
  // Where the box's shadow falls: its centre moved along the sunlight down to y = 0.
  const Eigen::Vector3f sun = environmentFor(frame.sky, 0.0).lightDirection;
  const Eigen::Vector3f shadowCentre = centre - sun * (centre.y() / sun.y());
  // Looking from the side, at right angles to the shadow's offset, so box
  // and shadow are apart on screen.
  Camera& camera = m_renderer->camera();
  const Eigen::Vector3f side = Eigen::Vector3f::UnitY().cross(shadowCentre).normalized();
  camera.target = 0.5f * (shadowCentre + Eigen::Vector3f(0, 1.0f, 0));
  camera.yaw_rad = std::atan2(side.x(), side.z());
  camera.distance_m = 10.0f;
  camera.pitch_rad = 0.8f;
  const Eigen::Vector2i at = toPixel(camera, shadowCentre);
  ASSERT_TRUE(at.x() > 10 && at.x() < kWidth - 10 && at.y() > 10 && at.y() < kHeight - 10) << at.transpose();
  // Not covered by the box itself as the camera sees it.
  const Eigen::Vector2i boxAt = toPixel(camera, centre);
  ASSERT_GT((at - boxAt).norm(), 25.0f) << "the test looks at bare ground";

  m_renderer->settings().shadows = false;
  const Image off = render(frame, "off.png");
  m_renderer->settings().shadows = true;
  const Image on = render(frame, "on.png");
  const float litOff = meanColor(off, at.x(), at.y(), 3).sum();
  const float litOn = meanColor(on, at.x(), at.y(), 3).sum();
  EXPECT_LT(litOn, 0.75f * litOff) << "shadowed ground: " << litOn << " vs lit " << litOff;
  // Ground far from the shadow is the same either way (no acne, no darkening).
  const Eigen::Vector2i open = toPixel(camera, Eigen::Vector3f(2.5f * side.x(), 0.0f, 2.5f * side.z()));
  EXPECT_NEAR(meanColor(on, open.x(), open.y(), 3).sum(), meanColor(off, open.x(), open.y(), 3).sum(), 6.0f);
}

TEST_F(LookRender, TheSkyAtTheHorizonHasTheFogColour) {
  for (float hour : {12.0f, 18.3f}) {
    FrameSnapshot frame;
    frame.sky.timeOfDay_h = hour;
    // A wall 900 m away, deep in fog (250 m: 1 - exp(-13) of fog colour),
    // up to eye height across the lower half of the view; above it the sky.
    DrawShape wall;
    wall.kind = ShapeKind::Box;
    wall.halfExtents = {2000.0f, 400.0f, 5.0f};
    wall.color = {0.1f, 0.5f, 0.1f};
    Camera& camera = m_renderer->camera();
    camera.target = {0, 1, 0};
    camera.pitch_rad = 0.0f;
    camera.distance_m = 10.0f;
    const FrameView view = makeFrameView(camera, float(kWidth) / kHeight);
    // Look away from the sun (its glow is not the horizon's colour).
    const Environment e = environmentFor(frame.sky, 0.0);
    camera.yaw_rad = std::atan2(e.lightDirection.x(), e.lightDirection.z());
    const FrameView away = makeFrameView(camera, float(kWidth) / kHeight);
    (void)view;
    wall.position = away.eye + 900.0f * Eigen::Vector3f(away.forward.x(), 0, away.forward.z()).normalized() -
                    Eigen::Vector3f(0, 399.0f, 0);
    wall.orientation = Eigen::Quaternionf::FromTwoVectors(Eigen::Vector3f::UnitZ(),
                                                          Eigen::Vector3f(away.forward.x(), 0, away.forward.z()));
    frame.shapes.push_back(wall);
    const Image image = render(frame, "horizon" + std::to_string(int(hour)) + ".png");
    const Eigen::Vector3f fog = toScreen(e.horizonColor);
    const Eigen::Vector3f wallColor = meanColor(image, kWidth / 2, kHeight / 2 + 12, 4);
    const Eigen::Vector3f skyAtHorizon = meanColor(image, kWidth / 2, kHeight / 2 - 1, 0);
    EXPECT_LT((wallColor - fog).cwiseAbs().maxCoeff(), 3.0f) << hour << " h: fogged wall " << wallColor.transpose()
                                                               << " fog " << fog.transpose();
    EXPECT_LT((skyAtHorizon - fog).cwiseAbs().maxCoeff(), 3.0f)
        << hour << " h: sky at the horizon " << skyAtHorizon.transpose() << " fog " << fog.transpose();
  }
}

TEST_F(LookRender, TimeOfDayAndWeatherChangeTheSky) {
  Camera& camera = m_renderer->camera();
  camera.pitch_rad = -0.6f;  // looking up at the sky
  FrameSnapshot frame;
  frame.sky.timeOfDay_h = 12.0f;
  frame.sky.cloudCover = 0.35f;
  const Image noon = render(frame, "noon.png");
  frame.sky.timeOfDay_h = 0.5f;
  const Image night = render(frame, "night.png");
  frame.sky.timeOfDay_h = 12.0f;
  frame.sky.weather = Weather::Storm;
  const Image storm = render(frame, "storm.png");
  const float noonMean = meanColor(noon, kWidth / 2, kHeight / 2, 60).sum();
  EXPECT_LT(meanColor(night, kWidth / 2, kHeight / 2, 60).sum(), 0.25f * noonMean);
  const Eigen::Vector3f stormMean = meanColor(storm, kWidth / 2, kHeight / 2, 60);
  EXPECT_LT(stormMean.sum(), 0.8f * noonMean);
  EXPECT_LT(stormMean.maxCoeff() - stormMean.minCoeff(), 20.0f) << "a storm sky is grey: " << stormMean.transpose();
}

TEST_F(LookRender, CloudsMoveWithTheWind) {
  Camera& camera = m_renderer->camera();
  camera.pitch_rad = -0.9f;
  FrameSnapshot frame;
  frame.sky.cloudCover = 0.6f;
  const Image a = render(frame, "clouds0.png");
  frame.simTime_s = 30.0;
  const Image b = render(frame, "clouds30.png");
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  int changed = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) changed += std::abs(int(a.rgb[i]) - int(b.rgb[i])) > 6;
  EXPECT_GT(changed, int(a.rgb.size() / 20)) << "30 s of wind moved the clouds";
  m_renderer->settings().clouds = false;
  frame.simTime_s = 0;
  const Image clear = render(frame, "noclouds0.png");
  frame.simTime_s = 30;
  const Image clear30 = render(frame, "noclouds30.png");
  EXPECT_EQ(clear.rgb, clear30.rgb) << "clouds off: the sky does not change with time";
}

}  // namespace
}  // namespace tumble::render
