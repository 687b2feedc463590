#include "app/minimap.h"

#include <algorithm>
#include <cmath>

namespace tumble::app {

namespace {

struct Rgb {
  float r, g, b;
};

Rgb mix(Rgb a, Rgb b, float t) { return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t}; }

// Height ramp: t = 0 lowest .. 1 highest point of the map.
Rgb ramp(float t) {
  const Rgb low{0.24f, 0.47f, 0.20f}, mid{0.55f, 0.50f, 0.32f}, high{0.93f, 0.93f, 0.93f};
  return t < 0.6f ? mix(low, mid, t / 0.6f) : mix(mid, high, (t - 0.6f) / 0.4f);
}

}  // namespace

bool MinimapImage::update(const render::TerrainSurface* s) {
  if (!s || s->samplesX < 2 || s->samplesZ < 2 || !s->heights) {
    const bool had = !m_colors.empty();
    m_colors.clear();
    m_heights = nullptr;
    return had;
  }
  if (!m_colors.empty() && s->revision == m_revision && s->heights == m_heights && s->samplesX == m_samplesX &&
      s->samplesZ == m_samplesZ)
    return false;
  m_revision = s->revision;
  m_heights = s->heights;
  m_samplesX = s->samplesX;
  m_samplesZ = s->samplesZ;
  minX_m = s->originX_m;
  minZ_m = s->originZ_m;
  maxX_m = s->originX_m + float(s->samplesX - 1) * s->spacing_m;
  maxZ_m = s->originZ_m + float(s->samplesZ - 1) * s->spacing_m;
  auto height = [&](int i, int j) {
    i = std::clamp(i, 0, s->samplesX - 1);
    j = std::clamp(j, 0, s->samplesZ - 1);
    return s->baseHeight_m + float(s->heights[std::size_t(j) * std::size_t(s->samplesX) + std::size_t(i)]) * s->heightScale_m;
  };
  // One sample per cell (the nearest to its centre) and the samples one
  // cell away for the slope.
  const float stepX = float(s->samplesX - 1) / kCells, stepZ = float(s->samplesZ - 1) / kCells;
  std::vector<float> h(std::size_t(kCells) * kCells);
  float lo = 1e30f, hi = -1e30f;
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      const float v = height(int(std::lround((float(i) + 0.5f) * stepX)), int(std::lround((float(j) + 0.5f) * stepZ)));
      h[std::size_t(j) * kCells + std::size_t(i)] = v;
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
  const float cellX_m = (maxX_m - minX_m) / kCells, cellZ_m = (maxZ_m - minZ_m) / kCells;
  const float range = std::max(hi - lo, 1e-3f);
  // Light from the north-west (-X, -Z: the map's top left) and above.
  const float lx = -1, ly = 1.5f, lz = -1, ll = std::sqrt(lx * lx + ly * ly + lz * lz);
  m_colors.assign(std::size_t(kCells) * kCells, 0);
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      auto at = [&](int x, int z) {
        return h[std::size_t(std::clamp(z, 0, kCells - 1)) * kCells + std::size_t(std::clamp(x, 0, kCells - 1))];
      };
      const float dhdx = (at(i + 1, j) - at(i - 1, j)) / (2 * cellX_m);
      const float dhdz = (at(i, j + 1) - at(i, j - 1)) / (2 * cellZ_m);
      const float nl = std::sqrt(dhdx * dhdx + 1 + dhdz * dhdz);
      const float lambert = (-dhdx * lx + ly - dhdz * lz) / (nl * ll);
      const float shade = 0.45f + 0.55f * std::clamp(lambert, 0.0f, 1.0f);
      const Rgb c = ramp((at(i, j) - lo) / range);
      auto byte = [&](float v) { return std::uint32_t(std::clamp(v * shade, 0.0f, 1.0f) * 255.0f + 0.5f); };
      m_colors[std::size_t(j) * kCells + std::size_t(i)] = 0xFF000000u | byte(c.b) << 16 | byte(c.g) << 8 | byte(c.r);
    }
  ++m_builds;
  return true;
}

}  // namespace tumble::app
