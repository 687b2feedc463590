#pragma once
// The designer's free-fly camera: an eye that moves with WASD, turns with
// the mouse while the right button is held, climbs with E / Space and sinks
// with Q / Ctrl; Shift moves faster. Plain data and math (no SDL): the
// designer feeds it the keys held and the mouse motion, and copies the
// result into render::Camera (Chase mode: the app sets eye, target and up).
#include "render/renderer.h"

namespace tumble::app {

/// What the player holds this frame (designer_mode.cpp fills it from SDL events).
struct FlyInput {
  bool forward = false, back = false, left = false, right = false, up = false, down = false;
  bool fast = false;
  float lookDx_px = 0, lookDy_px = 0;  ///< mouse motion with the look button held, pixels
};

struct FlyCamera {
  static constexpr float kSpeed_mps = 20.0f;       ///< walking speed of the eye
  static constexpr float kFastFactor = 4.0f;       ///< Shift
  static constexpr float kLookRadPerPixel = 0.004f;
  static constexpr float kMaxPitch_rad = 1.5f;     ///< just short of straight up / down

  Eigen::Vector3f position_m{0, 30, 60};
  float yaw_rad = 3.14159265f;  ///< 0 looks along +Z; turning left increases it
  float pitch_rad = -0.35f;     ///< positive looks up

  /// Unit view direction.
  Eigen::Vector3f forward() const;
  /// Moves and turns for one frame of `dt_s` seconds.
  void update(const FlyInput& input, float dt_s);
  /// Looks at `point` from where the eye is.
  void lookAt(const Eigen::Vector3f& point);
  /// The renderer's camera for this eye (mode Chase: eye, target, up).
  void apply(render::Camera& camera) const;
};

}  // namespace tumble::app
