#pragma once
// Pixel statistics of screenshots the tests take (`run --screenshot`,
// `play`/`design --frames N --screenshot`): what a player sees, measured.
#include <stb/stb_image.h>

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

}  // namespace tumble::test
