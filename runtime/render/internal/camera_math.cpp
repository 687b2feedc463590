#include "render/internal/camera_math.h"

#include <algorithm>
#include <cmath>

namespace tumble::render {

bool placedByApp(const Camera& camera) {
  return camera.mode == CameraMode::Chase || camera.mode == CameraMode::Hood || camera.mode == CameraMode::Cockpit;
}

Eigen::Vector3f eyePosition(const Camera& camera) {
  if (placedByApp(camera) && camera.eye_m.allFinite() && (camera.eye_m - camera.target).norm() > 1e-4f) {
    return camera.eye_m;
  }
  const float cp = std::cos(camera.pitch_rad);
  const Eigen::Vector3f offset(cp * std::sin(camera.yaw_rad), std::sin(camera.pitch_rad),
                               cp * std::cos(camera.yaw_rad));
  return camera.target + camera.distance_m * offset;
}

Eigen::Matrix4f viewMatrix(const Camera& camera) {
  const Eigen::Vector3f eye = eyePosition(camera);
  const Eigen::Vector3f forward = (camera.target - eye).normalized();
  // The app's up for body-fixed views; world Y otherwise, or when the given
  // up is (nearly) along the view direction.
  Eigen::Vector3f upHint = Eigen::Vector3f::UnitY();
  if (placedByApp(camera) && camera.up.allFinite() && forward.cross(camera.up).norm() > 1e-3f * camera.up.norm()) {
    upHint = camera.up;
  }
  const Eigen::Vector3f right = forward.cross(upHint).normalized();
  const Eigen::Vector3f up = right.cross(forward);
  Eigen::Matrix4f view = Eigen::Matrix4f::Identity();
  view.block<1, 3>(0, 0) = right.transpose();
  view.block<1, 3>(1, 0) = up.transpose();
  view.block<1, 3>(2, 0) = -forward.transpose();
  view(0, 3) = -right.dot(eye);
  view(1, 3) = -up.dot(eye);
  view(2, 3) = forward.dot(eye);
  return view;
}

Eigen::Matrix4f projectionMatrix(float fovY_rad, float aspect, float near_m, float far_m) {
  const float f = 1.0f / std::tan(0.5f * fovY_rad);
  Eigen::Matrix4f proj = Eigen::Matrix4f::Zero();
  proj(0, 0) = f / aspect;
  proj(1, 1) = f;
  proj(2, 2) = (far_m + near_m) / (near_m - far_m);
  proj(2, 3) = 2.0f * far_m * near_m / (near_m - far_m);
  proj(3, 2) = -1.0f;
  return proj;
}

FrameView makeFrameView(const Camera& camera, float aspect, float far_m) {
  FrameView view;
  const Eigen::Matrix4f viewMat = viewMatrix(camera);
  view.viewProjection =
      projectionMatrix(camera.fovY_rad, aspect, kNearPlane_m, far_m) * viewMat;
  view.eye = eyePosition(camera);
  view.right = viewMat.block<1, 3>(0, 0).transpose();
  view.up = viewMat.block<1, 3>(1, 0).transpose();
  view.forward = -viewMat.block<1, 3>(2, 0).transpose();
  view.tanHalfFovY = std::tan(0.5f * camera.fovY_rad);
  view.tanHalfFovX = view.tanHalfFovY * aspect;
  return view;
}

void clampCamera(Camera& camera) {
  camera.pitch_rad = std::clamp(camera.pitch_rad, -kMaxPitch_rad, kMaxPitch_rad);
  camera.distance_m = std::clamp(camera.distance_m, kMinDistance_m, kMaxDistance_m);
  // Keep yaw small so float precision does not erode after long sessions of
  // orbiting in one direction.
  camera.yaw_rad = std::remainder(camera.yaw_rad, 2.0f * static_cast<float>(kPi));
  camera.fovY_rad = std::clamp(camera.fovY_rad, 0.1f, 3.0f);
}

}  // namespace tumble::render
