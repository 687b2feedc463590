#include "render/renderer.h"

#include <algorithm>
#include <cmath>

#include "core/log.h"
#include "render/internal/camera_math.h"
#include "render/internal/rain.h"
#include "render/internal/renderer_impl.h"
#include "render/internal/screenshot.h"
#include "render/internal/sky_model.h"

namespace tumble::render {

Result<std::unique_ptr<Renderer>> Renderer::create(const WindowConfig& config) {
  auto impl = std::make_unique<Impl>();
  impl->config = config;
  impl->quality.msaaSamples = config.msaaSamples;
  impl->quality.terrainLodPixels = config.terrainLodPixels;
  impl->quality.terrainDetail = config.terrainDetail;
  impl->quality.terrainBlend = config.terrainBlend;
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
                                       r.config.terrainLodPixels, r.config.terrainDetail, r.config.terrainBlend,
                                       r.terrainStats);
  if (!status && !r.reportedTerrainError) {
    log::warn("render: terrain not drawn: " + status.error() + " (reported once)");
    r.reportedTerrainError = true;
  }
}

// Sun shadows: depth maps of everything that casts (shapes, convex meshes,
// models) for each cascade, then the cascades' matrices into the
// environment the lit passes read. Off (config, or the light too dim to
// cast a visible shadow): the lit shaders skip every shadow lookup.
void drawShadowMaps(Renderer::Impl& r, const FrameSnapshot& frame, const FrameView& view) {
  Environment& e = r.environment;
  e.shadowCascades = 0;
  e.shadowTexture = 0;
  e.viewForward = view.forward;
  if (!r.config.shadows || e.lightColor.maxCoeff() < 0.03f || e.lightDirection.y() <= 0.0f) return;
  if (Status s = r.shadowMaps.resize(r.config.shadowMapSize, r.config.shadowCascades); !s) {
    if (!r.reportedShadowError) log::warn("render: no shadows: " + s.error() + " (reported once)");
    r.reportedShadowError = true;
    return;
  }
  const ShadowCascades cascades = fitShadowCascades(view, e.lightDirection, r.config.shadowCascades,
                                                    r.config.shadowDistance_m, r.shadowMaps.size());
  const float pixelsPerRadian = static_cast<float>(r.targets.height()) / (2.0f * view.tanHalfFovY);
  Eigen::Matrix4f toTexture = Eigen::Matrix4f::Identity() * 0.5f;
  toTexture.col(3) = Eigen::Vector4f(0.5f, 0.5f, 0.5f, 1.0f);
  for (int i = 0; i < cascades.count; ++i) {
    r.shadowMaps.bindCascade(i);
    r.shapes.drawDepth(cascades.lightViewProjection[i]);
    r.convexMeshes.drawDepth(cascades.lightViewProjection[i]);
    r.surfaces.drawDepth(cascades.lightViewProjection[i]);
    r.meshes.drawDepth(frame.models, cascades.lightViewProjection[i]);
    if (frame.terrain != nullptr) {
      // Failures are reported by the terrain's own draw.
      (void)r.terrain.drawDepth(*frame.terrain, cascades.lightViewProjection[i], view.eye, pixelsPerRadian,
                                r.config.terrainLodPixels);
    }
    e.shadowMatrices[i] = toTexture * cascades.lightViewProjection[i];
    e.shadowFar_m[i] = cascades.far_m[i];
    e.shadowTexel_m[i] = cascades.texel_m[i];
  }
  r.shadowMaps.finish();
  e.shadowCascades = cascades.count;
  e.shadowTexture = r.shadowMaps.texture();
}

// Lightning of a storm at this frame's time: the bolts still flickering
// (segment pairs) and the brightest flash, 0..1.
float activeLightning(const FrameSnapshot& frame, std::vector<Eigen::Vector3f>& bolts) {
  bolts.clear();
  float flash = 0;
  for (const LightningStrike& s : lightningStrikes(frame.sky, frame.simTime_s - 1.0, frame.simTime_s + 1e-6)) {
    const float age = float(frame.simTime_s - s.time_s);
    if (age < 0 || age >= s.duration_s) continue;
    // Return strokes: a bright start, two flickers, fading.
    const float flicker = (1.0f - age / s.duration_s) * (0.6f + 0.4f * std::cos(age * 45.0f));
    flash = std::max(flash, flicker);
    const std::vector<Eigen::Vector3f> bolt = lightningBolt(s);
    bolts.insert(bolts.end(), bolt.begin(), bolt.end());
  }
  return flash;
}

}  // namespace

Renderer::Renderer(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
Renderer::~Renderer() = default;

bool Renderer::offscreen() const { return m_impl->context->offscreen(); }
std::uint32_t Renderer::windowId() const { return SDL_GetWindowID(m_impl->context->window()); }
Camera& Renderer::camera() { return m_impl->camera; }
WindowConfig& Renderer::settings() { return m_impl->config; }

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

  r.environment = environmentFor(frame.sky, frame.simTime_s);
  std::vector<Eigen::Vector3f> bolts;
  const float flash = r.config.lightning ? activeLightning(frame, bolts) : 0.0f;
  r.environment.skyAmbient += Eigen::Vector3f(0.25f, 0.27f, 0.35f) * flash;
  r.shapes.prepare(frame.shapes);
  r.convexMeshes.prepare(frame.shapes);
  if (Status s = r.surfaces.prepare(frame.surfaces); !s && !r.reportedSurfaceError) {
    log::warn("render: surfaces not drawn: " + s.error() + " (reported once)");
    r.reportedSurfaceError = true;
  }
  drawShadowMaps(r, frame, view);

  r.targets.bindScene();
  glClear(GL_DEPTH_BUFFER_BIT);  // the sky fills every pixel nothing else covers, so no colour clear
  drawTerrain(r, frame, view);
  r.shapes.draw(view, r.environment);
  r.meshes.draw(frame.models, view, r.environment, r.meshStats);
  if (!r.meshes.lastError().empty() && !r.reportedMeshError) {
    log::warn("render: models not drawn: " + r.meshes.lastError() + " (reported once)");
    r.reportedMeshError = true;
  }
  r.convexMeshes.draw(view, r.environment);
  r.surfaces.draw(view, r.environment);
  r.lines.draw(frame.lines, view);
  // The sky after everything opaque, at the far plane with the depth test:
  // it shades only the pixels nothing covers (a sky shaded under the ground
  // cost a full screen of cube and cloud lookups).
  r.sky.draw(view, r.environment, r.config.skyCubeSize, r.config.clouds, 0.35f * flash);
  // Last in the scene: transparent, depth-tested, no depth writes. The
  // storm's rain after the scene's own particles (additive, no sorting).
  r.rain.clear();
  appendRain(frame.sky, frame.simTime_s, view.eye, r.quality.rainDrops, r.rain);
  Status particles = r.particles.draw(frame.particles, frame.additiveParticles, view);
  if (particles) particles = r.particles.draw({}, r.rain, view);
  if (!particles && !r.reportedParticleError) {
    log::warn("render: particles not drawn: " + particles.error() + " (reported once)");
    r.reportedParticleError = true;
  }
  // Effects over the scene: lightning (hidden by what stands in front), then
  // the lens flare (faded by the depth test of the sun).
  Status effects = r.effects.drawLightning(bolts, flash, view);
  if (effects && r.config.lensFlare) {
    auto visible = r.effects.drawFlare(view, r.environment);
    if (!visible) effects = makeError(visible.error());
  }
  if (!effects && !r.reportedEffectsError) {
    log::warn("render: effects not drawn: " + effects.error() + " (reported once)");
    r.reportedEffectsError = true;
  }
  // A frame only shown goes straight to the window: the scene is scaled
  // (or resolved) into the window's framebuffer and the HUD drawn there,
  // which saves a full-size copy per frame. A frame someone keeps (offscreen,
  // or a screenshot) is finished in the renderer's own frame target first.
  const bool direct = !r.context->offscreen() && screenshotPath == nullptr && width == r.targets.width() &&
                      height == r.targets.height();
  if (direct) {
    r.targets.resolveToWindow();
  } else {
    r.targets.resolve();
  }
  if (r.hud) r.hud->draw(hud, controls, r.camera.mode, r.tuning);
  r.hasFrame = !direct;

  Status result = Ok{};
  if (screenshotPath != nullptr) result = saveScreenshot(screenshotPath);

  // Offscreen there is no one to show the frame to; skip the copy.
  if (!r.context->offscreen()) {
    if (!direct && width > 0 && height > 0) r.targets.blitToWindow(width, height);
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
  r.config.terrainDetail = quality.terrainDetail;
  r.config.terrainBlend = quality.terrainBlend;
  r.environment.fogDensity_per_m = 1.0f / std::max(1.0f, quality.fogDistance_m);
  r.config.shadows = quality.shadows;
  r.config.shadowMapSize = std::clamp(quality.shadowMapSize, 64, 4096);
  r.config.shadowCascades = std::clamp(quality.shadowCascades, 1, 3);
  r.config.lensFlare = quality.lensFlare;
  r.quality.rainDrops = std::clamp(quality.rainDrops, 0, 100000);
}

const RenderQuality& Renderer::quality() const { return m_impl->quality; }

void Renderer::setWindowMode(int width, int height, bool fullscreen) {
  SDL_Window* window = m_impl->context->window();
  SDL_SetWindowFullscreen(window, fullscreen ? SDL_WINDOW_FULLSCREEN_DESKTOP : 0);
  if (!fullscreen) SDL_SetWindowSize(window, std::max(64, width), std::max(64, height));
}
std::pair<int, int> Renderer::windowSize() const {
  int w = 0, h = 0;
  SDL_GetWindowSize(m_impl->context->window(), &w, &h);
  return {w, h};
}
std::pair<Eigen::Vector3f, Eigen::Vector3f> Renderer::viewRay(float x, float y) const {
  const Impl& r = *m_impl;
  const float aspect = static_cast<float>(r.targets.width()) / static_cast<float>(std::max(1, r.targets.height()));
  const FrameView view = makeFrameView(r.camera, aspect);
  Eigen::Vector3f dir = view.forward + x * view.tanHalfFovX * view.right + y * view.tanHalfFovY * view.up;
  return {view.eye, dir.normalized()};
}

std::optional<Eigen::Vector2f> Renderer::viewPoint(const Eigen::Vector3f& world_m) const {
  const Impl& r = *m_impl;
  const float aspect = static_cast<float>(r.targets.width()) / static_cast<float>(std::max(1, r.targets.height()));
  const FrameView view = makeFrameView(r.camera, aspect);
  const Eigen::Vector3f d = world_m - view.eye;
  const float depth = d.dot(view.forward);
  if (!(depth > 1e-6f)) return std::nullopt;
  return Eigen::Vector2f(d.dot(view.right) / (depth * view.tanHalfFovX), d.dot(view.up) / (depth * view.tanHalfFovY));
}

const TerrainStats& Renderer::terrainStats() const { return m_impl->terrainStats; }
const MeshStats& Renderer::meshStats() const { return m_impl->meshStats; }

Status Renderer::saveScreenshot(const std::string& path) {
  const Impl& r = *m_impl;
  if (!r.hasFrame) {
    return makeError(path + ": no frame to save: none drawn yet, or the last went straight to the window "
                     "(pass the path to drawFrame)");
  }
  const RgbImage image =
      readFramebuffer(r.targets.frameFramebuffer(), r.targets.width(), r.targets.height());
  if (std::string errors = drainGlErrors(); !errors.empty()) {
    return makeError(path + ": reading the frame back failed: " + errors);
  }
  return writePng(path, image);
}

}  // namespace tumble::render
