#pragma once
// Synthetic height fields for the terrain rendering tests: owned arrays plus
// the TerrainSurface view the renderer reads (what the app fills from
// terrain::Terrain). Heights come from closed forms or a small seeded
// diamond-square, so nothing depends on the terrain module.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "render/renderer.h"

namespace tumble::render::test {

struct TestTerrain {
  int nx = 0, nz = 0;
  std::vector<std::uint16_t> heights;
  std::vector<std::uint8_t> texture, bump;  // per block
  TerrainSurface surface;

  TestTerrain(int samplesX, int samplesZ, float spacing_m = 1.0f)
      : nx(samplesX),
        nz(samplesZ),
        heights(std::size_t(samplesX) * samplesZ, 0),
        texture(std::size_t(samplesX - 1) * (samplesZ - 1), 0),
        bump(std::size_t(samplesX - 1) * (samplesZ - 1), 0) {
    surface.samplesX = nx;
    surface.samplesZ = nz;
    surface.spacing_m = spacing_m;
    surface.heights = heights.data();
    surface.textureIndex = texture.data();
    surface.bump = bump.data();
  }
  TestTerrain(const TestTerrain&) = delete;  // surface points into this object

  void setHeight_m(int i, int j, double y_m) {
    const double v = (y_m - surface.baseHeight_m) / surface.heightScale_m;
    heights[std::size_t(j) * nx + i] = std::uint16_t(std::clamp(std::lround(v), 0l, 65535l));
  }
  double height_m(int i, int j) const {
    return surface.baseHeight_m + heights[std::size_t(j) * nx + i] * double(surface.heightScale_m);
  }
  std::uint8_t& textureAt(int bi, int bj) { return texture[std::size_t(bj) * (nx - 1) + bi]; }
  Eigen::Vector3f centre() const {
    return {surface.originX_m + 0.5f * (nx - 1) * surface.spacing_m, 0,
            surface.originZ_m + 0.5f * (nz - 1) * surface.spacing_m};
  }
};

/// Diamond-square on a (2^k + 1)^2 grid, values 0..1, deterministic for a seed.
inline std::vector<float> plasma(int size, std::uint64_t seed, float roughness = 0.55f) {
  std::vector<float> h(std::size_t(size) * size, 0.0f);
  std::uint64_t state = seed;
  const auto random = [&state]() {  // splitmix64 -> [-1, 1)
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return float(double(z >> 11) * (2.0 / 9007199254740992.0) - 1.0);
  };
  const auto at = [&](int i, int j) -> float& { return h[std::size_t(j) * size + i]; };
  float amplitude = 1.0f;
  for (int step = size - 1; step > 1; step /= 2, amplitude *= roughness) {
    const int half = step / 2;
    for (int j = half; j < size; j += step)
      for (int i = half; i < size; i += step)
        at(i, j) = 0.25f * (at(i - half, j - half) + at(i + half, j - half) + at(i - half, j + half) +
                            at(i + half, j + half)) + amplitude * random();
    for (int j = 0; j < size; j += half) {
      for (int i = (j / half) % 2 == 0 ? half : 0; i < size; i += step) {
        float sum = 0;
        int count = 0;
        if (i >= half) sum += at(i - half, j), ++count;
        if (i + half < size) sum += at(i + half, j), ++count;
        if (j >= half) sum += at(i, j - half), ++count;
        if (j + half < size) sum += at(i, j + half), ++count;
        at(i, j) = sum / float(count) + amplitude * random();
      }
    }
  }
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  const float low = *lo, range = std::max(*hi - *lo, 1e-6f);
  for (float& v : h) v = (v - low) / range;
  return h;
}

/// Fills a square terrain with plasma hills up to `height_m` and paints
/// materials the way a designer might: sand low, grass, dirt, rock on
/// steep slopes, snow on top; bump stronger on rock and gravel.
inline void paintPlasmaLandscape(TestTerrain& t, std::uint64_t seed, float height_m) {
  const std::vector<float> h = plasma(t.nx, seed, 0.5f);
  for (int j = 0; j < t.nz; ++j)
    for (int i = 0; i < t.nx; ++i) t.setHeight_m(i, j, height_m * std::pow(h[std::size_t(j) * t.nx + i], 1.6f));
  for (int bj = 0; bj + 1 < t.nz; ++bj) {
    for (int bi = 0; bi + 1 < t.nx; ++bi) {
      const double y = t.height_m(bi, bj) / height_m;
      const double slope = std::hypot(t.height_m(bi + 1, bj) - t.height_m(bi, bj),
                                      t.height_m(bi, bj + 1) - t.height_m(bi, bj)) / t.surface.spacing_m;
      std::uint8_t tex = 0, b = 70;          // grass
      if (y < 0.04) tex = 2, b = 30;         // sand
      else if (y < 0.07) tex = 3, b = 40;    // mud by the shore
      else if (y > 0.85) tex = 4, b = 20;    // snow
      else if (slope > 0.9) tex = 1, b = 230;  // rock
      else if (slope > 0.6) tex = 5, b = 170;  // gravel
      else if (slope > 0.4) tex = 6, b = 110;  // dirt
      else if (y > 0.55) tex = 7, b = 100;   // moss up high
      t.textureAt(bi, bj) = tex;
      t.bump[std::size_t(bj) * (t.nx - 1) + bi] = b;
    }
  }
}

}  // namespace tumble::render::test
