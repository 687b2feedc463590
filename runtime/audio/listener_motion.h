#pragma once
// The listener's velocity (OpenAL's AL_VELOCITY on the listener, which the
// Doppler shift uses) from where the listener was put: the app moves the
// listener with the camera once a frame but steps the audio at the fixed
// step, so a step may see the same position as the last one (two steps in
// one frame) or a position that moved over several steps. The velocity is
// the last change of position over the time between the two steps that saw
// the change, held until the next change.
//
//   ListenerMotion motion;
//   Vec3 v = motion.update(cameraEye_m, stepStart_s);  // once per audio step
#include <optional>

#include "core/math.h"

namespace tumble::audio {

class ListenerMotion {
 public:
  /// Faster than this is a jump (a camera cut, a restart), not motion: the
  /// listener then counts as standing still. Nothing the camera follows
  /// moves faster than sound, m/s.
  static constexpr double kJumpSpeed_mps = 343;
  /// The listener at position_m at time_s (non-decreasing); returns its velocity, m/s.
  Vec3 update(const Vec3& position_m, double time_s);
  const Vec3& velocity_mps() const { return m_velocity; }

 private:
  std::optional<Vec3> m_position;
  double m_time_s = 0;
  Vec3 m_velocity = Vec3::Zero();
};

}  // namespace tumble::audio
