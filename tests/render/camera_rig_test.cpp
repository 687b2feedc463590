// Vehicle cameras: the chase spring against its analytic behaviour
// (critically damped: no overshoot, lag 2 v / w at constant speed, the same
// path at any frame rate), hood and cockpit fixed to the body, mode cycling.
#include <gtest/gtest.h>

#include <cmath>

#include "render/camera_rig.h"
#include "render/internal/camera_math.h"

namespace tumble::render {
namespace {

TEST(CameraRig, ChaseLagsAConstantSpeedTargetByTwoVOverW) {
  CameraRig rig;
  rig.settings.chaseStiffness_per_s = 3.0f;
  Camera camera;
  camera.mode = CameraMode::Chase;
  const float v = 20.0f, dt = 1.0f / 60.0f;  // m/s along +Z
  BodyPose pose;
  for (int i = 0; i <= 600; ++i) {
    pose.position_m = {0, 0, v * dt * float(i)};
    rig.update(pose, i == 0 ? 0.0f : dt, camera);
  }
  const Eigen::Vector3f goal = pose.position_m + rig.settings.chaseOffset_m;
  const float lag = goal.z() - camera.eye_m.z();
  // 2 v / w for a continuously moving goal; the goal here is the body's pose
  // at the end of each frame, held for the frame, which on average leads the
  // continuous one by half a frame: lag = 2 v / w - v dt / 2 (13.17 m).
  EXPECT_NEAR(lag, 2.0f * v / rig.settings.chaseStiffness_per_s - 0.5f * v * dt, 0.005f);
  EXPECT_NEAR(camera.eye_m.y(), goal.y(), 1e-4f);
  EXPECT_NEAR(rig.chaseVelocity().z(), v, 0.01f);
  // The camera looks at the point ahead of the body.
  EXPECT_LT((camera.target - (pose.position_m + rig.settings.chaseLookAt_m)).norm(), 1e-4f);
}

TEST(CameraRig, ChaseNeverOvershootsAStepAndIsFrameRateIndependent) {
  const float w = 4.0f;
  auto run = [&](float fps, float seconds, std::vector<float>* path) {
    CameraRig rig;
    rig.settings.chaseStiffness_per_s = w;
    Camera camera;
    camera.mode = CameraMode::Chase;
    BodyPose pose;
    rig.update(pose, 0, camera);              // starts at rest at the goal
    pose.position_m = {10, 0, 0};             // the body jumps 10 m
    const int frames = int(std::lround(fps * seconds));
    for (int i = 0; i < frames; ++i) {
      rig.update(pose, 1.0f / fps, camera);
      if (path) path->push_back(camera.eye_m.x());
    }
    return camera.eye_m.x();
  };
  std::vector<float> path;
  const float at1s = run(60, 1.0f, &path);
  for (std::size_t i = 1; i < path.size(); ++i) {
    EXPECT_GE(path[i], path[i - 1]) << "frame " << i;  // monotonic approach
    EXPECT_LE(path[i], 10.0f) << "frame " << i;         // never past the goal
  }
  // Analytic: remaining error (1 + w t) exp(-w t) of the step.
  const float expected = 10.0f * (1.0f - (1.0f + w) * std::exp(-w));
  EXPECT_NEAR(at1s, expected, 1e-3f);
  EXPECT_NEAR(run(10, 1.0f, nullptr), expected, 1e-3f);
  EXPECT_NEAR(run(240, 1.0f, nullptr), expected, 1e-3f);
  // A 2 s stall in one frame does not fling the camera past the goal.
  const float stalled = run(0.5f, 2.0f, nullptr);
  EXPECT_LE(stalled, 10.0f);
  EXPECT_GT(stalled, 9.9f);
}

TEST(CameraRig, HoodAndCockpitAreFixedToTheBody) {
  CameraRig rig;
  Camera camera;
  BodyPose pose;
  pose.position_m = {3, 1, -2};
  // Turned 90 degrees left (about +Y) and rolled 0.2 rad.
  pose.orientation = Eigen::Quaternionf(Eigen::AngleAxisf(float(kPi) / 2, Eigen::Vector3f::UnitY())) *
                     Eigen::Quaternionf(Eigen::AngleAxisf(0.2f, Eigen::Vector3f::UnitZ()));
  for (CameraMode mode : {CameraMode::Hood, CameraMode::Cockpit}) {
    camera.mode = mode;
    rig.update(pose, 0.5f, camera);
    const Eigen::Vector3f local = mode == CameraMode::Hood ? rig.settings.hoodEye_m : rig.settings.cockpitEye_m;
    EXPECT_LT((camera.eye_m - (pose.position_m + pose.orientation * local)).norm(), 1e-5f);
    const FrameView view = makeFrameView(camera, 1.5f);
    // Looking along the body's front (+Z turned to +X) ...
    EXPECT_LT((view.forward - pose.orientation * Eigen::Vector3f::UnitZ()).norm(), 1e-4f);
    // ... with the body's up: the view rolls with the car.
    EXPECT_LT((view.up - pose.orientation * Eigen::Vector3f::UnitY()).norm(), 1e-4f);
    EXPECT_LT((view.eye - camera.eye_m).norm(), 1e-5f);
  }
  // The chase camera keeps the horizon level.
  camera.mode = CameraMode::Chase;
  rig.update(pose, 0.0f, camera);
  EXPECT_NEAR(makeFrameView(camera, 1.5f).right.y(), 0.0f, 1e-5f);
}

TEST(CameraRig, CameraKeyCyclesModes) {
  EXPECT_EQ(nextCameraMode(CameraMode::Orbit, false), CameraMode::Follow);
  EXPECT_EQ(nextCameraMode(CameraMode::Follow, false), CameraMode::Orbit);
  CameraMode m = CameraMode::Orbit;
  std::vector<std::string> seen;
  for (int i = 0; i < 5; ++i) {
    m = nextCameraMode(m, true);
    seen.push_back(cameraModeName(m));
  }
  EXPECT_EQ(seen, (std::vector<std::string>{"follow", "chase", "hood", "cockpit", "orbit"}));
  EXPECT_EQ(cameraModeFromName("hood"), CameraMode::Hood);
  EXPECT_FALSE(cameraModeFromName("helicopter").has_value());
}

}  // namespace
}  // namespace tumble::render
