#pragma once
// Sky gradient: zenith to horizon above, horizon to a dim ground colour below,
// with a glow around the sun. Fills the whole frame, so it replaces a colour
// clear and must be drawn first.
#include "core/result.h"
#include "render/internal/camera_math.h"
#include "render/internal/environment.h"
#include "render/internal/gl_util.h"

namespace tumble::render {

class SkyPass {
 public:
  Status init();
  void draw(const FrameView& view, const Environment& environment) const;

 private:
  GlProgram m_program;
  GlVertexArray m_emptyVao;  // core profile draws need a bound VAO even without attributes
  GLint m_right = -1, m_up = -1, m_forward = -1, m_tanHalfFov = -1;
  GLint m_zenith = -1, m_horizon = -1, m_ground = -1, m_lightDirection = -1, m_lightColor = -1;
};

}  // namespace tumble::render
