#include "render/internal/surface_pass.h"

#include <algorithm>
#include <cstddef>

#include "render/internal/shaders.h"

namespace tumble::render {

std::size_t appendTwoSided(const DrawSurface& surface, std::vector<MeshVertex>& out) {
  const std::vector<Eigen::Vector3f>& p = surface.positions;
  const std::vector<std::uint32_t>& idx = surface.indices;
  auto valid = [&](std::size_t t, Eigen::Vector3f* areaNormal) {
    const std::uint32_t a = idx[t], b = idx[t + 1], c = idx[t + 2];
    if (a >= p.size() || b >= p.size() || c >= p.size()) return false;
    *areaNormal = (p[b] - p[a]).cross(p[c] - p[a]);  // twice the area, along the face normal
    return areaNormal->allFinite() && areaNormal->squaredNorm() > 0.0f;
  };
  // Smooth normals: the area-weighted sum of the faces at each vertex.
  std::vector<Eigen::Vector3f> normals(p.size(), Eigen::Vector3f::Zero());
  Eigen::Vector3f n;
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3)
    if (valid(t, &n))
      for (int k = 0; k < 3; ++k) normals[idx[t + k]] += n;
  const std::size_t before = out.size();
  auto vertex = [&](std::uint32_t i, float side) {
    MeshVertex v{};
    const float length = normals[i].norm();
    const Eigen::Vector3f unit = length > 0 ? Eigen::Vector3f(normals[i] / length) : Eigen::Vector3f::UnitY();
    for (int k = 0; k < 3; ++k) v.position[k] = p[i][k], v.normal[k] = side * unit[k];
    v.capOffset = 0.0f;
    out.push_back(v);
  };
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    if (!valid(t, &n)) continue;
    vertex(idx[t], 1), vertex(idx[t + 1], 1), vertex(idx[t + 2], 1);
    vertex(idx[t], -1), vertex(idx[t + 2], -1), vertex(idx[t + 1], -1);
  }
  return out.size() - before;
}

Status SurfacePass::init() {
  auto program = buildProgram("surface shader", shaders::kShapeVertex, shaders::kShapeFragment);
  if (!program) return makeError(program.error());
  m_program = std::move(*program);
  m_lit.locate(m_program);
  m_checker = uniformLocation(m_program, "uChecker");
  auto depth = buildProgram("surface shadow shader", shaders::kShapeVertex, shaders::kDepthFragment);
  if (!depth) return makeError(depth.error());
  m_depthProgram = std::move(*depth);
  m_depthViewProjection = uniformLocation(m_depthProgram, "uViewProjection");
  m_vao = makeVertexArray();
  m_vertices = makeBuffer();
  glBindVertexArray(m_vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, m_vertices.get());
  auto attribute = [](GLuint location, GLint components, std::size_t offset) {
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                          reinterpret_cast<const void*>(offset));
  };
  attribute(shaders::kAttribPosition, 3, offsetof(MeshVertex, position));
  attribute(shaders::kAttribNormal, 3, offsetof(MeshVertex, normal));
  attribute(shaders::kAttribCapOffset, 1, offsetof(MeshVertex, capOffset));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  if (std::string errors = drainGlErrors(); !errors.empty()) return makeError("surface pass set-up: " + errors);
  return Ok{};
}

Status SurfacePass::prepare(const std::vector<DrawSurface>& surfaces) {
  m_ranges.clear();
  if (surfaces.empty()) return Ok{};
  if (!created())
    if (Status s = init(); !s) return s;
  m_scratch.clear();
  for (const DrawSurface& surface : surfaces) {
    Range range;
    range.first = static_cast<GLint>(m_scratch.size());
    range.count = static_cast<GLsizei>(appendTwoSided(surface, m_scratch));
    for (int k = 0; k < 3; ++k) range.color[k] = std::clamp(surface.color[k], 0.0f, 1.0f);
    if (range.count > 0) m_ranges.push_back(range);
  }
  glBindBuffer(GL_ARRAY_BUFFER, m_vertices.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_scratch.size() * sizeof(MeshVertex)), m_scratch.data(),
               GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  return Ok{};
}

// The shape shader's per-instance inputs as constant attributes (their
// arrays are disabled in this pass's vertex array): no move, no turn, unit
// scale, the surface's colour.
void SurfacePass::bindConstants(const Eigen::Vector3f& color) const {
  glVertexAttrib3f(shaders::kAttribInstancePosition, 0, 0, 0);
  glVertexAttrib4f(shaders::kAttribInstanceRotation, 0, 0, 0, 1);
  glVertexAttrib3f(shaders::kAttribInstanceScale, 1, 1, 1);
  glVertexAttrib1f(shaders::kAttribInstanceHalfHeight, 0);
  glVertexAttrib3f(shaders::kAttribInstanceColor, color.x(), color.y(), color.z());
}

void SurfacePass::drawDepth(const Eigen::Matrix4f& lightViewProjection) const {
  if (m_ranges.empty()) return;
  glUseProgram(m_depthProgram.get());
  glUniformMatrix4fv(m_depthViewProjection, 1, GL_FALSE, lightViewProjection.data());
  glBindVertexArray(m_vao.get());
  for (const Range& range : m_ranges) {
    bindConstants(range.color);
    glDrawArrays(GL_TRIANGLES, range.first, range.count);
  }
  glBindVertexArray(0);
}

void SurfacePass::draw(const FrameView& view, const Environment& environment) const {
  if (m_ranges.empty()) return;
  glUseProgram(m_program.get());
  m_lit.apply(view, environment);
  glUniform1i(m_checker, 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glBindVertexArray(m_vao.get());
  for (const Range& range : m_ranges) {
    bindConstants(range.color);
    glDrawArrays(GL_TRIANGLES, range.first, range.count);
  }
  glBindVertexArray(0);
  glDisable(GL_CULL_FACE);
}

}  // namespace tumble::render
