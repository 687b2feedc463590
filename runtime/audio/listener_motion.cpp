#include "audio/listener_motion.h"

namespace tumble::audio {

Vec3 ListenerMotion::update(const Vec3& position_m, double time_s) {
  if (!position_m.allFinite()) return m_velocity;
  if (!m_position) {
    m_position = position_m;
    m_time_s = time_s;
    return m_velocity;
  }
  if (position_m == *m_position) return m_velocity;  // not moved since the last step (no new frame)
  const double elapsed_s = time_s - m_time_s;
  const Vec3 v = elapsed_s > 0 ? Vec3((position_m - *m_position) / Real(elapsed_s)) : Vec3::Zero();
  m_velocity = v.allFinite() && v.norm() < kJumpSpeed_mps ? v : Vec3::Zero();
  m_position = position_m;
  m_time_s = time_s;
  return m_velocity;
}

}  // namespace tumble::audio
