#include "render/internal/line_pass.h"

#include <cstddef>

#include "render/internal/shaders.h"

namespace tumble::render {

Status LinePass::init() {
  auto program = buildProgram("line shader", shaders::kLineVertex, shaders::kLineFragment);
  if (!program) return makeError(program.error());
  m_program = std::move(*program);
  m_viewProjection = uniformLocation(m_program, "uViewProjection");
  m_vao = makeVertexArray();
  m_buffer = makeBuffer();
  glBindVertexArray(m_vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, m_buffer.get());
  glEnableVertexAttribArray(shaders::kAttribLinePosition);
  glVertexAttribPointer(shaders::kAttribLinePosition, 3, GL_FLOAT, GL_FALSE, sizeof(LineVertex),
                        reinterpret_cast<const void*>(offsetof(LineVertex, position)));
  glEnableVertexAttribArray(shaders::kAttribLineColor);
  glVertexAttribPointer(shaders::kAttribLineColor, 3, GL_FLOAT, GL_FALSE, sizeof(LineVertex),
                        reinterpret_cast<const void*>(offsetof(LineVertex, color)));
  glBindVertexArray(0);
  return Ok{};
}

void LinePass::draw(const std::vector<DebugLine>& lines, const FrameView& view) {
  if (lines.empty()) return;
  // Depth-tested lines first, then the overlay (drawn over everything, with
  // its depth written so the sky drawn later does not cover it).
  m_vertices.clear();
  GLsizei tested = 0;
  for (bool overlay : {false, true}) {
    for (const DebugLine& line : lines) {
      if (line.overlay != overlay) continue;
      m_vertices.push_back({{line.a.x(), line.a.y(), line.a.z()},
                            {line.color.x(), line.color.y(), line.color.z()}});
      m_vertices.push_back({{line.b.x(), line.b.y(), line.b.z()},
                            {line.color.x(), line.color.y(), line.color.z()}});
    }
    if (!overlay) tested = static_cast<GLsizei>(m_vertices.size());
  }
  const GLsizei overlayVertices = static_cast<GLsizei>(m_vertices.size()) - tested;
  glUseProgram(m_program.get());
  glUniformMatrix4fv(m_viewProjection, 1, GL_FALSE, view.viewProjection.data());
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glBindVertexArray(m_vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, m_buffer.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_vertices.size() * sizeof(LineVertex)),
               m_vertices.data(), GL_STREAM_DRAW);
  if (tested > 0) glDrawArrays(GL_LINES, 0, tested);
  if (overlayVertices > 0) {
    glDepthFunc(GL_ALWAYS);
    glDrawArrays(GL_LINES, tested, overlayVertices);
  }
  glBindVertexArray(0);
  glDepthFunc(GL_LESS);
}

}  // namespace tumble::render
