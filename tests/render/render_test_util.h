#pragma once
// Helpers for tests that really render: an offscreen renderer, a scratch
// folder for screenshots, and PNG read-back with pixel counting.
#include <gtest/gtest.h>
#include <stb_image.h>  // libstb provides the implementation

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "render/renderer.h"

namespace tumble::render::test {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // top-down rows
  const std::uint8_t* at(int x, int y) const {
    return rgb.data() + (static_cast<std::size_t>(y) * width + x) * 3;
  }
};

inline Image loadPng(const std::string& path) {
  Image image;
  int channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &image.width, &image.height, &channels, 3);
  if (data == nullptr) {
    ADD_FAILURE() << path << ": stb_image could not read it: " << stbi_failure_reason();
    return image;
  }
  image.rgb.assign(data, data + static_cast<std::size_t>(image.width) * image.height * 3);
  stbi_image_free(data);
  return image;
}

using PixelTest = std::function<bool(int r, int g, int b)>;

/// Pixels in [x0, x1) x [y0, y1) (clipped to the image) that pass `test`.
inline int countPixels(const Image& image, const PixelTest& test, int x0 = 0, int y0 = 0,
                       int x1 = 1 << 30, int y1 = 1 << 30) {
  int count = 0;
  for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y) {
    for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) {
      const std::uint8_t* p = image.at(x, y);
      if (test(p[0], p[1], p[2])) ++count;
    }
  }
  return count;
}

// Colour families. The sky runs from pale blue-white to mid blue (blue is
// always its largest channel), so none of these occur in a sky-only frame.
inline bool isReddish(int r, int g, int b) { return r > 90 && r > g + 50 && r > b + 50; }
inline bool isGreenish(int r, int g, int b) { return g > 90 && g > r + 40 && g > b + 40; }
inline bool isYellowish(int r, int g, int b) { return r > 90 && g > 90 && b + 60 < std::min(r, g); }

/// A renderer on SDL's offscreen driver. GL must work here (CI has Mesa), so
/// failing to create one fails the test rather than skipping it.
inline std::unique_ptr<Renderer> makeOffscreenRenderer(int width, int height, bool hud) {
  ::setenv("SDL_VIDEODRIVER", "offscreen", 1);
  WindowConfig config;
  config.width = width;
  config.height = height;
  config.hud = hud;
  config.forceOffscreen = true;
  auto renderer = Renderer::create(config);
  EXPECT_TRUE(renderer.ok()) << (renderer.ok() ? "" : renderer.error());
  if (!renderer.ok()) return nullptr;
  EXPECT_TRUE((*renderer)->offscreen());
  return std::move(*renderer);
}

/// A folder of its own per test, removed afterwards unless the test failed
/// (then the PNGs are kept to look at; the path is printed).
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_path = std::filesystem::temp_directory_path() /
             ("tumble_render_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
              std::to_string(::getpid()));
    std::filesystem::create_directories(m_path);
  }
  ~ScratchDir() {
    if (::testing::Test::HasFailure()) {
      std::printf("screenshots kept in %s\n", m_path.c_str());
    } else {
      std::error_code ignored;
      std::filesystem::remove_all(m_path, ignored);
    }
  }
  std::string file(const std::string& name) const { return (m_path / name).string(); }

 private:
  std::filesystem::path m_path;
};

/// A test fixture with a Width x Height offscreen renderer (no HUD) and a
/// scratch folder; render() draws a frame and reads its PNG back.
template <int Width, int Height>
class OffscreenRenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    m_renderer = makeOffscreenRenderer(Width, Height, /*hud=*/false);
    ASSERT_NE(m_renderer, nullptr) << "no OpenGL: offscreen rendering must work here";
  }
  Image render(const FrameSnapshot& frame, const std::string& name) {
    Controls controls;
    const std::string path = m_scratch.file(name);
    const Status status = m_renderer->drawFrame(frame, HudStats{}, controls, path.c_str());
    EXPECT_TRUE(status.ok()) << (status.ok() ? "" : status.error());
    return loadPng(path);
  }
  ScratchDir m_scratch;
  std::unique_ptr<Renderer> m_renderer;
};

}  // namespace tumble::render::test
