#include "render/renderer.h"

#include <algorithm>

#include "core/log.h"
#include "render/internal/camera_math.h"
#include "render/internal/renderer_impl.h"
#include "render/internal/screenshot.h"

namespace tumble::render {

Result<std::unique_ptr<Renderer>> Renderer::create(const WindowConfig& config) {
  auto impl = std::make_unique<Impl>();
  impl->config = config;
  impl->quality.msaaSamples = config.msaaSamples;
  impl->quality.terrainLodPixels = config.terrainLodPixels;
  impl->quality.fogDistance_m = 1.0f / impl->environment.fogDensity_per_m;
  auto context = GlContext::create({config.width, config.height, config.title, config.forceOffscreen});
  if (!context) return makeError("renderer: " + context.error());
  impl->context = std::move(*context);

  int width = 0, height = 0;
  impl->context->drawableSize(width, height);
  if (Status s = impl->targets.resize(width, height, config.msaaSamples, impl->quality.resolutionScale); !s) {
    return makeError("renderer: " + s.error());
  }
  if (Status s = impl->sky.init(); !s) return makeError("renderer: " + s.error());
  if (Status s = impl->shapes.init(); !s) return makeError("renderer: " + s.error());
  if (Status s = impl->convexMeshes.init(); !s) return makeError("renderer: " + s.error());
  if (Status s = impl->lines.init(); !s) return makeError("renderer: " + s.error());
  if (config.hud) {
    auto hud = Hud::create(impl->context->window(), impl->context->context());
    if (!hud) return makeError("renderer: " + hud.error());
    impl->hud = std::move(*hud);
  }
  if (std::string errors = drainGlErrors(); !errors.empty()) {
    return makeError("renderer: OpenGL errors during set-up: " + errors);
  }
  log::info(std::string("render: ") + reinterpret_cast<const char*>(glGetString(GL_RENDERER)) +
            ", OpenGL " + reinterpret_cast<const char*>(glGetString(GL_VERSION)) +
            (impl->context->offscreen() ? ", offscreen" : ""));
  return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
}

namespace {

void drawTerrain(Renderer::Impl& r, const FrameSnapshot& frame, const FrameView& view) {
  if (frame.terrain == nullptr) {
    r.terrainStats = TerrainStats{};
    return;
  }
  // Pixels per radian near the screen centre: what the LOD rule needs.
  const float pixelsPerRadian = static_cast<float>(r.targets.sceneHeight()) / (2.0f * view.tanHalfFovY);
  const Status status = r.terrain.draw(*frame.terrain, view, r.environment, pixelsPerRadian,
                                       r.config.terrainLodPixels, r.terrainStats);
  if (!status && !r.reportedTerrainError) {
    log::warn("render: terrain not drawn: " + status.error() + " (reported once)");
    r.reportedTerrainError = true;
  }
}

}  // namespace

Renderer::Renderer(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
Renderer::~Renderer() = default;

bool Renderer::offscreen() const { return m_impl->context->offscreen(); }
std::uint32_t Renderer::windowId() const { return SDL_GetWindowID(m_impl->context->window()); }
Camera& Renderer::camera() { return m_impl->camera; }

Eigen::Vector2i Renderer::framebufferSize() const {
  return {m_impl->targets.width(), m_impl->targets.height()};
}

Status Renderer::drawFrame(const FrameSnapshot& frame, const HudStats& hud, Controls& controls,
                           const char* screenshotPath) {
  Impl& r = *m_impl;
  int width = 0, height = 0;
  r.context->drawableSize(width, height);
  // A minimised window has a 0x0 drawable: keep the old targets, draw anyway
  // so a requested screenshot still gets the last good size.
  if (width > 0 && height > 0) {
    if (Status status = r.targets.resize(width, height, r.config.msaaSamples, r.quality.resolutionScale); !status) {
      return makeError("renderer: " + status.error());
    }
  }

  clampCamera(r.camera);
  const float aspect = static_cast<float>(r.targets.width()) / static_cast<float>(r.targets.height());
  const FrameView view = makeFrameView(r.camera, aspect, r.quality.farPlane_m);

  r.targets.bindScene();
  glClear(GL_DEPTH_BUFFER_BIT);  // the sky covers every pixel, so no colour clear
  r.sky.draw(view, r.environment);
  drawTerrain(r, frame, view);
  r.shapes.draw(frame.shapes, view, r.environment);
  r.meshes.draw(frame.models, view, r.environment, r.meshStats);
  if (!r.meshes.lastError().empty() && !r.reportedMeshError) {
    log::warn("render: models not drawn: " + r.meshes.lastError() + " (reported once)");
    r.reportedMeshError = true;
  }
  r.convexMeshes.draw(frame.shapes, view, r.environment);
  r.lines.draw(frame.lines, view);
  // Last in the scene: transparent, depth-tested, no depth writes.
  if (Status s = r.particles.draw(frame.particles, frame.additiveParticles, view); !s && !r.reportedParticleError) {
    log::warn("render: particles not drawn: " + s.error() + " (reported once)");
    r.reportedParticleError = true;
  }
  r.targets.resolve();
  if (r.hud) r.hud->draw(hud, controls, r.camera.mode, r.tuning);
  r.hasFrame = true;

  Status result = Ok{};
  if (screenshotPath != nullptr) result = saveScreenshot(screenshotPath);

  // Offscreen there is no one to show the frame to; skip the copy.
  if (!r.context->offscreen()) {
    if (width > 0 && height > 0) r.targets.blitToWindow(width, height);
    r.context->present();
  }
  if (std::string errors = drainGlErrors(); !errors.empty() && !r.reportedGlError) {
    log::warn("render: OpenGL error during frame: " + errors + " (reported once)");
    r.reportedGlError = true;
  }
  return result;
}

void Renderer::setTuningPanel(TuningPanel* panel) { m_impl->tuning = panel; }

void Renderer::setQuality(const RenderQuality& quality) {
  Impl& r = *m_impl;
  r.quality = quality;
  r.quality.resolutionScale = std::clamp(quality.resolutionScale, 0.25f, 1.0f);
  r.quality.farPlane_m = std::max(quality.farPlane_m, 1.0f);
  r.config.msaaSamples = std::max(1, quality.msaaSamples);
  r.config.terrainLodPixels = std::max(1.0f, quality.terrainLodPixels);
  r.environment.fogDensity_per_m = 1.0f / std::max(1.0f, quality.fogDistance_m);
}

const RenderQuality& Renderer::quality() const { return m_impl->quality; }

void Renderer::setWindowMode(int width, int height, bool fullscreen) {
  SDL_Window* window = m_impl->context->window();
  SDL_SetWindowFullscreen(window, fullscreen ? SDL_WINDOW_FULLSCREEN_DESKTOP : 0);
  if (!fullscreen) SDL_SetWindowSize(window, std::max(64, width), std::max(64, height));
}
std::pair<Eigen::Vector3f, Eigen::Vector3f> Renderer::viewRay(float x, float y) const {
  const Impl& r = *m_impl;
  const float aspect = static_cast<float>(r.targets.width()) / static_cast<float>(std::max(1, r.targets.height()));
  const FrameView view = makeFrameView(r.camera, aspect);
  Eigen::Vector3f dir = view.forward + x * view.tanHalfFovX * view.right + y * view.tanHalfFovY * view.up;
  return {view.eye, dir.normalized()};
}

const TerrainStats& Renderer::terrainStats() const { return m_impl->terrainStats; }
const MeshStats& Renderer::meshStats() const { return m_impl->meshStats; }

Status Renderer::saveScreenshot(const std::string& path) {
  const Impl& r = *m_impl;
  if (!r.hasFrame) {
    return makeError(path + ": no frame to save yet; call drawFrame first");
  }
  const RgbImage image =
      readFramebuffer(r.targets.frameFramebuffer(), r.targets.width(), r.targets.height());
  if (std::string errors = drainGlErrors(); !errors.empty()) {
    return makeError(path + ": reading the frame back failed: " + errors);
  }
  return writePng(path, image);
}

}  // namespace tumble::render
