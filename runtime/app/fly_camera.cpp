#include "app/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace tumble::app {

Eigen::Vector3f FlyCamera::forward() const {
  const float c = std::cos(pitch_rad);
  return {c * std::sin(yaw_rad), std::sin(pitch_rad), c * std::cos(yaw_rad)};
}

void FlyCamera::update(const FlyInput& in, float dt_s) {
  yaw_rad -= kLookRadPerPixel * in.lookDx_px;
  yaw_rad = std::remainder(yaw_rad, 2.0f * 3.14159265f);
  pitch_rad = std::clamp(pitch_rad - kLookRadPerPixel * in.lookDy_px, -kMaxPitch_rad, kMaxPitch_rad);
  // Moves in the horizontal plane (looking down does not dive), up / down along Y.
  const Eigen::Vector3f ahead(std::sin(yaw_rad), 0, std::cos(yaw_rad));
  const Eigen::Vector3f rightward(-std::cos(yaw_rad), 0, std::sin(yaw_rad));
  Eigen::Vector3f move = Eigen::Vector3f::Zero();
  if (in.forward) move += ahead;
  if (in.back) move -= ahead;
  if (in.right) move += rightward;
  if (in.left) move -= rightward;
  if (in.up) move += Eigen::Vector3f::UnitY();
  if (in.down) move -= Eigen::Vector3f::UnitY();
  if (move.squaredNorm() > 0) move.normalize();
  position_m += move * (kSpeed_mps * (in.fast ? kFastFactor : 1.0f) * dt_s);
}

void FlyCamera::lookAt(const Eigen::Vector3f& point) {
  const Eigen::Vector3f d = point - position_m;
  if (d.squaredNorm() < 1e-8f) return;
  yaw_rad = std::atan2(d.x(), d.z());
  pitch_rad = std::clamp(std::atan2(d.y(), std::hypot(d.x(), d.z())), -kMaxPitch_rad, kMaxPitch_rad);
}

void FlyCamera::apply(render::Camera& camera) const {
  camera.mode = render::CameraMode::Chase;
  camera.vehicleModes = false;
  camera.eye_m = position_m;
  camera.target = position_m + forward();
  camera.up = Eigen::Vector3f::UnitY();
}

}  // namespace tumble::app
