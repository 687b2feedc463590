#include "terrain/generators.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace tumble::terrain {

namespace {

// Diamond-square on an n x n grid (n = 2^k + 1). Random numbers are drawn in
// a fixed loop order, which is what makes the result a function of the seed.
std::vector<double> diamondSquare(int n, const PlasmaParams& params) {
  std::vector<double> f(std::size_t(n) * std::size_t(n), 0.0);
  auto at = [&](int i, int j) -> double& { return f[std::size_t(j) * std::size_t(n) + std::size_t(i)]; };
  Rng rng(params.seed);
  double amplitude = 1.0;
  const int last = n - 1;
  at(0, 0) = rng.symmetric();
  at(last, 0) = rng.symmetric();
  at(0, last) = rng.symmetric();
  at(last, last) = rng.symmetric();
  const double roughness = std::clamp(params.roughness, 0.01, 1.0);
  for (int step = last; step > 1; step /= 2) {
    const int half = step / 2;
    // Diamond: centre of each square = mean of its corners + noise.
    for (int j = half; j < n; j += step)
      for (int i = half; i < n; i += step) {
        const double mean = 0.25 * (at(i - half, j - half) + at(i + half, j - half) + at(i - half, j + half) +
                                    at(i + half, j + half));
        at(i, j) = mean + amplitude * rng.symmetric();
      }
    // Square: edge midpoints = mean of the 3 or 4 diamond neighbours + noise.
    for (int j = 0; j < n; j += half)
      for (int i = ((j / half) % 2 == 0) ? half : 0; i < n; i += step) {
        double sum = 0;
        int count = 0;
        if (i >= half) sum += at(i - half, j), ++count;
        if (i + half < n) sum += at(i + half, j), ++count;
        if (j >= half) sum += at(i, j - half), ++count;
        if (j + half < n) sum += at(i, j + half), ++count;
        at(i, j) = sum / count + amplitude * rng.symmetric();
      }
    amplitude *= roughness;
  }
  return f;
}

// Field of width x height (cropped from the covering 2^k+1 grid), normalised to [0, 1].
std::vector<double> plasmaField(int width, int height, const PlasmaParams& params) {
  int n = 2;
  while (n - 1 < std::max(width, height) - 1) n = (n - 1) * 2 + 1;
  const std::vector<double> full = diamondSquare(n, params);
  std::vector<double> out(std::size_t(width) * std::size_t(height));
  double lo = full[0], hi = full[0];
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const double v = full[std::size_t(j) * std::size_t(n) + std::size_t(i)];
      out[std::size_t(j) * std::size_t(width) + std::size_t(i)] = v;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  const double range = hi - lo;
  for (double& v : out) v = range > 0 ? (v - lo) / range : 0.0;
  return out;
}

std::uint16_t toSample(double v) { return std::uint16_t(std::clamp(std::floor(v + 0.5), 0.0, 65535.0)); }

}  // namespace

HeightMap generatePlasma(int width, int height, const PlasmaParams& params) {
  TUMBLE_ASSERT(width >= 1 && height >= 1, "generatePlasma: size must be positive");
  const std::vector<double> field = plasmaField(width, height, params);
  HeightMap map(width, height);
  auto& s = map.samples();
  for (std::size_t k = 0; k < s.size(); ++k) s[k] = toSample(field[k] * 65535.0);
  return map;
}

void addPlasmaRegion(HeightMap& map, int x0, int z0, int w, int h, double amplitude, const PlasmaParams& params) {
  if (w < 2 || h < 2) return;
  const std::vector<double> field = plasmaField(w, h, params);
  for (int j = std::max(0, z0); j < std::min(map.height(), z0 + h); ++j)
    for (int i = std::max(0, x0); i < std::min(map.width(), x0 + w); ++i) {
      const int li = i - x0, lj = j - z0;
      const double window = std::sin(std::numbers::pi * li / (w - 1)) * std::sin(std::numbers::pi * lj / (h - 1));
      const double add = amplitude * window * field[std::size_t(lj) * std::size_t(w) + std::size_t(li)];
      map.set(i, j, toSample(map.at(i, j) + add));
    }
}

void addRidge(HeightMap& map, const RidgeParams& p) {
  struct Point {
    double x, z, crest;  // crest: height factor near 1
  };
  std::vector<Point> line = {{p.fromX, p.fromZ, 1.0}, {p.toX, p.toZ, 1.0}};
  Rng rng(p.seed);
  const double length = std::hypot(p.toX - p.fromX, p.toZ - p.fromZ);
  // Midpoint displacement: each pass halves every segment and pushes the
  // midpoint sideways by up to jaggedness * segment length, until segments
  // are shorter than one sample (at most 20 passes: 1M points).
  for (int pass = 0; pass < 20; ++pass) {
    double longest = 0;
    std::vector<Point> next;
    next.reserve(line.size() * 2);
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      const Point& a = line[k];
      const Point& b = line[k + 1];
      const double dx = b.x - a.x, dz = b.z - a.z;
      const double seg = std::hypot(dx, dz);
      longest = std::max(longest, seg);
      next.push_back(a);
      const double side = p.jaggedness * rng.symmetric();
      const double crestJitter = length > 0 ? p.jaggedness * (seg / length) * rng.symmetric() : 0.0;
      // (-dz, dx) is the segment's perpendicular scaled by its length.
      next.push_back({0.5 * (a.x + b.x) - dz * side, 0.5 * (a.z + b.z) + dx * side,
                      std::clamp(0.5 * (a.crest + b.crest) + crestJitter, 0.0, 2.0)});
    }
    next.push_back(line.back());
    if (longest <= 1.0) break;
    line.swap(next);
  }
  const double hw = std::max(p.halfWidth, 1e-6);
  double minX = 1e300, minZ = 1e300, maxX = -1e300, maxZ = -1e300;
  for (const Point& q : line) {
    minX = std::min(minX, q.x), maxX = std::max(maxX, q.x);
    minZ = std::min(minZ, q.z), maxZ = std::max(maxZ, q.z);
  }
  const int i0 = std::max(0, int(std::floor(minX - hw))), i1 = std::min(map.width() - 1, int(std::ceil(maxX + hw)));
  const int j0 = std::max(0, int(std::floor(minZ - hw))), j1 = std::min(map.height() - 1, int(std::ceil(maxZ + hw)));
  if (i0 > i1 || j0 > j1) return;
  const int bw = i1 - i0 + 1;
  std::vector<double> influence(std::size_t(bw) * std::size_t(j1 - j0 + 1), 0.0);
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const Point& a = line[k];
    const Point& b = line[k + 1];
    const double dx = b.x - a.x, dz = b.z - a.z;
    const double len2 = dx * dx + dz * dz;
    const int si0 = std::max(i0, int(std::floor(std::min(a.x, b.x) - hw)));
    const int si1 = std::min(i1, int(std::ceil(std::max(a.x, b.x) + hw)));
    const int sj0 = std::max(j0, int(std::floor(std::min(a.z, b.z) - hw)));
    const int sj1 = std::min(j1, int(std::ceil(std::max(a.z, b.z) + hw)));
    for (int j = sj0; j <= sj1; ++j)
      for (int i = si0; i <= si1; ++i) {
        double t = len2 > 0 ? ((i - a.x) * dx + (j - a.z) * dz) / len2 : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        const double d = std::hypot(i - (a.x + t * dx), j - (a.z + t * dz));
        const double s = d / hw;
        if (s >= 1.0) continue;
        const double profile = (1 - s * s) * (1 - s * s) * (a.crest + t * (b.crest - a.crest));
        double& v = influence[std::size_t(j - j0) * std::size_t(bw) + std::size_t(i - i0)];
        v = std::max(v, profile);
      }
  }
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const double v = influence[std::size_t(j - j0) * std::size_t(bw) + std::size_t(i - i0)];
      if (v > 0) map.set(i, j, toSample(map.at(i, j) + p.height * v));
    }
}

}  // namespace tumble::terrain
