#include "render/internal/rain.h"

#include <cmath>
#include <cstdint>

namespace tumble::render {

namespace {

// Integer hash (a 32-bit finaliser, as in MurmurHash3), as 0..1.
float unitHash(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return float(x >> 8) * (1.0f / 16777216.0f);
}

// x moved by whole periods into [lo, lo + period).
float wrapInto(double x, double lo, double period) {
  return float(lo + (x - lo - period * std::floor((x - lo) / period)));
}

}  // namespace

Eigen::Vector3f rainVelocity(const SkySettings& sky, const RainShape& shape) {
  return {shape.windShare * sky.wind_mps.x(), -shape.fallSpeed_mps, shape.windShare * sky.wind_mps.y()};
}

void appendRain(const SkySettings& sky, double time_s, const Eigen::Vector3f& eye, int drops,
                std::vector<DrawParticle>& out, const RainShape& shape) {
  if (sky.weather != Weather::Storm || drops <= 0) return;
  const Eigen::Vector3f v = rainVelocity(sky, shape);
  const double side = 2.0 * shape.halfWidth_m, height = double(shape.below_m) + shape.above_m;
  const Eigen::Vector3f stretch = v * shape.exposure_s;
  out.reserve(out.size() + std::size_t(drops));
  for (int i = 0; i < drops; ++i) {
    const std::uint32_t k = std::uint32_t(i) * 3u;
    // Where the drop is at time 0, then carried by the rain; the lattice
    // repeats every `side` (X, Z) and `height` (Y), so the box around the
    // eye always holds exactly one copy of every drop.
    const double x = unitHash(k) * side + v.x() * time_s;
    const double y = unitHash(k + 1) * height + v.y() * time_s;
    const double z = unitHash(k + 2) * side + v.z() * time_s;
    DrawParticle p;
    p.position = {wrapInto(x, eye.x() - shape.halfWidth_m, side), wrapInto(y, eye.y() - shape.below_m, height),
                  wrapInto(z, eye.z() - shape.halfWidth_m, side)};
    if ((p.position - eye).squaredNorm() < shape.clearRadius_m * shape.clearRadius_m) continue;
    p.size_m = shape.width_m;
    p.stretch_m = stretch;
    p.color = Eigen::Vector4f(0.55f, 0.58f, 0.65f, 0.6f);
    out.push_back(p);
  }
}

}  // namespace tumble::render
