#pragma once
// The minimap's picture of a terrain: a small top-down image of the height
// field (kCells x kCells cells over the whole map), coloured by height
// (green lowland, brown slopes, white tops) and hill-shaded from the
// north-west. Built once per terrain and again whenever the terrain's
// surface changes (TerrainSurface::revision, size or arrays). Plain data;
// app/driving_hud.cpp draws it.
//
// Map frame: image column i grows with world X, row j with world Z, so the
// picture is the terrain seen from above (Y up, right-handed: X right, Z
// down the screen).
#include <cstdint>
#include <vector>

#include "render/renderer.h"

namespace tumble::app {

class MinimapImage {
 public:
  static constexpr int kCells = 96;  ///< per side

  /// Rebuilds the image if the surface differs from the one it was built
  /// from; null or an empty surface: no image. True if it (re)built now.
  bool update(const render::TerrainSurface* surface);
  bool empty() const { return m_colors.empty(); }
  /// Colour of cell (i, j), packed as Dear ImGui's IM_COL32 (a << 24 | b << 16 | g << 8 | r).
  std::uint32_t color(int i, int j) const { return m_colors[std::size_t(j) * kCells + std::size_t(i)]; }
  /// The kCells x kCells picture as RGBA bytes, row j = 0 first (null when empty).
  const std::uint8_t* rgba() const {
    return m_colors.empty() ? nullptr : reinterpret_cast<const std::uint8_t*>(m_colors.data());
  }
  /// World extent the image covers, m.
  float minX_m = 0, minZ_m = 0, maxX_m = 0, maxZ_m = 0;
  /// How many times it was built (the report shows it: once per terrain).
  int builds() const { return m_builds; }

 private:
  std::vector<std::uint32_t> m_colors;
  int m_builds = 0;
  // What it was built from.
  std::uint64_t m_revision = 0;
  const std::uint16_t* m_heights = nullptr;
  int m_samplesX = 0, m_samplesZ = 0;
};

}  // namespace tumble::app
