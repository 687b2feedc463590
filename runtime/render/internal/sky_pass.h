#pragma once
// The sky: a cube map of the clear sky (horizon gradient, sun glow and disc;
// built on the CPU by sky_model.h and rebuilt only when the sun or the sky
// colours change) and two cloud layers of a generated plasma texture that
// the wind moves. Drawn as one full-screen triangle at the far plane after
// the opaque passes: the depth test leaves it every pixel nothing covers,
// so it replaces a colour clear without shading pixels twice.
#include <array>

#include "core/result.h"
#include "render/internal/camera_math.h"
#include "render/internal/environment.h"
#include "render/internal/gl_util.h"

namespace tumble::render {

class SkyPass {
 public:
  Status init();
  /// cubeSize: texels per cube face edge (16..1024; a change rebuilds the
  /// cube); clouds: draw the cloud layers (the plasma is made the first
  /// time); flash: lightning's brightening of the whole sky, 0..1.
  void draw(const FrameView& view, const Environment& environment, int cubeSize, bool clouds, float flash);
  /// Times the cube was rebuilt (a sun or colour change); for tests and stats.
  int cubeBuilds() const { return m_cubeBuilds; }

 private:
  void rebuildCubeIfChanged(const Environment& environment);
  void makeClouds();

  GlProgram m_program;
  GlVertexArray m_emptyVao;  // core profile draws need a bound VAO even without attributes
  GlTexture m_cube, m_clouds;
  int m_cubeSize = 128;
  int m_cubeBuilds = 0;
  std::array<float, 17> m_cubeKey{};  // the colours and sun the cube was built for
  bool m_hasCube = false;
  GLint m_right = -1, m_up = -1, m_forward = -1, m_tanHalfFov = -1;
  GLint m_sky = -1, m_cloudTexture = -1, m_cloudCover = -1, m_cloudOffset = -1, m_cloudColor = -1,
        m_cloudShadow = -1, m_horizon = -1, m_flash = -1;
};

}  // namespace tumble::render
