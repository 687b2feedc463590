// The camera puts its target at the centre of the screen, keeps the eye at
// the configured distance, and the projection maps the field of view to the
// edges of clip space.
#include <gtest/gtest.h>

#include <cmath>

#include "render/internal/camera_math.h"

namespace tumble::render {
namespace {

Eigen::Vector4f clip(const Eigen::Matrix4f& viewProjection, const Eigen::Vector3f& p) {
  return viewProjection * p.homogeneous();
}

TEST(RenderCameraMath, EyeIsAtDistanceAboveTargetForPositivePitch) {
  Camera camera;
  camera.target = {1, 2, 3};
  camera.distance_m = 10;
  camera.pitch_rad = 0.5f;
  const Eigen::Vector3f eye = eyePosition(camera);
  EXPECT_NEAR((eye - camera.target).norm(), 10.0f, 1e-4f);
  EXPECT_NEAR(eye.y() - camera.target.y(), 10.0f * std::sin(0.5f), 1e-4f);
}

TEST(RenderCameraMath, TargetProjectsToScreenCentre) {
  Camera camera;
  camera.target = {-3, 0.5f, 7};
  camera.yaw_rad = 2.2f;
  const Eigen::Vector4f c = clip(makeFrameView(camera, 16.0f / 9.0f).viewProjection, camera.target);
  ASSERT_GT(c.w(), 0.0f);
  EXPECT_NEAR(c.x() / c.w(), 0.0f, 1e-5f);
  EXPECT_NEAR(c.y() / c.w(), 0.0f, 1e-5f);
  // Between the near and far planes.
  EXPECT_GT(c.z() / c.w(), -1.0f);
  EXPECT_LT(c.z() / c.w(), 1.0f);
}

TEST(RenderCameraMath, HalfFieldOfViewAboveTheAxisLandsOnTheTopEdge) {
  Camera camera;
  camera.pitch_rad = 0.0f;  // horizontal view, so "up" is world +Y
  camera.fovY_rad = 1.0f;
  const FrameView view = makeFrameView(camera, 2.0f);
  const Eigen::Vector3f eye = eyePosition(camera);
  const float d = 5.0f;
  const Eigen::Vector3f top = eye + d * view.forward + d * std::tan(0.5f) * Eigen::Vector3f::UnitY();
  const Eigen::Vector4f c = clip(view.viewProjection, top);
  EXPECT_NEAR(c.y() / c.w(), 1.0f, 1e-4f);
  // With aspect 2, the same angle to the side is only half way to the edge.
  const Eigen::Vector3f side = eye + d * view.forward + d * std::tan(0.5f) * view.right;
  const Eigen::Vector4f s = clip(view.viewProjection, side);
  EXPECT_NEAR(s.x() / s.w(), 0.5f, 1e-4f);
}

TEST(RenderCameraMath, PointBehindTheEyeHasNegativeW) {
  Camera camera;
  const FrameView view = makeFrameView(camera, 1.0f);
  const Eigen::Vector3f behind = view.eye - 3.0f * view.forward;
  EXPECT_LT(clip(view.viewProjection, behind).w(), 0.0f);
}

TEST(RenderCameraMath, BasisIsOrthonormalAndRightHanded) {
  Camera camera;
  camera.yaw_rad = -1.1f;
  camera.pitch_rad = 1.2f;
  const FrameView view = makeFrameView(camera, 1.5f);
  EXPECT_NEAR(view.right.norm(), 1.0f, 1e-5f);
  EXPECT_NEAR(view.up.norm(), 1.0f, 1e-5f);
  EXPECT_NEAR(view.right.dot(view.up), 0.0f, 1e-5f);
  EXPECT_NEAR(view.right.cross(view.up).dot(-view.forward), 1.0f, 1e-5f);
  EXPECT_NEAR(view.right.y(), 0.0f, 1e-5f) << "no roll: right stays horizontal";
}

TEST(RenderCameraMath, ClampKeepsPitchAndDistanceUsable) {
  Camera camera;
  camera.pitch_rad = 3.0f;
  camera.distance_m = -2.0f;
  camera.yaw_rad = 100.0f;
  clampCamera(camera);
  EXPECT_FLOAT_EQ(camera.pitch_rad, kMaxPitch_rad);
  EXPECT_FLOAT_EQ(camera.distance_m, kMinDistance_m);
  EXPECT_LE(std::abs(camera.yaw_rad), 3.1416f);
  EXPECT_NEAR(std::sin(camera.yaw_rad), std::sin(100.0f), 1e-3f);
}

}  // namespace
}  // namespace tumble::render
