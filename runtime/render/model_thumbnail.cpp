// Pictures of single models for the HUD's panels (the designer's object
// palette): the model alone, lit by the default sun, seen from the front
// left and a little above, drawn into a small multisampled target of its
// own and read back as an RGBA UI image. The window's frame is not touched.
#include <algorithm>
#include <cmath>
#include <vector>

#include "render/internal/camera_math.h"
#include "render/internal/gl_util.h"
#include "render/internal/render_targets.h"
#include "render/internal/renderer_impl.h"
#include "render/internal/screenshot.h"
#include "render/model.h"
#include "render/renderer.h"

namespace tumble::render {

namespace {
constexpr int kMinThumbnail_px = 16, kMaxThumbnail_px = 512;
}  // namespace

Result<UiImage> Renderer::renderModelThumbnail(const std::shared_ptr<const Model>& model, int size_px) {
  if (!model || model->nodes.empty()) return makeError("thumbnail: no model");
  if (size_px < kMinThumbnail_px || size_px > kMaxThumbnail_px)
    return makeError("thumbnail of " + std::to_string(size_px) + " pixels: expected " +
                     std::to_string(kMinThumbnail_px) + ".." + std::to_string(kMaxThumbnail_px));
  const BoundingBox& box = model->nodes[0].coverBox;
  if (box.empty || !box.min.allFinite() || !box.max.allFinite())
    return makeError("thumbnail: " + model->source + " has no bounds");
  Impl& r = *m_impl;

  // The whole model in view: the eye backs off along the view direction
  // until every corner of the model's box is inside 90 % of the field of
  // view, so long, flat and tall models fill the square alike.
  Camera camera;
  camera.target = box.center();
  camera.fovY_rad = 0.6f;
  camera.yaw_rad = 0.7f;
  camera.pitch_rad = 0.35f;
  camera.distance_m = 1.0f;
  const FrameView axes = makeFrameView(camera, 1.0f);  // right, up, forward do not depend on the distance
  const float tanHalf = 0.9f * std::tan(0.5f * camera.fovY_rad);
  const float size_m = std::max((box.max - box.min).norm(), 1e-3f);
  float distance_m = 0.0f;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3f corner((k & 1) ? box.max.x() : box.min.x(), (k & 2) ? box.max.y() : box.min.y(),
                                 (k & 4) ? box.max.z() : box.min.z());
    const Eigen::Vector3f p = corner - camera.target;
    const float depth = p.dot(axes.forward);  // beyond the target: positive
    distance_m = std::max({distance_m, std::abs(p.dot(axes.right)) / tanHalf - depth,
                           std::abs(p.dot(axes.up)) / tanHalf - depth});
  }
  // Never inside the box, and the near plane (5 cm) ahead of it.
  camera.distance_m = std::max(distance_m, 0.5f * size_m + 0.1f);
  // Not clampCamera: a 1 cm model or a 600 m one still fills the picture.
  const float far_m = camera.distance_m + 2.0f * size_m;
  const FrameView view = makeFrameView(camera, 1.0f, far_m);
  Environment environment;  // the default daylight sun; no fog at thumbnail range
  environment.fogDensity_per_m = 0.0f;

  RenderTargets targets;
  if (Status s = targets.resize(size_px, size_px, std::max(1, r.config.msaaSamples)); !s)
    return makeError("thumbnail: " + s.error());
  targets.bindScene();
  glClearColor(0.16f, 0.18f, 0.21f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  ModelInstance instance;
  instance.model = model;
  MeshStats stats;  // not the frame's: the report counts what the player's view drew
  r.meshes.draw({instance}, view, environment, stats);
  targets.resolve();
  const RgbImage rgb = readFramebuffer(targets.frameFramebuffer(), size_px, size_px);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);  // GL's default, which the other passes expect
  if (std::string errors = drainGlErrors(); !errors.empty())
    return makeError("thumbnail of " + model->source + ": " + errors);
  if (!r.meshes.lastError().empty()) return makeError("thumbnail of " + model->source + ": " + r.meshes.lastError());
  std::vector<std::uint8_t> rgba(std::size_t(size_px) * std::size_t(size_px) * 4);
  for (std::size_t p = 0; p < std::size_t(size_px) * std::size_t(size_px); ++p) {
    rgba[4 * p + 0] = rgb.pixels[3 * p + 0];
    rgba[4 * p + 1] = rgb.pixels[3 * p + 1];
    rgba[4 * p + 2] = rgb.pixels[3 * p + 2];
    rgba[4 * p + 3] = 255;
  }
  return makeUiImage(rgba.data(), size_px, size_px);
}

}  // namespace tumble::render
