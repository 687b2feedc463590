#include "particles/emitter_def.h"

#include <algorithm>
#include <cmath>

namespace tumble::particles {

namespace {

template <typename Key, typename V>
V evalKeys(const std::vector<Key>& keys, float t, V fallback) {
  if (keys.empty()) return fallback;
  if (t <= keys.front().t) return keys.front().value;
  if (t >= keys.back().t) return keys.back().value;
  // Few keys (a handful): a linear scan beats a binary search.
  std::size_t i = 1;
  while (keys[i].t < t) ++i;
  const Key& a = keys[i - 1];
  const Key& b = keys[i];
  float span = b.t - a.t;
  float f = span > 0 ? (t - a.t) / span : 1.0f;
  return V(a.value + (b.value - a.value) * f);
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

template <typename Curve>
Status validateCurve(const Curve& c, const char* field, float lo, float hi, const char* what) {
  if (c.keys.empty()) return makeError(std::string("field '") + field + "': needs at least one key {t, value}");
  for (std::size_t i = 0; i < c.keys.size(); ++i) {
    const auto& k = c.keys[i];
    if (!(k.t >= 0 && k.t <= 1))
      return makeError(std::string("field '") + field + "': key " + std::to_string(i + 1) + " has t = " + num(k.t) +
                       "; t is normalised life, 0..1");
    if (i > 0 && k.t < c.keys[i - 1].t)
      return makeError(std::string("field '") + field + "': keys must be sorted by t (key " + std::to_string(i + 1) +
                       " has t = " + num(k.t) + " after t = " + num(c.keys[i - 1].t) + ")");
    Eigen::ArrayXf v = Eigen::Map<const Eigen::ArrayXf>(reinterpret_cast<const float*>(&k.value),
                                                        sizeof(k.value) / sizeof(float));
    if (!v.allFinite() || v.minCoeff() < lo || v.maxCoeff() > hi)
      return makeError(std::string("field '") + field + "': key " + std::to_string(i + 1) + " is out of range; " +
                       what);
  }
  return Ok{};
}

}  // namespace

float Curve1::eval(float t) const { return evalKeys(keys, t, 0.0f); }

Eigen::Vector3f Curve3::eval(float t) const { return evalKeys(keys, t, Eigen::Vector3f(1, 1, 1)); }

Status validate(const EmitterDef& d) {
  auto finite = [](float v) { return std::isfinite(v); };
  if (!finite(d.rate_per_s) || d.rate_per_s < 0 || d.rate_per_s > 1e6f)
    return makeError("field 'rate': " + num(d.rate_per_s) + " is not valid; expected particles per second, 0..1e6");
  for (std::size_t i = 0; i < d.bursts.size(); ++i) {
    const Burst& b = d.bursts[i];
    if (!finite(b.time_s) || b.time_s < 0 || b.count < 0 || b.count > kMaxParticlesPerEmitter)
      return makeError("field 'bursts': entry " + std::to_string(i + 1) +
                       " is not valid; expected {time = seconds >= 0, count = 0.." +
                       std::to_string(kMaxParticlesPerEmitter) + "}");
  }
  if (!finite(d.duration_s) || d.duration_s < 0)
    return makeError("field 'duration': " + num(d.duration_s) + "; expected seconds >= 0 (0: until stopped)");
  if (!finite(d.lifetimeMin_s) || !finite(d.lifetimeMax_s) || d.lifetimeMin_s <= 0 ||
      d.lifetimeMin_s > d.lifetimeMax_s)
    return makeError("field 'lifetime': {" + num(d.lifetimeMin_s) + ", " + num(d.lifetimeMax_s) +
                     "} is not valid; expected seconds, a number > 0 or {min, max} with 0 < min <= max");
  if (d.maxCount < 1 || d.maxCount > kMaxParticlesPerEmitter)
    return makeError("field 'max_count': " + std::to_string(d.maxCount) + "; expected 1.." +
                     std::to_string(kMaxParticlesPerEmitter));
  if (!d.boxSize_m.allFinite() || d.boxSize_m.minCoeff() < 0)
    return makeError("field 'box_size': expected {x, y, z} metres, each >= 0");
  if (!finite(d.radius_m) || d.radius_m < 0) return makeError("field 'radius': " + num(d.radius_m) + "; expected metres >= 0");
  if (!finite(d.coneAngle_rad) || d.coneAngle_rad < 0 || d.coneAngle_rad > 1.5708f)
    return makeError("field 'cone_angle': " + num(d.coneAngle_rad) + "; expected radians 0..pi/2 (math.rad(30) is 30 degrees)");
  if (!d.direction.allFinite() || d.direction.norm() < 1e-6f)
    return makeError("field 'direction': expected a non-zero vector {x, y, z}");
  if (!finite(d.spread_rad) || d.spread_rad < 0 || d.spread_rad > 3.1416f)
    return makeError("field 'spread': " + num(d.spread_rad) + "; expected radians 0..pi (math.rad(15) is 15 degrees)");
  if (!finite(d.speedMin_mps) || !finite(d.speedMax_mps) || d.speedMin_mps < 0 || d.speedMin_mps > d.speedMax_mps)
    return makeError("field 'speed': {" + num(d.speedMin_mps) + ", " + num(d.speedMax_mps) +
                     "} is not valid; expected m/s, a number >= 0 or {min, max} with 0 <= min <= max");
  if (!finite(d.inheritVelocity) || d.inheritVelocity < 0 || d.inheritVelocity > 1)
    return makeError("field 'inherit_velocity': " + num(d.inheritVelocity) + "; expected a share 0..1");
  if (!finite(d.gravityScale) || std::abs(d.gravityScale) > 100)
    return makeError("field 'gravity': " + num(d.gravityScale) + "; expected a multiple of the world's gravity, -100..100");
  if (!d.acceleration_mps2.allFinite()) return makeError("field 'acceleration': expected {x, y, z} m/s^2, finite");
  if (!finite(d.drag_per_s) || d.drag_per_s < 0)
    return makeError("field 'drag': " + num(d.drag_per_s) + "; expected 1/s >= 0");
  if (!finite(d.spinMin_radps) || !finite(d.spinMax_radps) || d.spinMin_radps > d.spinMax_radps)
    return makeError("field 'spin': {" + num(d.spinMin_radps) + ", " + num(d.spinMax_radps) +
                     "} is not valid; expected rad/s, a number or {min, max} with min <= max");
  if (!finite(d.stretch_s) || d.stretch_s < 0 || d.stretch_s > 10)
    return makeError("field 'stretch': " + num(d.stretch_s) + "; expected seconds 0..10 (streak length = speed x stretch)");
  if (auto s = validateCurve(d.size_m, "size", 0, 1e4f, "sizes are metres >= 0"); !s) return s;
  if (auto s = validateCurve(d.color, "color", 0, 64, "colour channels are linear 0..1 (up to 64 for glowing additive particles)"); !s) return s;
  if (auto s = validateCurve(d.alpha, "alpha", 0, 1, "alpha is 0..1"); !s) return s;
  return Ok{};
}

}  // namespace tumble::particles
