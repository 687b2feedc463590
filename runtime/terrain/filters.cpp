#include "terrain/filters.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/file_util.h"
#include "terrain/png_io.h"

namespace tumble::terrain {

namespace {

std::uint16_t toSample(double v) { return std::uint16_t(std::clamp(std::floor(v + 0.5), 0.0, 65535.0)); }

// Keys cubic convolution weight, a = -0.5 (Catmull-Rom): interpolating and
// exact for polynomials up to degree 2.
double keys(double x) {
  constexpr double a = -0.5;
  x = std::abs(x);
  if (x < 1) return ((a + 2) * x - (a + 3)) * x * x + 1;
  if (x < 2) return ((a * x - 5 * a) * x + 8 * a) * x - 4 * a;
  return 0;
}

// Resample one line of n values (stride `stride`) to m values. Indices beyond
// the ends extend linearly, so lines (and ramps) are reproduced exactly.
void resampleLine(const double* src, int n, std::size_t srcStride, double* dst, int m, std::size_t dstStride) {
  auto get = [&](int k) {
    if (n == 1) return src[0];
    if (k < 0) return src[0] + k * (src[srcStride] - src[0]);
    if (k > n - 1) {
      const double last = src[std::size_t(n - 1) * srcStride], prev = src[std::size_t(n - 2) * srcStride];
      return last + (k - (n - 1)) * (last - prev);
    }
    return src[std::size_t(k) * srcStride];
  };
  for (int i = 0; i < m; ++i) {
    const double x = m > 1 ? double(i) * double(n - 1) / double(m - 1) : 0.0;
    const int base = std::min(int(std::floor(x)), std::max(n - 2, 0));
    const double t = x - base;
    double sum = 0;
    for (int k = -1; k <= 2; ++k) sum += keys(t - k) * get(base + k);
    dst[std::size_t(i) * dstStride] = sum;
  }
}

struct Rgb {
  double r, g, b;
};

Rgb tint(double t) {
  // Hypsometric tint stops: lowland green, upland olive, brown, rock, snow.
  static constexpr std::array<std::pair<double, Rgb>, 5> kStops = {{{0.0, {70, 120, 55}},
                                                                     {0.35, {130, 155, 80}},
                                                                     {0.65, {140, 110, 75}},
                                                                     {0.85, {150, 145, 140}},
                                                                     {1.0, {250, 250, 250}}}};
  t = std::clamp(t, 0.0, 1.0);
  for (std::size_t k = 1; k < kStops.size(); ++k) {
    if (t <= kStops[k].first) {
      const double u = (t - kStops[k - 1].first) / (kStops[k].first - kStops[k - 1].first);
      const Rgb& a = kStops[k - 1].second;
      const Rgb& b = kStops[k].second;
      return {a.r + u * (b.r - a.r), a.g + u * (b.g - a.g), a.b + u * (b.b - a.b)};
    }
  }
  return kStops.back().second;
}

}  // namespace

Result<Kernel> makeKernel(int size, std::vector<double> weights, const std::string& what) {
  if (size < 1 || size > 15 || size % 2 == 0)
    return makeError(what + ": kernel size " + std::to_string(size) + " is invalid (expected an odd size 1..15)");
  if (weights.size() != std::size_t(size) * std::size_t(size))
    return makeError(what + ": kernel of size " + std::to_string(size) + " needs " + std::to_string(size * size) +
                     " weights, got " + std::to_string(weights.size()));
  for (double w : weights)
    if (!std::isfinite(w)) return makeError(what + ": kernel weights must be finite numbers");
  return Kernel{size, std::move(weights)};
}

HeightMap convolve(const HeightMap& map, const Kernel& kernel) {
  TUMBLE_ASSERT(kernel.size % 2 == 1 && kernel.weights.size() == std::size_t(kernel.size * kernel.size),
                "convolve: kernel must be odd-sized and square; build it with makeKernel()");
  const int r = kernel.size / 2;
  const int w = map.width(), h = map.height();
  HeightMap out(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      double sum = 0;
      const double* k = kernel.weights.data();
      for (int dj = -r; dj <= r; ++dj)
        for (int di = -r; di <= r; ++di) sum += *k++ * map.clampedAt(i + di, j + dj);
      out.set(i, j, toSample(sum));
    }
  return out;
}

HeightMap smooth(const HeightMap& map, int passes) {
  const Kernel binomial{3, {1 / 16.0, 2 / 16.0, 1 / 16.0, 2 / 16.0, 4 / 16.0, 2 / 16.0, 1 / 16.0, 2 / 16.0, 1 / 16.0}};
  HeightMap out = map;
  for (int k = 0; k < passes; ++k) out = convolve(out, binomial);
  return out;
}

HeightMap sharpen(const HeightMap& map, double amount) {
  const double a = amount;
  const Kernel laplacian{3, {0, -a, 0, -a, 1 + 4 * a, -a, 0, -a, 0}};
  return convolve(map, laplacian);
}

HeightMap resampleBicubic(const HeightMap& map, int newWidth, int newHeight) {
  TUMBLE_ASSERT(newWidth >= 1 && newHeight >= 1, "resampleBicubic: size must be positive");
  const int w = map.width(), h = map.height();
  std::vector<double> src(map.samples().begin(), map.samples().end());
  // Separable: X first into newWidth x h, then Z into newWidth x newHeight.
  std::vector<double> mid(std::size_t(newWidth) * std::size_t(h));
  for (int j = 0; j < h; ++j)
    resampleLine(src.data() + std::size_t(j) * std::size_t(w), w, 1, mid.data() + std::size_t(j) * std::size_t(newWidth),
                 newWidth, 1);
  std::vector<double> dst(std::size_t(newWidth) * std::size_t(newHeight));
  for (int i = 0; i < newWidth; ++i)
    resampleLine(mid.data() + i, h, std::size_t(newWidth), dst.data() + i, newHeight, std::size_t(newWidth));
  HeightMap out(newWidth, newHeight);
  for (std::size_t k = 0; k < dst.size(); ++k) out.samples()[k] = toSample(dst[k]);
  return out;
}

std::vector<std::uint8_t> shadedRelief(const HeightMap& map, const TerrainDesc& desc, const ReliefParams& params) {
  const int w = map.width(), h = map.height();
  std::vector<std::uint8_t> rgb(std::size_t(w) * std::size_t(h) * 3);
  if (map.empty()) return rgb;
  const auto [lo, hi] = std::minmax_element(map.samples().begin(), map.samples().end());
  const double range = std::max(1.0, double(*hi) - double(*lo));
  Eigen::Vector3d light = params.towardLight.cast<double>();
  light = light.norm() > 0 ? light.normalized() : Eigen::Vector3d(0, 1, 0);
  const double k = desc.heightScale_m / (2.0 * desc.spacing_m);  // central difference, units -> slope
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const double dydx = k * (double(map.clampedAt(i + 1, j)) - double(map.clampedAt(i - 1, j)));
      const double dydz = k * (double(map.clampedAt(i, j + 1)) - double(map.clampedAt(i, j - 1)));
      const Eigen::Vector3d n = Eigen::Vector3d(-dydx, 1.0, -dydz).normalized();
      const double shade = params.ambient + (1 - params.ambient) * std::max(0.0, n.dot(light));
      const Rgb c = params.elevationTint ? tint((map.at(i, j) - *lo) / range) : Rgb{255, 255, 255};
      std::uint8_t* p = rgb.data() + (std::size_t(j) * std::size_t(w) + std::size_t(i)) * 3;
      p[0] = std::uint8_t(std::clamp(c.r * shade + 0.5, 0.0, 255.0));
      p[1] = std::uint8_t(std::clamp(c.g * shade + 0.5, 0.0, 255.0));
      p[2] = std::uint8_t(std::clamp(c.b * shade + 0.5, 0.0, 255.0));
    }
  return rgb;
}

Status saveShadedReliefPng(const HeightMap& map, const TerrainDesc& desc, const std::string& path,
                           const ReliefParams& params) {
  const std::vector<std::uint8_t> rgb = shadedRelief(map, desc, params);
  auto png = encodePngRgb8(rgb.data(), map.width(), map.height());
  if (!png) return makeError(path + ": " + png.error());
  return writeFileAtomic(path, png->data(), png->size());
}

}  // namespace tumble::terrain
