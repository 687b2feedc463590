#include "render/internal/gl_context.h"

#include <epoxy/gl.h>

#include <cstdlib>
#include <cstring>

#include "core/log.h"

namespace tumble::render {

namespace {

constexpr const char* kOffscreenDriver = "offscreen";

bool envSet(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0';
}

// A display server, or a driver the user chose explicitly (kmsdrm runs
// without either variable; SDL_VIDEODRIVER=offscreen is honoured as well).
bool displayWorthTrying() {
  return envSet("DISPLAY") || envSet("WAYLAND_DISPLAY") || envSet("SDL_VIDEODRIVER");
}

struct Attempt {
  SDL_Window* window = nullptr;
  SDL_GLContext context = nullptr;
  std::string error;
};

// One attempt on one video driver (nullptr: SDL's choice, which honours
// SDL_VIDEODRIVER). On failure everything it created is released again, so
// the next attempt starts from a clean SDL video subsystem.
Attempt tryDriver(const char* driver, const GlContextConfig& config) {
  Attempt attempt;
  const std::string label = driver ? driver : "default";
  if (driver) {
    // OVERRIDE so it wins over an SDL_VIDEODRIVER variable naming a driver
    // that just failed; reset afterwards so it does not leak to later code.
    SDL_SetHintWithPriority(SDL_HINT_VIDEODRIVER, driver, SDL_HINT_OVERRIDE);
  }
  const int initResult = SDL_InitSubSystem(SDL_INIT_VIDEO);
  if (driver) SDL_ResetHint(SDL_HINT_VIDEODRIVER);
  if (initResult != 0) {
    attempt.error = label + " video driver: SDL_Init(VIDEO) failed: " + SDL_GetError();
    return attempt;
  }

  SDL_GL_ResetAttributes();
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
  SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
  // The scene is drawn into the renderer's own framebuffer objects, so the
  // window needs no depth or multisample buffers of its own.
  SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 0);

  // Resizable is ignored by the offscreen driver.
  const Uint32 flags = SDL_WINDOW_OPENGL | SDL_WINDOW_ALLOW_HIGHDPI | SDL_WINDOW_RESIZABLE;
  attempt.window = SDL_CreateWindow(config.title.c_str(), SDL_WINDOWPOS_CENTERED,
                                    SDL_WINDOWPOS_CENTERED, config.width, config.height, flags);
  if (!attempt.window) {
    attempt.error = label + " video driver: SDL_CreateWindow(" + std::to_string(config.width) +
                    "x" + std::to_string(config.height) + ") failed: " + SDL_GetError();
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
    return attempt;
  }
  attempt.context = SDL_GL_CreateContext(attempt.window);
  if (!attempt.context) {
    attempt.error = label + " video driver: no OpenGL 3.3 core context: " + SDL_GetError();
    SDL_DestroyWindow(attempt.window);
    attempt.window = nullptr;
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
    return attempt;
  }
  // epoxy_gl_version() is 0 if the context is unusable even though SDL
  // returned one (seen with broken driver installs).
  if (epoxy_gl_version() < 33) {
    attempt.error = label + " video driver: context reports OpenGL " +
                    std::to_string(epoxy_gl_version()) + ", need 3.3";
    SDL_GL_DeleteContext(attempt.context);
    SDL_DestroyWindow(attempt.window);
    attempt.context = nullptr;
    attempt.window = nullptr;
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
  }
  return attempt;
}

}  // namespace

Result<std::unique_ptr<GlContext>> GlContext::create(const GlContextConfig& config) {
  if (config.width <= 0 || config.height <= 0) {
    return makeError("window size " + std::to_string(config.width) + "x" +
                     std::to_string(config.height) + " is invalid: width and height must be > 0");
  }
  std::string errors;
  const bool tryDisplay = !config.forceOffscreen && displayWorthTrying();
  if (!tryDisplay) {
    errors = config.forceOffscreen ? "offscreen requested" : "no DISPLAY or WAYLAND_DISPLAY";
  }
  for (const char* driver : {static_cast<const char*>(nullptr), kOffscreenDriver}) {
    if (driver == nullptr && !tryDisplay) continue;
    Attempt attempt = tryDriver(driver, config);
    if (attempt.context) {
      std::unique_ptr<GlContext> result(new GlContext());
      result->m_window = attempt.window;
      result->m_context = attempt.context;
      const char* current = SDL_GetCurrentVideoDriver();
      result->m_offscreen = current != nullptr && std::strcmp(current, kOffscreenDriver) == 0;
      // Vsync on a real display avoids tearing and burning a core; offscreen
      // there is nothing to sync to. Failure just means no vsync.
      SDL_GL_SetSwapInterval(result->m_offscreen ? 0 : 1);
      if (driver != nullptr && tryDisplay) {
        log::warn("render: display unusable, rendering offscreen (" + errors + ")");
      }
      return result;
    }
    errors += errors.empty() ? "" : "; ";
    errors += attempt.error;
  }
  return makeError("could not create an OpenGL 3.3 core context: " + errors +
                   ". Offscreen rendering needs Mesa's EGL (Debian: libegl-mesa0, "
                   "libgl1-mesa-dri).");
}

GlContext::~GlContext() {
  if (m_context) SDL_GL_DeleteContext(m_context);
  if (m_window) SDL_DestroyWindow(m_window);
  SDL_QuitSubSystem(SDL_INIT_VIDEO);
}

void GlContext::drawableSize(int& width, int& height) const {
  SDL_GL_GetDrawableSize(m_window, &width, &height);
}

void GlContext::present() { SDL_GL_SwapWindow(m_window); }

}  // namespace tumble::render
