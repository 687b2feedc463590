#pragma once
// The SDL window and its OpenGL 3.3 core context, on a real display when
// there is one and on SDL's offscreen driver (EGL + Mesa) otherwise.
#include <SDL.h>

#include <memory>
#include <string>

#include "core/result.h"

namespace tumble::render {

struct GlContextConfig {
  int width = 1280, height = 720;
  std::string title = "Tumble";
  bool forceOffscreen = false;
};

class GlContext {
 public:
  // Tries the platform's driver first unless forceOffscreen is set or no
  // DISPLAY / WAYLAND_DISPLAY is present, then the offscreen driver. The
  // error lists each attempt with SDL's reason.
  static Result<std::unique_ptr<GlContext>> create(const GlContextConfig& config);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  SDL_Window* window() const { return m_window; }
  SDL_GLContext context() const { return m_context; }
  bool offscreen() const { return m_offscreen; }
  /// Size of the window's drawable in pixels (differs from the window size in
  /// points on high-DPI displays).
  void drawableSize(int& width, int& height) const;
  void present();

 private:
  GlContext() = default;
  SDL_Window* m_window = nullptr;
  SDL_GLContext m_context = nullptr;
  bool m_offscreen = false;
};

}  // namespace tumble::render
