#pragma once
// View and projection matrices for the orbit/follow camera. Pure math, no GL,
// so tests can check where a world point lands on screen.
#include "core/math.h"
#include "render/renderer.h"

namespace tumble::render {

// Depth range of the projection. 5 cm keeps small debris from being clipped
// when the camera is close; 2 km covers the drawn ground plane with margin.
inline constexpr float kNearPlane_m = 0.05f;
inline constexpr float kFarPlane_m = 2000.0f;
// Pitch is kept short of straight up/down, where the look-at basis (Y up)
// degenerates and the view would flip.
inline constexpr float kMaxPitch_rad = 1.50f;
inline constexpr float kMinDistance_m = 0.5f;
inline constexpr float kMaxDistance_m = 500.0f;

/// Chase, Hood and Cockpit: the app places the eye (Camera::eye_m, up).
bool placedByApp(const Camera& camera);
Eigen::Vector3f eyePosition(const Camera& camera);
/// Right-handed look-at, camera looking down its -Z (OpenGL convention).
Eigen::Matrix4f viewMatrix(const Camera& camera);
/// OpenGL clip space (z in -w..w).
Eigen::Matrix4f projectionMatrix(float fovY_rad, float aspect, float near_m, float far_m);

/// Everything the passes need to know about the camera for one frame.
struct FrameView {
  Eigen::Matrix4f viewProjection;
  Eigen::Vector3f eye, right, up, forward;  // forward points from eye to target
  float tanHalfFovX = 1, tanHalfFovY = 1;
};
FrameView makeFrameView(const Camera& camera, float aspect, float far_m = kFarPlane_m);

/// Keeps pitch and distance in their valid ranges after user input.
void clampCamera(Camera& camera);

}  // namespace tumble::render
