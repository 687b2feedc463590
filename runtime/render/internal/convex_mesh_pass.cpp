#include "render/internal/convex_mesh_pass.h"

#include <cstddef>

#include "render/internal/mesh_builder.h"
#include "render/internal/shaders.h"

namespace tumble::render {

namespace {

void meshAttribute(GLuint location, GLint components, std::size_t offset) {
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                        reinterpret_cast<const void*>(offset));
}

void instanceAttribute(GLuint location, GLint components, std::size_t offset) {
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, sizeof(ShapeInstance),
                        reinterpret_cast<const void*>(offset));
  glVertexAttribDivisor(location, 1);
}

}  // namespace

Status ConvexMeshPass::init() {
  auto program = buildProgram("convex mesh shader", shaders::kShapeVertex, shaders::kShapeFragment);
  if (!program) return makeError(program.error());
  m_program = std::move(*program);
  m_lit.locate(m_program);
  auto depth = buildProgram("convex mesh shadow shader", shaders::kShapeVertex, shaders::kDepthFragment);
  if (!depth) return makeError(depth.error());
  m_depthProgram = std::move(*depth);
  m_depthViewProjection = uniformLocation(m_depthProgram, "uViewProjection");
  m_checker = uniformLocation(m_program, "uChecker");
  return Ok{};
}

ConvexMeshPass::Mesh ConvexMeshPass::upload(const ConvexMeshData& data) {
  // One vertex per triangle corner, with the triangle's normal. Indices past
  // the vertex array and degenerate triangles are skipped.
  std::vector<MeshVertex> flat;
  flat.reserve(data.indices.size());
  for (std::size_t t = 0; t + 2 < data.indices.size(); t += 3) {
    const std::uint32_t i0 = data.indices[t], i1 = data.indices[t + 1], i2 = data.indices[t + 2];
    if (i0 >= data.vertices.size() || i1 >= data.vertices.size() || i2 >= data.vertices.size()) continue;
    const Eigen::Vector3f a = data.vertices[i0], b = data.vertices[i1], c = data.vertices[i2];
    Eigen::Vector3f n = (b - a).cross(c - a);
    if (!(n.norm() > 0.0f) || !n.allFinite()) continue;
    n.normalize();
    for (const Eigen::Vector3f& p : {a, b, c}) {
      MeshVertex v{};
      for (int k = 0; k < 3; ++k) v.position[k] = p[k], v.normal[k] = n[k];
      v.capOffset = 0.0f;
      flat.push_back(v);
    }
  }
  Mesh mesh;
  mesh.vao = makeVertexArray();
  mesh.vertices = makeBuffer();
  mesh.instances = makeBuffer();
  mesh.vertexCount = static_cast<GLsizei>(flat.size());
  glBindVertexArray(mesh.vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, mesh.vertices.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(flat.size() * sizeof(MeshVertex)), flat.data(),
               GL_STATIC_DRAW);
  meshAttribute(shaders::kAttribPosition, 3, offsetof(MeshVertex, position));
  meshAttribute(shaders::kAttribNormal, 3, offsetof(MeshVertex, normal));
  meshAttribute(shaders::kAttribCapOffset, 1, offsetof(MeshVertex, capOffset));
  glBindBuffer(GL_ARRAY_BUFFER, mesh.instances.get());
  instanceAttribute(shaders::kAttribInstancePosition, 3, offsetof(ShapeInstance, position));
  instanceAttribute(shaders::kAttribInstanceRotation, 4, offsetof(ShapeInstance, rotation));
  instanceAttribute(shaders::kAttribInstanceScale, 3, offsetof(ShapeInstance, scale));
  instanceAttribute(shaders::kAttribInstanceHalfHeight, 1, offsetof(ShapeInstance, halfHeight));
  instanceAttribute(shaders::kAttribInstanceColor, 3, offsetof(ShapeInstance, color));
  glBindVertexArray(0);
  return mesh;
}

void ConvexMeshPass::prepare(const std::vector<DrawShape>& shapes) {
  ++m_frame;
  bool any = false;
  for (const DrawShape& shape : shapes) {
    if (shape.kind != ShapeKind::ConvexMesh || !shape.convexMesh || shape.convexMesh->id == 0) continue;
    auto it = m_meshes.find(shape.convexMesh->id);
    if (it == m_meshes.end()) it = m_meshes.emplace(shape.convexMesh->id, upload(*shape.convexMesh)).first;
    Mesh& mesh = it->second;
    if (mesh.lastUsedFrame != m_frame) mesh.pending.clear();
    mesh.lastUsedFrame = m_frame;
    mesh.pending.push_back(makeInstance(shape));
    any = true;
  }
  for (auto it = m_meshes.begin(); it != m_meshes.end();) {
    if (m_frame - it->second.lastUsedFrame > kEvictFrames) it = m_meshes.erase(it);
    else ++it;
  }
  m_any = any;
  if (!any) return;
  for (auto& [id, mesh] : m_meshes) {
    if (mesh.lastUsedFrame != m_frame || mesh.pending.empty() || mesh.vertexCount == 0) continue;
    glBindBuffer(GL_ARRAY_BUFFER, mesh.instances.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.pending.size() * sizeof(ShapeInstance)),
                 mesh.pending.data(), GL_STREAM_DRAW);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void ConvexMeshPass::drawDepth(const Eigen::Matrix4f& lightViewProjection) const {
  if (!m_any) return;
  glUseProgram(m_depthProgram.get());
  glUniformMatrix4fv(m_depthViewProjection, 1, GL_FALSE, lightViewProjection.data());
  for (const auto& [id, mesh] : m_meshes) {
    if (mesh.lastUsedFrame != m_frame || mesh.pending.empty() || mesh.vertexCount == 0) continue;
    glBindVertexArray(mesh.vao.get());
    glDrawArraysInstanced(GL_TRIANGLES, 0, mesh.vertexCount, static_cast<GLsizei>(mesh.pending.size()));
  }
  glBindVertexArray(0);
}

void ConvexMeshPass::draw(const FrameView& view, const Environment& environment) {
  if (!m_any) return;

  glUseProgram(m_program.get());
  m_lit.apply(view, environment);
  glUniform1i(m_checker, 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  for (auto& [id, mesh] : m_meshes) {
    if (mesh.lastUsedFrame != m_frame || mesh.pending.empty() || mesh.vertexCount == 0) continue;
    glBindVertexArray(mesh.vao.get());
    glDrawArraysInstanced(GL_TRIANGLES, 0, mesh.vertexCount, static_cast<GLsizei>(mesh.pending.size()));
  }
  glBindVertexArray(0);
  glDisable(GL_CULL_FACE);
}

}  // namespace tumble::render
