#pragma once
// Terrain brushes: local edits of a Terrain's heights and material layers,
// the scenario designer's tools. Each edit touches only the samples (or
// blocks) under it, refits the quad-tree over exactly that rectangle
// (Terrain::editHeights) and returns the rectangle, so undo, the collision
// tree and the renderer's chunks update only what changed.
//
// Brush shape. A dab centred at (x, z) with radius R weighs sample at
// distance r by
//   w(r) = 1                                  for r <= (1 - falloff) R
//   w(r) = smoothstep((R - r) / (falloff R))  for (1 - falloff) R < r < R
//   w(r) = 0                                  for r >= R
// so falloff 0 is a hard-edged disc and falloff 1 a smooth bump. Heights are
// worked in metres and rounded to the nearest 16-bit value (clamped to
// 0..65535: a brush cannot push the ground past the map's height range).
//
// What each kind does in one dab of duration dt (s), with s = strength * dt * w:
//   Raise    h += s
//   Lower    h -= s
//   Smooth   h moves towards the 3 x 3 binomial average of its neighbours
//            (read before the dab) by at most s metres
//   Flatten  h moves towards flattenHeight_m by at most s metres
//   Noise    h += s * n(x, z), n a value noise in [-1, 1] with features
//            about R / 3 across, fixed by the seed (the same dab repeated
//            grows the same bumps)
#include <cstdint>
#include <vector>

#include "terrain/material_map.h"
#include "terrain/terrain.h"

namespace tumble::terrain {

/// Inclusive rectangle of height-map samples [i0, i1] x [j0, j1]; empty when i1 < i0 or j1 < j0.
struct SampleRect {
  int i0 = 0, j0 = 0, i1 = -1, j1 = -1;
  bool empty() const { return i1 < i0 || j1 < j0; }
  /// Grows to cover `o` too (an empty `o` changes nothing).
  void include(const SampleRect& o);
  long long sampleCount() const { return empty() ? 0 : (long long)(i1 - i0 + 1) * (j1 - j0 + 1); }
  bool operator==(const SampleRect&) const = default;
};

enum class BrushKind { Raise, Lower, Smooth, Flatten, Noise };

struct Brush {
  BrushKind kind = BrushKind::Raise;
  double radius_m = 5.0;            ///< where the weight reaches 0, m (> 0)
  double strength_m_per_s = 2.0;    ///< height change rate at full weight, m/s (>= 0)
  double falloff = 0.5;             ///< 0 hard edge .. 1 smooth from the centre
  double flattenHeight_m = 0.0;     ///< Flatten: the world height aimed at, m
  std::uint64_t seed = 1;           ///< Noise: which bumps
};

/// One byte per layer of a material (material_map.h): what a painted block becomes.
struct SurfaceMaterial {
  std::uint8_t texture = 0;   ///< render::TerrainSurface texture index
  std::uint8_t friction = 60; ///< mu * 100
  std::uint8_t bump = 0;      ///< fine shading detail 0..255
  std::uint8_t softness = 40; ///< softness * 100 (rolling drag on soft ground)
  std::uint8_t sound = 0;     ///< SurfaceSound
};

/// Reused work memory of the brushes (no allocation per dab once grown).
struct BrushScratch {
  std::vector<double> heights_m;
};

/// Samples within `radius_m` of (x, z), clipped to the map (empty off the map).
SampleRect samplesInRadius(const Terrain& terrain, double x_m, double z_m, double radius_m);

/// One dab; returns the samples it changed (empty if none). dt_s >= 0.
SampleRect applyBrush(Terrain& terrain, const Brush& brush, double x_m, double z_m, double dt_s,
                      BrushScratch& scratch);

/// A ridge (raise) or ditch along the straight segment from -> to (world x, z
/// in metres): cross-section (1 - u^2)^2, u = distance / (width / 2), with
/// the crest height_m (> 0) above (ridge) or below (ditch) the ground as it
/// was. Where the line's profile is smaller than zero nothing changes.
SampleRect applyLine(Terrain& terrain, bool ridge, double fromX_m, double fromZ_m, double toX_m, double toZ_m,
                     double width_m, double height_m);

/// Blocks whose centres lie within radius_m of (x, z) take `material` in all
/// five layers (material maps are created if the terrain has none). Returns
/// the samples at the corners of the painted blocks (what the renderer
/// redraws); empty if no block was painted.
SampleRect paintSurface(Terrain& terrain, const SurfaceMaterial& material, double x_m, double z_m, double radius_m);

/// Brush weight w(r) described above (exposed for tests and previews).
double brushWeight(double r_m, double radius_m, double falloff);

}  // namespace tumble::terrain
