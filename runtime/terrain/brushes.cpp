#include "terrain/brushes.h"

#include <algorithm>
#include <cmath>

#include "core/random.h"

namespace tumble::terrain {

void SampleRect::include(const SampleRect& o) {
  if (o.empty()) return;
  if (empty()) {
    *this = o;
    return;
  }
  i0 = std::min(i0, o.i0), j0 = std::min(j0, o.j0);
  i1 = std::max(i1, o.i1), j1 = std::max(j1, o.j1);
}

double brushWeight(double r, double radius, double falloff) {
  if (!(radius > 0) || !(r < radius)) return 0.0;
  const double f = std::clamp(falloff, 0.0, 1.0);
  const double inner = (1.0 - f) * radius;
  if (r <= inner) return 1.0;
  const double t = (radius - r) / (f * radius);  // f > 0 here: r > inner = radius when f = 0 is excluded above
  return t * t * (3.0 - 2.0 * t);
}

namespace {

/// Sample columns/rows whose coordinate lies in [lo, hi] (world m), clipped.
SampleRect samplesInBox(const Terrain& t, double x0, double z0, double x1, double z1) {
  const TerrainDesc& d = t.desc();
  const HeightMap& h = t.heights();
  SampleRect r;
  if (!(x1 >= x0) || !(z1 >= z0)) return r;
  const double fi0 = std::ceil((x0 - d.originX_m) / d.spacing_m), fi1 = std::floor((x1 - d.originX_m) / d.spacing_m);
  const double fj0 = std::ceil((z0 - d.originZ_m) / d.spacing_m), fj1 = std::floor((z1 - d.originZ_m) / d.spacing_m);
  if (fi1 < 0 || fj1 < 0 || fi0 > h.width() - 1 || fj0 > h.height() - 1) return r;
  r.i0 = int(std::max(fi0, 0.0)), r.i1 = int(std::min(fi1, double(h.width() - 1)));
  r.j0 = int(std::max(fj0, 0.0)), r.j1 = int(std::min(fj1, double(h.height() - 1)));
  return r;
}

std::uint16_t toValue(const TerrainDesc& d, double height_m) {
  const double v = std::round((height_m - d.baseHeight_m) / d.heightScale_m);
  return std::uint16_t(std::clamp(v, 0.0, 65535.0));
}

/// Value noise in [-1, 1]: a hash per lattice point of a grid `cell` metres
/// across, blended with smoothstep weights (continuous, no seams).
double valueNoise(std::uint64_t seed, double x, double z, double cell) {
  auto lattice = [seed](long long gx, long long gz) {
    std::uint64_t s = seed ^ (std::uint64_t(gx) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(gz) * 0xC2B2AE3D27D4EB4Full);
    return double(splitmix64(s) >> 11) * 0x1.0p-52 - 1.0;
  };
  const double fx = x / cell, fz = z / cell;
  const double gx = std::floor(fx), gz = std::floor(fz);
  double u = fx - gx, v = fz - gz;
  u = u * u * (3 - 2 * u);
  v = v * v * (3 - 2 * v);
  const long long ix = (long long)gx, iz = (long long)gz;
  const double a = lattice(ix, iz), b = lattice(ix + 1, iz), c = lattice(ix, iz + 1), e = lattice(ix + 1, iz + 1);
  return (a * (1 - u) + b * u) * (1 - v) + (c * (1 - u) + e * u) * v;
}

}  // namespace

SampleRect samplesInRadius(const Terrain& t, double x, double z, double radius) {
  if (!(radius > 0) || !std::isfinite(x) || !std::isfinite(z)) return {};
  return samplesInBox(t, x - radius, z - radius, x + radius, z + radius);
}

SampleRect applyBrush(Terrain& t, const Brush& brush, double x, double z, double dt, BrushScratch& scratch) {
  const SampleRect area = samplesInRadius(t, x, z, brush.radius_m);
  if (area.empty() || !(dt > 0) || !(brush.strength_m_per_s > 0)) return {};
  const TerrainDesc& d = t.desc();
  const HeightMap& map = t.heights();
  // The area and a ring of one sample (Smooth reads neighbours), as read
  // before the dab, so the result does not depend on the visiting order.
  const int ri0 = std::max(area.i0 - 1, 0), rj0 = std::max(area.j0 - 1, 0);
  const int ri1 = std::min(area.i1 + 1, map.width() - 1), rj1 = std::min(area.j1 + 1, map.height() - 1);
  const int rw = ri1 - ri0 + 1;
  scratch.heights_m.resize(std::size_t(rw) * std::size_t(rj1 - rj0 + 1));
  for (int j = rj0; j <= rj1; ++j)
    for (int i = ri0; i <= ri1; ++i)
      scratch.heights_m[std::size_t(j - rj0) * rw + (i - ri0)] = t.toHeight_m(map.at(i, j));
  auto old = [&](int i, int j) {
    i = std::clamp(i, ri0, ri1), j = std::clamp(j, rj0, rj1);
    return scratch.heights_m[std::size_t(j - rj0) * rw + (i - ri0)];
  };
  const double cell = std::max(d.spacing_m, brush.radius_m / 3.0);
  SampleRect changed;
  t.editHeights(area.i0, area.j0, area.i1, area.j1, [&](HeightMap& h) {
    for (int j = area.j0; j <= area.j1; ++j) {
      const double pz = d.originZ_m + j * d.spacing_m;
      for (int i = area.i0; i <= area.i1; ++i) {
        const double px = d.originX_m + i * d.spacing_m;
        const double w = brushWeight(std::hypot(px - x, pz - z), brush.radius_m, brush.falloff);
        if (w <= 0) continue;
        const double step = brush.strength_m_per_s * dt * w;  // m
        const double h0 = old(i, j);
        double h1 = h0;
        switch (brush.kind) {
          case BrushKind::Raise: h1 = h0 + step; break;
          case BrushKind::Lower: h1 = h0 - step; break;
          case BrushKind::Smooth: {
            const double avg = (4 * h0 + 2 * (old(i - 1, j) + old(i + 1, j) + old(i, j - 1) + old(i, j + 1)) +
                                old(i - 1, j - 1) + old(i + 1, j - 1) + old(i - 1, j + 1) + old(i + 1, j + 1)) / 16;
            h1 = h0 + std::clamp(avg - h0, -step, step);
            break;
          }
          case BrushKind::Flatten: h1 = h0 + std::clamp(brush.flattenHeight_m - h0, -step, step); break;
          case BrushKind::Noise: h1 = h0 + step * valueNoise(brush.seed, px, pz, cell); break;
        }
        const std::uint16_t v = toValue(d, h1);
        if (v != h.at(i, j)) {
          h.set(i, j, v);
          changed.include({i, j, i, j});
        }
      }
    }
  });
  return changed;
}

SampleRect applyLine(Terrain& t, bool ridge, double ax, double az, double bx, double bz, double width, double height) {
  const double hw = width / 2;
  if (!(hw > 0) || !(height > 0) || !std::isfinite(ax + az + bx + bz + height)) return {};
  const SampleRect area =
      samplesInBox(t, std::min(ax, bx) - hw, std::min(az, bz) - hw, std::max(ax, bx) + hw, std::max(az, bz) + hw);
  if (area.empty()) return {};
  const TerrainDesc& d = t.desc();
  const double dx = bx - ax, dz = bz - az, len2 = dx * dx + dz * dz;
  const double sign = ridge ? 1.0 : -1.0;
  SampleRect changed;
  t.editHeights(area.i0, area.j0, area.i1, area.j1, [&](HeightMap& h) {
    for (int j = area.j0; j <= area.j1; ++j) {
      const double pz = d.originZ_m + j * d.spacing_m;
      for (int i = area.i0; i <= area.i1; ++i) {
        const double px = d.originX_m + i * d.spacing_m;
        const double s = len2 > 0 ? std::clamp(((px - ax) * dx + (pz - az) * dz) / len2, 0.0, 1.0) : 0.0;
        const double u = std::hypot(px - (ax + s * dx), pz - (az + s * dz)) / hw;
        if (u >= 1) continue;
        const double profile = (1 - u * u) * (1 - u * u);
        const std::uint16_t v = toValue(d, t.toHeight_m(h.at(i, j)) + sign * height * profile);
        if (v != h.at(i, j)) {
          h.set(i, j, v);
          changed.include({i, j, i, j});
        }
      }
    }
  });
  return changed;
}

SampleRect paintSurface(Terrain& t, const SurfaceMaterial& mat, double x, double z, double radius) {
  if (!(radius > 0) || !std::isfinite(x) || !std::isfinite(z)) return {};
  const TerrainDesc& d = t.desc();
  // Block (bi, bj) has its centre at sample coordinates (bi + 0.5, bj + 0.5):
  // the same box test as samples, shifted by half a spacing.
  SampleRect blocks = samplesInBox(t, x - radius - 0.5 * d.spacing_m, z - radius - 0.5 * d.spacing_m,
                                   x + radius - 0.5 * d.spacing_m, z + radius - 0.5 * d.spacing_m);
  blocks.i1 = std::min(blocks.i1, t.blocksX() - 1);
  blocks.j1 = std::min(blocks.j1, t.blocksZ() - 1);
  if (blocks.empty()) return {};
  MaterialMaps& m = t.materials() ? *t.materials() : t.createMaterials();
  const std::uint8_t bytes[kMaterialLayerCount] = {mat.texture, mat.bump, mat.friction, mat.sound, mat.softness};
  SampleRect changed;
  for (int bj = blocks.j0; bj <= blocks.j1; ++bj) {
    const double cz = d.originZ_m + (bj + 0.5) * d.spacing_m;
    for (int bi = blocks.i0; bi <= blocks.i1; ++bi) {
      const double cx = d.originX_m + (bi + 0.5) * d.spacing_m;
      if (std::hypot(cx - x, cz - z) > radius) continue;
      bool any = false;
      for (int l = 0; l < kMaterialLayerCount; ++l) {
        if (m.get(MaterialLayer(l), bi, bj) == bytes[l]) continue;
        m.set(MaterialLayer(l), bi, bj, bytes[l]);
        any = true;
      }
      if (any) changed.include({bi, bj, bi + 1, bj + 1});
    }
  }
  return changed;
}

}  // namespace tumble::terrain
