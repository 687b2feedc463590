#pragma once
// Weather and light effects drawn over the finished scene, before the
// resolve: lightning bolts (camera-facing glowing strips along the
// midpoint-displaced polyline of lightning.cpp, additive, hidden by what
// stands in front) and the sun's lens flare (billboards made here on the
// CPU, faded by how much of the sun a depth test finds uncovered: an
// occlusion query of a small quad at the sun against the scene's depth).
// Nothing is created until a frame needs it.
#include <vector>

#include "core/result.h"
#include "render/internal/camera_math.h"
#include "render/internal/environment.h"
#include "render/internal/gl_util.h"

namespace tumble::render {

/// The flare's sprites: `count` square images of size x size, side by side
/// (row-major, one byte each): a soft glow, a thin ring, a hexagon and a
/// streak. Deterministic; tested without GL.
std::vector<std::uint8_t> buildFlareSprites(int size, int count);

class EffectsPass {
 public:
  EffectsPass() = default;
  ~EffectsPass();
  EffectsPass(const EffectsPass&) = delete;
  EffectsPass& operator=(const EffectsPass&) = delete;
  /// Bolts as segment pairs (world m), brightness 0..1 (flicker).
  Status drawLightning(const std::vector<Eigen::Vector3f>& segments, float brightness, const FrameView& view);
  /// Draws the flare if the sun is in view and not hidden; returns the
  /// uncovered fraction of the sun (0..1) the depth test found.
  Result<float> drawFlare(const FrameView& view, const Environment& environment);

 private:
  Status init();
  bool m_initialised = false;
  GlProgram m_program;         // world or screen-space strips: position, uv, colour
  GlVertexArray m_vao;
  GlBuffer m_vertices;
  GlTexture m_sprites;
  GLuint m_query = 0;
  GLint m_viewProjection = -1, m_texture = -1, m_useTexture = -1;
  std::vector<float> m_scratch;
};

}  // namespace tumble::render
