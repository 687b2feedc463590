#include "render/camera_rig.h"

#include <cmath>

namespace tumble::render {

void springStep(Eigen::Vector3f& x, Eigen::Vector3f& v, const Eigen::Vector3f& goal, float rate_per_s, float dt_s) {
  const float w = rate_per_s, t = std::max(dt_s, 0.0f);
  const Eigen::Vector3f e0 = x - goal;
  const Eigen::Vector3f c = v + w * e0;
  const float decay = std::exp(-w * t);
  x = goal + (e0 + c * t) * decay;
  v = (v - w * c * t) * decay;
}

void CameraRig::update(const BodyPose& pose, float dt_s, Camera& camera) {
  const Eigen::Quaternionf q = pose.orientation.normalized();
  auto toWorld = [&](const Eigen::Vector3f& local) { Eigen::Vector3f w = pose.position_m + q * local; return w; };
  switch (camera.mode) {
    case CameraMode::Orbit: m_started = false; return;
    case CameraMode::Follow:
      m_started = false;
      camera.target = pose.position_m;
      return;
    case CameraMode::Chase: {
      const Eigen::Vector3f goal = toWorld(settings.chaseOffset_m);
      if (!m_started || !m_eye.allFinite() || !m_velocity.allFinite()) {
        m_eye = goal;
        m_velocity.setZero();
        m_started = true;
      } else {
        springStep(m_eye, m_velocity, goal, settings.chaseStiffness_per_s, dt_s);
      }
      camera.eye_m = m_eye;
      camera.target = toWorld(settings.chaseLookAt_m);
      camera.up = Eigen::Vector3f::UnitY();  // the horizon stays level when the car rolls
      return;
    }
    case CameraMode::Hood:
    case CameraMode::Cockpit: {
      m_started = false;
      const Eigen::Vector3f eye = camera.mode == CameraMode::Hood ? settings.hoodEye_m : settings.cockpitEye_m;
      camera.eye_m = toWorld(eye);
      camera.target = toWorld(eye + Eigen::Vector3f(0, 0, settings.lookAhead_m));
      camera.up = q * Eigen::Vector3f::UnitY();  // fixed to the body: rolls and pitches with it
      return;
    }
  }
}

CameraMode nextCameraMode(CameraMode mode, bool vehicleModes) {
  switch (mode) {
    case CameraMode::Orbit: return CameraMode::Follow;
    case CameraMode::Follow: return vehicleModes ? CameraMode::Chase : CameraMode::Orbit;
    case CameraMode::Chase: return CameraMode::Hood;
    case CameraMode::Hood: return CameraMode::Cockpit;
    case CameraMode::Cockpit: return CameraMode::Orbit;
  }
  return CameraMode::Orbit;
}

const char* cameraModeName(CameraMode mode) {
  switch (mode) {
    case CameraMode::Orbit: return "orbit";
    case CameraMode::Follow: return "follow";
    case CameraMode::Chase: return "chase";
    case CameraMode::Hood: return "hood";
    case CameraMode::Cockpit: return "cockpit";
  }
  return "orbit";
}

std::optional<CameraMode> cameraModeFromName(std::string_view name) {
  for (CameraMode m : {CameraMode::Orbit, CameraMode::Follow, CameraMode::Chase, CameraMode::Hood, CameraMode::Cockpit}) {
    if (name == cameraModeName(m)) return m;
  }
  return std::nullopt;
}

}  // namespace tumble::render
