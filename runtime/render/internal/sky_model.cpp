#include "render/internal/sky_model.h"

#include <algorithm>
#include <cmath>

namespace tumble::render {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kNoonElevation_rad = 65.0f * kPi / 180.0f;

// Colours of the sky's extremes (linear RGB). Day colours are the default
// Environment's, so a lab scene without a time of day looks as before.
const Eigen::Vector3f kNightZenith{0.004f, 0.006f, 0.018f};
const Eigen::Vector3f kNightHorizon{0.018f, 0.024f, 0.045f};
const Eigen::Vector3f kNightAmbient{0.025f, 0.03f, 0.05f};
const Eigen::Vector3f kSunsetHorizon{0.95f, 0.52f, 0.30f};
const Eigen::Vector3f kSunsetLight{1.0f, 0.55f, 0.28f};
const Eigen::Vector3f kMoonLight{0.10f, 0.12f, 0.18f};
const Eigen::Vector3f kStormSky{0.20f, 0.22f, 0.25f};

// Sun disc: angular radius, with a soft rim (cosines of the angles).
constexpr float kSunDiscCosInner = 0.99985f;  // ~1.0 degree
constexpr float kSunDiscCosOuter = 0.99970f;  // ~1.4 degrees

float smoothstep(float a, float b, float x) {
  const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

Eigen::Vector3f mix(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float t) { return a + t * (b - a); }

float luminance(const Eigen::Vector3f& c) { return 0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z(); }

// Towards grey of the same brightness (overcast light has no colour).
Eigen::Vector3f greyed(const Eigen::Vector3f& c, float amount) {
  return mix(c, Eigen::Vector3f::Constant(luminance(c)), amount);
}

void applyTimeOfDay(const Eigen::Vector3f& sun, Environment& e) {
  const Environment day;  // default (afternoon) colours
  const float y = sun.y();
  const float daylight = smoothstep(-0.12f, 0.2f, y);
  const float low = 1.0f - smoothstep(0.0f, 0.45f, y);  // how much sunset tint
  const float twilight = daylight * low;
  if (y >= 0.0f) {
    e.lightDirection = sun;
    e.lightColor = mix(day.lightColor, kSunsetLight, low) * smoothstep(-0.02f, 0.08f, y);
  } else {  // the moon, opposite the sun
    e.lightDirection = -sun;
    e.lightColor = kMoonLight * smoothstep(0.0f, 0.15f, -y);
  }
  e.zenithColor = mix(kNightZenith, day.zenithColor, daylight);
  e.horizonColor = mix(mix(kNightHorizon, day.horizonColor, daylight), kSunsetHorizon, 0.75f * twilight);
  e.skyAmbient = mix(kNightAmbient, day.skyAmbient, daylight);
  e.groundAmbient = mix(kNightAmbient * 0.5f, day.groundAmbient, daylight);
  e.groundColor = mix(kNightHorizon * 0.5f, day.groundColor, daylight);
}

void applyWeather(Weather weather, Environment& e) {
  const float bright = luminance(e.horizonColor) / luminance(Environment{}.horizonColor);
  switch (weather) {
    case Weather::Clear: break;
    case Weather::Cloudy:
      e.zenithColor = greyed(mix(e.zenithColor, e.horizonColor, 0.5f), 0.6f);
      e.horizonColor = greyed(e.horizonColor, 0.5f);
      e.lightColor *= 0.55f;
      e.sunDisc = 0.35f;
      break;
    case Weather::Storm:
      e.zenithColor = kStormSky * 0.7f * bright;
      e.horizonColor = kStormSky * bright;
      e.groundColor = kStormSky * 0.6f * bright;
      e.lightColor *= 0.22f;
      e.skyAmbient = greyed(e.skyAmbient, 0.7f) * 0.6f;
      e.groundAmbient *= 0.6f;
      e.sunDisc = 0.0f;
      break;
  }
}

}  // namespace

float weatherFogDistance_m(Weather weather) {
  switch (weather) {
    case Weather::Clear: return 250.0f;
    case Weather::Cloudy: return 180.0f;
    case Weather::Storm: return 70.0f;
  }
  return 250.0f;
}

Eigen::Vector3f sunDirectionAt(float timeOfDay_h) {
  float t = std::fmod(timeOfDay_h, 24.0f);
  if (t < 0) t += 24.0f;
  // Hour angle: 0 at 6:00 (east, +X), pi/2 at noon, pi at 18:00 (west, -X).
  const float hour = (t - 6.0f) * kPi / 12.0f;
  const float elevation = kNoonElevation_rad * std::sin(hour);
  // Towards +Z by day, -Z by night (the path continues under the horizon).
  return Eigen::Vector3f(std::cos(hour) * std::cos(elevation), std::sin(elevation),
                         std::sin(hour) * std::cos(elevation))
      .normalized();
}

namespace {

// The sun these settings put in the sky (the lab's fixed sun by default).
Eigen::Vector3f sunOf(const SkySettings& s) {
  if (!s.sunDirection && !s.timeOfDay_h) return Environment{}.lightDirection;
  Eigen::Vector3f sun = s.sunDirection ? *s.sunDirection : sunDirectionAt(*s.timeOfDay_h);
  if (!(sun.norm() > 1e-6f) || !sun.allFinite()) sun = Environment{}.lightDirection;
  return sun.normalized();
}

}  // namespace

Environment environmentFor(const SkySettings& s, double simTime_s) {
  Environment e;
  if (s.sunDirection || s.timeOfDay_h) applyTimeOfDay(sunOf(s), e);
  applyWeather(s.weather, e);
  float cover = std::isfinite(s.cloudCover) ? std::clamp(s.cloudCover, 0.0f, 1.0f) : 0.0f;
  if (s.weather == Weather::Cloudy) cover = std::max(cover, 0.75f);
  if (s.weather == Weather::Storm) cover = 1.0f;
  e.cloudCover = cover;
  const float fog = s.fogDistance_m ? *s.fogDistance_m : weatherFogDistance_m(s.weather);
  e.fogDensity_per_m = (std::isfinite(fog) && fog > 0.0f) ? 1.0f / fog : 0.0f;
  // Offsets wrap at 100 km so float precision lasts for days of play.
  const Eigen::Vector2f wind = s.wind_mps.allFinite() ? s.wind_mps : Eigen::Vector2f::Zero();
  for (int i = 0; i < 2; ++i) e.cloudOffset_m[i] = float(std::fmod(double(wind[i]) * simTime_s, 100000.0));
  // Clouds are lit by the sun; moonlight (light from below the horizon's
  // sun) greys them only faintly.
  const bool moonlit = (s.sunDirection || s.timeOfDay_h) && e.lightDirection.dot(sunOf(s)) < 0.0f;
  e.cloudColor = (e.lightColor * (moonlit ? 0.08f : 0.85f) + 0.6f * e.skyAmbient + 0.1f * e.horizonColor).cwiseMin(1.0f);
  e.cloudShadowColor = mix(e.horizonColor, e.skyAmbient, 0.5f) * (s.weather == Weather::Storm ? 0.6f : 0.9f);
  return e;
}

Eigen::Vector3f clearSkyColor(const Environment& e, const Eigen::Vector3f& dir) {
  Eigen::Vector3f color;
  if (dir.y() >= 0.0f) {
    // A quick rise from the horizon (slope 3 at elevation 0, so the sky right
    // above the horizon stays within a step of 8-bit colour of the fog).
    color = mix(e.horizonColor, e.zenithColor, 1.0f - std::pow(1.0f - dir.y(), 3.0f));
  } else {
    color = mix(e.horizonColor, e.groundColor, std::min(1.0f, -dir.y() * 6.0f));
  }
  const float toSun = std::max(dir.dot(e.lightDirection), 0.0f);
  // Glow (a tight halo and a wide, warm one), then the disc itself.
  float light = 0.25f * std::pow(toSun, 64.0f) + 0.12f * std::pow(toSun, 6.0f) * e.sunDisc;
  light += 1.5f * e.sunDisc * smoothstep(kSunDiscCosOuter, kSunDiscCosInner, toSun);
  if (dir.y() < 0.0f) light *= std::max(0.0f, 1.0f + dir.y() * 12.0f);  // the disc sinks behind the ground
  return color + e.lightColor * light;
}

std::vector<float> buildSkyCube(const Environment& environment, int size) {
  std::vector<float> texels(static_cast<std::size_t>(6) * size * size * 3);
  std::size_t k = 0;
  for (int face = 0; face < 6; ++face) {
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const float s = 2.0f * (float(x) + 0.5f) / float(size) - 1.0f;
        const float t = 2.0f * (float(y) + 0.5f) / float(size) - 1.0f;
        Eigen::Vector3f d;
        switch (face) {  // the GL cube map face conventions
          case 0: d = {1, -t, -s}; break;
          case 1: d = {-1, -t, s}; break;
          case 2: d = {s, 1, t}; break;
          case 3: d = {s, -1, -t}; break;
          case 4: d = {s, -t, 1}; break;
          default: d = {-s, -t, -1}; break;
        }
        const Eigen::Vector3f c = clearSkyColor(environment, d.normalized());
        texels[k++] = c.x();
        texels[k++] = c.y();
        texels[k++] = c.z();
      }
    }
  }
  return texels;
}

std::vector<std::uint8_t> buildPlasma(int size, std::uint32_t seed) {
  // Diamond-square on a torus (indices wrap), so the result tiles.
  std::vector<float> h(static_cast<std::size_t>(size) * size, 0.0f);
  std::uint32_t state = seed * 747796405u + 2891336453u;
  auto random = [&state]() {  // xorshift32, -1..1
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return float(state >> 8) * (2.0f / 16777216.0f) - 1.0f;
  };
  auto at = [&](int x, int y) -> float& { return h[std::size_t((y & (size - 1)) * size + (x & (size - 1)))]; };
  float amplitude = 1.0f;
  for (int step = size; step > 1; step /= 2) {
    const int half = step / 2;
    for (int y = 0; y < size; y += step)
      for (int x = 0; x < size; x += step)
        at(x + half, y + half) = 0.25f * (at(x, y) + at(x + step, y) + at(x, y + step) + at(x + step, y + step)) +
                                 amplitude * random();
    for (int y = 0; y < size; y += half)
      for (int x = (y / half) % 2 == 0 ? half : 0; x < size; x += step)
        at(x, y) = 0.25f * (at(x - half, y) + at(x + half, y) + at(x, y - half) + at(x, y + half)) +
                   amplitude * random();
    amplitude *= 0.55f;
  }
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  const float range = std::max(*hi - *lo, 1e-6f);
  std::vector<std::uint8_t> out(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) out[i] = std::uint8_t(std::lround(255.0f * (h[i] - *lo) / range));
  return out;
}

}  // namespace tumble::render
