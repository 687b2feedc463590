// Lightning: the strike schedule (lightningStrikes) and the bolt's shape
// (lightningBolt), both pure functions of the settings and the time, so the
// picture and the thunder agree and a screenshot is repeatable.
#include <cmath>

#include "render/sky.h"

namespace tumble::render {

namespace {

// A slot of kSlot_s seconds holds at most one strike, at a hashed moment.
// Slots without a strike leave gaps: on average one strike per ~6 s.
constexpr double kSlot_s = 3.0;
constexpr float kBoltHeight_m = 450.0f;
constexpr int kLevels = 6;

std::uint32_t hash(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}
float unit(std::uint32_t h) { return float(h >> 8) * (1.0f / 16777216.0f); }  // 0..1

// Midpoint displacement between a and b: `levels` times every segment is
// halved and its middle moved sideways (perpendicular to the bolt's
// overall direction) by up to `spread` times its length.
void displace(const Eigen::Vector3f& a, const Eigen::Vector3f& b, int levels, float spread, std::uint32_t& state,
              std::vector<Eigen::Vector3f>& out) {
  if (levels == 0) {
    out.push_back(a);
    out.push_back(b);
    return;
  }
  const float length = (b - a).norm();
  state = hash(state + 0x9e3779b9u);
  const float dx = unit(state) - 0.5f;
  state = hash(state + 0x9e3779b9u);
  const float dz = unit(state) - 0.5f;
  const Eigen::Vector3f middle = 0.5f * (a + b) + Eigen::Vector3f(dx, 0.15f * dz, dz) * (spread * length);
  displace(a, middle, levels - 1, spread, state, out);
  displace(middle, b, levels - 1, spread, state, out);
}

}  // namespace

std::vector<LightningStrike> lightningStrikes(const SkySettings& settings, double from_s, double to_s) {
  std::vector<LightningStrike> strikes;
  if (settings.weather != Weather::Storm || !(to_s > from_s)) return strikes;
  const long long first = static_cast<long long>(std::floor(from_s / kSlot_s));
  const long long last = static_cast<long long>(std::floor(to_s / kSlot_s));
  for (long long slot = first; slot <= last; ++slot) {
    const std::uint32_t h = hash(static_cast<std::uint32_t>(slot) * 2654435761u + 17u);
    if (unit(h) < 0.5f) continue;  // no strike in this slot
    LightningStrike s;
    s.time_s = (double(slot) + 0.1 + 0.8 * unit(hash(h + 1))) * kSlot_s;
    if (s.time_s < from_s || s.time_s >= to_s) continue;
    const float angle = 6.2831853f * unit(hash(h + 2));
    const float distance = 150.0f + 500.0f * unit(hash(h + 3));
    s.ground_m = Eigen::Vector3f(settings.stormCentre_m.x() + distance * std::cos(angle), 0.0f,
                                 settings.stormCentre_m.y() + distance * std::sin(angle));
    s.duration_s = 0.25f + 0.2f * unit(hash(h + 4));
    s.seed = hash(h + 5);
    strikes.push_back(s);
  }
  return strikes;
}

std::vector<Eigen::Vector3f> lightningBolt(const LightningStrike& strike) {
  std::vector<Eigen::Vector3f> segments;
  std::uint32_t state = strike.seed;
  const Eigen::Vector3f top = strike.ground_m + Eigen::Vector3f(0.0f, kBoltHeight_m, 0.0f);
  displace(top, strike.ground_m, kLevels, 0.35f, state, segments);
  // One branch: from a third of the way down, off to one side, shorter.
  const Eigen::Vector3f fork = segments[segments.size() / 3];
  state = hash(state + 7u);
  const Eigen::Vector3f end = fork + Eigen::Vector3f(120.0f * (unit(state) - 0.5f), -160.0f, 60.0f * (unit(hash(state)) - 0.5f));
  displace(fork, end, kLevels - 2, 0.3f, state, segments);
  return segments;
}

}  // namespace tumble::render
