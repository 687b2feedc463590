#include "render/internal/screenshot.h"

#include <epoxy/gl.h>
// libstb (Debian libstb-dev) is a compiled library that already contains the
// implementation, so STB_IMAGE_WRITE_IMPLEMENTATION must not be defined here.
#include <stb_image_write.h>

#include <cstring>

#include "core/file_util.h"

namespace tumble::render {

RgbImage readFramebuffer(unsigned framebuffer, int width, int height) {
  RgbImage image;
  image.width = width;
  image.height = height;
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  std::vector<std::uint8_t> bottomUp(row * static_cast<std::size_t>(height));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  // Rows of 3-byte pixels are not 4-byte aligned in general.
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottomUp.data());
  image.pixels.resize(bottomUp.size());
  for (int y = 0; y < height; ++y) {
    std::memcpy(image.pixels.data() + static_cast<std::size_t>(y) * row,
                bottomUp.data() + static_cast<std::size_t>(height - 1 - y) * row, row);
  }
  return image;
}

namespace {

void appendBytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

Status writePng(const std::string& path, const RgbImage& image) {
  if (path.empty()) return makeError("screenshot: empty file name; give a path ending in .png");
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * 3) {
    return makeError(path + ": screenshot has no valid image data (" +
                     std::to_string(image.width) + "x" + std::to_string(image.height) + ")");
  }
  std::vector<std::uint8_t> png;
  png.reserve(image.pixels.size() / 2);
  const int ok = stbi_write_png_to_func(appendBytes, &png, image.width, image.height, 3,
                                        image.pixels.data(), image.width * 3);
  if (ok == 0 || png.empty()) return makeError(path + ": PNG encoding failed");
  return writeFileAtomic(path, png.data(), png.size());
}

}  // namespace tumble::render
