#pragma once
// Debug lines (contact normals, joint axes, velocity vectors ...), depth
// tested against the shapes so they read as part of the 3D scene. One
// GL_LINES draw; the vertex vector keeps its capacity across frames.
#include <vector>

#include "core/result.h"
#include "render/internal/camera_math.h"
#include "render/internal/gl_util.h"
#include "render/renderer.h"

namespace tumble::render {

class LinePass {
 public:
  Status init();
  void draw(const std::vector<DebugLine>& lines, const FrameView& view);

 private:
  struct LineVertex {
    float position[3];
    float color[3];
  };
  GlProgram m_program;
  GlVertexArray m_vao;
  GlBuffer m_buffer;
  GLint m_viewProjection = -1;
  std::vector<LineVertex> m_vertices;
};

}  // namespace tumble::render
