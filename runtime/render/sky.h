#pragma once
// The scene's sky, sun, fog and weather as plain data: what a scenario asks
// for with environment.set{...} (the app copies it into
// FrameSnapshot::sky). The renderer turns it into sun and sky colours each
// frame (internal/sky_model.h); nothing here is GL.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/math.h"

namespace tumble::render {

enum class Weather {
  Clear,   // the sky's own colours, the clouds as asked
  Cloudy,  // at least 75 % cloud cover, greyer sky, weaker sun
  Storm,   // full dark cover, dim sun, dense fog, lightning flashes
};

struct SkySettings {
  // Local solar time, hours 0..24. The sun rises at 6:00 in +X, stands
  // highest (65 degrees) towards +Z at 12:00 and sets at 18:00 in -X; at
  // night a dim moon lights from the opposite side. Unset (and no
  // sunDirection): the fixed afternoon sun of a lab scene.
  std::optional<float> timeOfDay_h;
  // Unit vector towards the sun (world, Y up); wins over timeOfDay_h.
  std::optional<Eigen::Vector3f> sunDirection;
  // Fog distance: at this distance fog hides 63 % of a colour. Unset: the
  // weather's own (clear 250 m, cloudy 180 m, storm 70 m). 0: no fog.
  std::optional<float> fogDistance_m;
  // Fraction of the sky covered by the two cloud layers, 0..1 (0: the lab's
  // clear sky; scenarios get 0.35 unless they set clouds).
  float cloudCover = 0.0f;
  Weather weather = Weather::Clear;
  // Horizontal wind that moves the cloud layers (the upper layer at half of
  // it, the lower at full), m/s in world X / Z at cloud height.
  Eigen::Vector2f wind_mps{6.0f, 2.5f};
  // Storm: lightning strikes the ground within 150..650 m of this point
  // (world X / Z, m).
  Eigen::Vector2f stormCentre_m{0.0f, 0.0f};
};

/// The fog distance a weather has when a scenario sets none, m (the values
/// listed at SkySettings::fogDistance_m).
float weatherFogDistance_m(Weather weather);

/// One lightning strike of a storm: when and where it hits the ground.
struct LightningStrike {
  double time_s = 0;                  // simulation time of the first flash
  Eigen::Vector3f ground_m{0, 0, 0};  // where the bolt ends (y = 0; the renderer draws it to the terrain or below the horizon)
  float duration_s = 0.35f;           // flicker time; the sky flash follows it
  std::uint32_t seed = 0;             // the bolt's shape (midpoint displacement)
};

/// Strikes beginning in [from_s, to_s) under these settings: none unless
/// weather is Storm. A fixed schedule (a strike every 3..9 s, drawn from a
/// hash of the time slot), the same in every run and frame rate, so the
/// app can start thunder (sound) for exactly the flashes the renderer draws.
std::vector<LightningStrike> lightningStrikes(const SkySettings& settings, double from_s, double to_s);

/// The bolt of a strike: a polyline from 450 m above the ground point down
/// to it, its segments halved and displaced sideways 6 times (midpoint
/// displacement, displacement halving each level), plus one branch.
/// Points are pairs (segment ends, world m).
std::vector<Eigen::Vector3f> lightningBolt(const LightningStrike& strike);

}  // namespace tumble::render
