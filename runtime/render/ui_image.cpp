// Images for the HUD's panels: menu thumbnails decoded with stb_image, and
// pictures the app computes (the minimap), uploaded as RGBA textures that
// Dear ImGui's OpenGL backend draws by name.
#include <stb_image.h>  // libstb provides the implementation

#include "render/internal/gl_util.h"
#include "render/internal/renderer_impl.h"
#include "render/renderer.h"

namespace tumble::render {

namespace {
constexpr int kMaxUiImageSide = 4096;

Result<UiImage> uploadRgba(const unsigned char* data, int w, int h) {
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, data);
  glBindTexture(GL_TEXTURE_2D, 0);
  if (std::string errors = drainGlErrors(); !errors.empty()) {
    glDeleteTextures(1, &tex);
    return makeError("texture upload failed: " + errors);
  }
  return UiImage{std::uintptr_t(tex), w, h};
}

}  // namespace

Result<UiImage> Renderer::loadUiImage(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (data == nullptr) return makeError(path + ": not a readable image (" + stbi_failure_reason() + ")");
  if (w <= 0 || h <= 0 || w > kMaxUiImageSide || h > kMaxUiImageSide) {
    stbi_image_free(data);
    return makeError(path + ": image is " + std::to_string(w) + "x" + std::to_string(h) + ", expected 1.." +
                     std::to_string(kMaxUiImageSide) + " pixels a side");
  }
  auto image = uploadRgba(data, w, h);
  stbi_image_free(data);
  if (!image) return makeError(path + ": " + image.error());
  return *image;
}

Result<UiImage> Renderer::makeUiImage(const std::uint8_t* rgba, int width, int height) {
  if (rgba == nullptr || width <= 0 || height <= 0 || width > kMaxUiImageSide || height > kMaxUiImageSide)
    return makeError("UI image of " + std::to_string(width) + "x" + std::to_string(height) + " pixels: expected 1.." +
                     std::to_string(kMaxUiImageSide) + " pixels a side");
  return uploadRgba(rgba, width, height);
}

void Renderer::freeUiImage(UiImage& image) {
  if (image.texture != 0) {
    const GLuint tex = GLuint(image.texture);
    glDeleteTextures(1, &tex);
  }
  image = UiImage{};
}

}  // namespace tumble::render
