#pragma once
// Vehicle cameras: chase (a critically damped spring behind the body), hood
// and cockpit (rigidly on the body), and the rule the camera key uses to
// step through the modes. Pure math on plain data; the app calls update()
// once per drawn frame with the followed body's interpolated pose.
//
// Body frame: Y up, front +Z (as the shipped vehicle models, and glTF).
//
// Chase spring. Per axis, the eye x follows the desired point d with
//   x'' = w^2 (d - x) - 2 w x'          (critically damped, rate w = stiffness)
// which never overshoots a step and lags a point moving at constant speed v
// by exactly 2 v / w. For d constant over a frame the solution is exact:
//   e = x - d, x(t) = d + (e0 + (v0 + w e0) t) exp(-w t),
//   v(t) = (v0 - w (v0 + w e0) t) exp(-w t),
// so any frame time is stable (no explicit-Euler blow-up at 10 fps).
#include <optional>
#include <string_view>

#include "core/math.h"
#include "render/renderer.h"

namespace tumble::render {

struct CameraRigSettings {
  Eigen::Vector3f chaseOffset_m{0.0f, 2.2f, -6.5f};  // eye, body frame (behind and above)
  Eigen::Vector3f chaseLookAt_m{0.0f, 1.0f, 2.0f};   // looked-at point, body frame
  float chaseStiffness_per_s = 4.0f;                 // spring rate w, 1/s
  Eigen::Vector3f hoodEye_m{0.0f, 1.25f, 1.0f};      // eye on the bonnet, body frame
  Eigen::Vector3f cockpitEye_m{0.35f, 1.15f, -0.1f}; // driver's eye, body frame
  float lookAhead_m = 20.0f;                         // hood / cockpit: look-at distance along +Z
};

struct BodyPose {
  Eigen::Vector3f position_m{0, 0, 0};
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
};

class CameraRig {
 public:
  CameraRigSettings settings;

  /// Places the camera for `camera.mode` following `pose`; advances the chase
  /// spring by dt_s (>= 0). Orbit leaves the camera alone; Follow moves its
  /// target to the body. The first Chase frame (or after reset) starts at rest
  /// at the desired point.
  void update(const BodyPose& pose, float dt_s, Camera& camera);
  void reset() { m_started = false; }
  const Eigen::Vector3f& chaseEye() const { return m_eye; }
  const Eigen::Vector3f& chaseVelocity() const { return m_velocity; }

 private:
  bool m_started = false;
  Eigen::Vector3f m_eye{0, 0, 0}, m_velocity{0, 0, 0};
};

/// One step of the critically damped spring (exact for a fixed goal).
void springStep(Eigen::Vector3f& x, Eigen::Vector3f& v, const Eigen::Vector3f& goal, float rate_per_s, float dt_s);

/// The mode after `mode` when the camera key is pressed: Orbit -> Follow ->
/// (Chase -> Hood -> Cockpit, only with vehicleModes) -> Orbit.
CameraMode nextCameraMode(CameraMode mode, bool vehicleModes);
const char* cameraModeName(CameraMode mode);
std::optional<CameraMode> cameraModeFromName(std::string_view name);

}  // namespace tumble::render
