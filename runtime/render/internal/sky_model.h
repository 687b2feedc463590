#pragma once
// From a scene's SkySettings (time of day, sun, fog, clouds, weather) to the
// colours every pass lights and fogs with (Environment), and the textures
// the sky is drawn from: a cube of the clear sky (horizon gradient, sun
// disc and glow) and a tiling plasma for the clouds. All on the CPU,
// deterministic, tested without GL.
#include <cstdint>
#include <vector>

#include "render/internal/environment.h"
#include "render/sky.h"

namespace tumble::render {

/// Direction towards the sun at a local solar time (hours, wraps at 24):
/// rises in +X at 6:00, highest (65 degrees) towards +Z at 12:00, sets in
/// -X at 18:00, below the horizon at night.
Eigen::Vector3f sunDirectionAt(float timeOfDay_h);

/// The environment for these settings at simulation time simTime_s (which
/// moves the clouds). Default settings (no time of day, no sun) keep the
/// default Environment's sun and sky colours.
Environment environmentFor(const SkySettings& settings, double simTime_s);

/// The clear sky's colour (linear RGB) seen along unit direction `dir`:
/// zenith-to-horizon gradient above, horizon-to-ground below, the sun's
/// glow and disc. At dir.y == 0 it is exactly horizonColor away from the
/// sun, so fog (which fades into horizonColor) meets the sky seamlessly.
Eigen::Vector3f clearSkyColor(const Environment& environment, const Eigen::Vector3f& dir);

/// The six faces of a cube map (GL order +X, -X, +Y, -Y, +Z, -Z), size x
/// size texels each, RGB floats, rows as GL uploads them: clearSkyColor
/// through each texel's centre.
std::vector<float> buildSkyCube(const Environment& environment, int size);

/// A tiling plasma (diamond-square midpoint displacement, values 0..255) of
/// size x size texels (size a power of two), the same for the same seed.
std::vector<std::uint8_t> buildPlasma(int size, std::uint32_t seed);

}  // namespace tumble::render
