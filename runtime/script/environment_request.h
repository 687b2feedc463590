#pragma once
// What a scenario asked of the sky with environment.set{...}: time of day,
// sun, fog, clouds, wind and weather. Plain data the app hands the renderer
// each frame (render/sky.h); script never includes render. Seen, not
// simulated: nothing here changes physics.
#include <cstdint>
#include <optional>
#include <string>

#include "core/math.h"

namespace tumble::script {

struct EnvironmentRequest {
  std::optional<double> timeOfDay_h;   ///< 0..24; unset: the lab's fixed afternoon sun
  std::optional<Vec3> sunDirection;    ///< unit, towards the sun; wins over timeOfDay_h
  std::optional<double> fogDistance_m; ///< 63 % hidden at this distance; 0 none; unset: the weather's
  double cloudCover = 0.35;            ///< 0..1
  std::string weather = "clear";       ///< "clear", "cloudy" or "storm"
  Eigen::Vector2d wind_mps{6.0, 2.5};  ///< moves the clouds, world X / Z
  std::uint64_t revision = 0;          ///< bumped by every environment.set
};

}  // namespace tumble::script
