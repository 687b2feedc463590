#pragma once
// Rain of a storm (no GL): streaks in a box that follows the eye, each drop
// a fixed point of a world-periodic lattice moving with the rain's velocity,
// so drops neither jump when the camera moves nor depend on the frame rate.
#include <vector>

#include "core/math.h"
#include "render/renderer.h"
#include "render/sky.h"

namespace tumble::render {

struct RainShape {
  float halfWidth_m = 18.0f;    // the box reaches this far from the eye in X and Z
  float below_m = 6.0f;         // and this far below the eye ...
  float above_m = 10.0f;        // ... and above it
  float fallSpeed_mps = 9.0f;   // a 2 mm drop's terminal speed is about 6.5 m/s, a 4 mm one's 8.8 m/s
  float windShare = 0.25f;      // ground wind as a share of SkySettings::wind_mps (given at cloud height)
  float exposure_s = 0.045f;    // streak length = speed x this (what a camera's shutter smears)
  float width_m = 0.014f;
  float clearRadius_m = 1.5f;   // no drops this close to the eye (inside a cockpit, on the lens)
};

/// The rain's velocity (m/s, world) under these settings.
Eigen::Vector3f rainVelocity(const SkySettings& sky, const RainShape& shape = {});

/// Appends up to `drops` streaks (additive) around `eye` at time `time_s`
/// when sky.weather is Storm; nothing otherwise or when drops <= 0.
void appendRain(const SkySettings& sky, double time_s, const Eigen::Vector3f& eye, int drops,
                std::vector<DrawParticle>& out, const RainShape& shape = {});

}  // namespace tumble::render
