#pragma once
// Surfaces remade every frame (DrawSurface: cloth), drawn with the lit shape
// shader so they take the same sun, ambient, shadows and fog as the shapes.
// Each frame every surface's smooth normals are averaged over the triangles
// at each vertex (area-weighted), and every triangle is written twice: as
// given with those normals, and reversed with them negated. Back faces are
// culled, so whichever side the camera sees is lit by its own normal (both
// sides of a cloth lit, no two-sided lighting in the shader). All surfaces
// share one vertex buffer re-specified each frame; the instance attributes
// of the shape shader are constants (identity transform, the surface's colour).
// GL objects are created on the first frame that has a surface.
#include <vector>

#include "core/result.h"
#include "render/internal/camera_math.h"
#include "render/internal/environment.h"
#include "render/internal/gl_util.h"
#include "render/internal/lit_uniforms.h"
#include "render/internal/mesh_builder.h"
#include "render/renderer.h"

namespace tumble::render {

/// Appends the two-sided triangles of `surface` (6 vertices per valid
/// triangle: front, then back) to `out`; returns how many it appended.
/// Triangles with an index past the positions, or of zero or non-finite
/// area, are skipped. Exposed for tests.
std::size_t appendTwoSided(const DrawSurface& surface, std::vector<MeshVertex>& out);

class SurfacePass {
 public:
  /// Builds and uploads this frame's surfaces (once per frame, before drawDepth and draw).
  Status prepare(const std::vector<DrawSurface>& surfaces);
  /// Depth only into the bound shadow map.
  void drawDepth(const Eigen::Matrix4f& lightViewProjection) const;
  void draw(const FrameView& view, const Environment& environment) const;
  bool created() const { return m_program.get() != 0; }

 private:
  struct Range {
    GLint first = 0;
    GLsizei count = 0;
    Eigen::Vector3f color{1, 1, 1};
  };
  Status init();
  void bindConstants(const Eigen::Vector3f& color) const;

  GlProgram m_program, m_depthProgram;
  LitUniforms m_lit;
  GLint m_checker = -1, m_depthViewProjection = -1;
  GlVertexArray m_vao;
  GlBuffer m_vertices;
  std::vector<MeshVertex> m_scratch;
  std::vector<Range> m_ranges;
};

}  // namespace tumble::render
