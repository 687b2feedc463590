#pragma once
// Reading the finished frame back from GL and storing it as a PNG.
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace tumble::render {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // RGB, 3 bytes per pixel, rows top-down
};

/// Reads the colour attachment of `framebuffer` (GL name) and flips it from
/// GL's bottom-up rows to the top-down order image files use.
RgbImage readFramebuffer(unsigned framebuffer, int width, int height);

/// Encodes as PNG (stb_image_write) and writes it atomically, so a crash or
/// full disk never leaves a truncated image where a good one was.
Status writePng(const std::string& path, const RgbImage& image);

}  // namespace tumble::render
