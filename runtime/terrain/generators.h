#pragma once
// Height-map generators, deterministic for a seed on every machine: all
// randomness comes from splitmix64 (below) and is turned into numbers with
// our own arithmetic, never through std::*_distribution (whose output is
// implementation-defined). Work is done in double; GCC/Clang in ISO mode do
// not contract to FMA, so the bytes match across x86-64 and AArch64 builds.
#include <cstdint>

#include "core/random.h"
#include "terrain/height_map.h"

namespace tumble::terrain {

/// splitmix64 (core/random.h): the same sequence everywhere.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : m_state(seed) {}
  std::uint64_t next() { return splitmix64(m_state); }
  /// Uniform in [0, 1) with 53 random bits.
  double unit() { return double(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [-1, 1).
  double symmetric() { return 2.0 * unit() - 1.0; }

 private:
  std::uint64_t m_state;
};

struct PlasmaParams {
  std::uint64_t seed = 1;
  /// Amplitude kept per halving of the feature size, in (0, 1]. 0.5 gives
  /// classic "natural" hills; 0.7 is craggy; 0.3 is smooth and rolling.
  double roughness = 0.5;
};

/// Plasma fractal (diamond-square, random midpoint displacement). The field
/// is generated on the smallest (2^n + 1)^2 grid covering width x height and
/// the top-left corner is kept (cropping keeps the feature scale, resampling
/// would stretch it), then normalised to the full range 0..65535.
HeightMap generatePlasma(int width, int height, const PlasmaParams& params);

/// Adds a plasma bump to the rectangle of samples [x0, x0+w) x [z0, z0+h)
/// (clipped to the map). The plasma is normalised to [0, 1], multiplied by
/// sin(pi u) sin(pi v) so it fades to nothing at the rectangle's border (no
/// cliff), then by `amplitude` (16-bit units; negative digs). Results clamp to 0..65535.
void addPlasmaRegion(HeightMap& map, int x0, int z0, int w, int h, double amplitude,
                     const PlasmaParams& params);

/// A ridge (height > 0) or ditch (height < 0) along a midpoint-displaced line.
/// Coordinates and widths are in samples; height in 16-bit units.
struct RidgeParams {
  double fromX = 0, fromZ = 0;     ///< start, in sample coordinates (column, row)
  double toX = 0, toZ = 0;         ///< end, in sample coordinates
  double height = 1000;            ///< crest height added, 16-bit units; negative for a ditch
  double halfWidth = 8;            ///< samples from the crest line to where the profile reaches 0
  double jaggedness = 0.2;         ///< sideways midpoint displacement per segment length, 0 = straight
  std::uint64_t seed = 1;
};

/// The cross-section is (1 - s^2)^2 with s = distance / halfWidth (smooth at
/// the crest and at the foot); crest height varies +-jaggedness along the line.
/// Where segments overlap the larger contribution wins, so bends do not double up.
void addRidge(HeightMap& map, const RidgeParams& params);

}  // namespace tumble::terrain
