#pragma once
// Pixel statistics of screenshots the tests take (`run --screenshot`,
// `play`/`design --frames N --screenshot`): what a player sees, measured.
#include <stb/stb_image.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace tumble::test {

/// Mean of the picture's R, G and B values (0..255); -1 if it does not load.
inline double meanBrightness(const std::string& path) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
  if (!data) return -1;
  double sum = 0;
  for (int i = 0; i < w * h * 3; ++i) sum += data[i];
  stbi_image_free(data);
  return sum / (w * h * 3);
}

/// Colour statistics of a rectangle of a screenshot (pixels, clipped to it).
struct RegionStats {
  bool loaded = false;
  int pixels = 0;
  std::array<double, 3> meanRgb{0, 0, 0};  ///< 0..255
  double brightnessSpread = 0;             ///< standard deviation of (R+G+B)/3 over the rectangle
};

inline RegionStats regionStats(const std::string& path, int x0, int y0, int width, int height) {
  RegionStats r;
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
  if (!data) return r;
  r.loaded = true;
  double sum = 0, sum2 = 0;
  for (int y = std::max(0, y0); y < std::min(h, y0 + height); ++y)
    for (int x = std::max(0, x0); x < std::min(w, x0 + width); ++x) {
      const unsigned char* p = data + (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3;
      for (int c = 0; c < 3; ++c) r.meanRgb[std::size_t(c)] += p[c];
      const double b = (p[0] + p[1] + p[2]) / 3.0;
      sum += b;
      sum2 += b * b;
      ++r.pixels;
    }
  stbi_image_free(data);
  if (r.pixels > 0) {
    for (double& m : r.meanRgb) m /= r.pixels;
    const double mean = sum / r.pixels;
    r.brightnessSpread = std::sqrt(std::max(0.0, sum2 / r.pixels - mean * mean));
  }
  return r;
}

}  // namespace tumble::test
