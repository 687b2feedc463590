// The mesh pass (internal/mesh_pass.h): uploads models, then draws the
// frame's sorted draw list with one material bind per material.
#include "render/internal/mesh_pass.h"

#include <cstddef>

#include "render/internal/shaders.h"

namespace tumble::render {

namespace {

void vertexAttribute(GLuint location, GLint components, std::size_t offset) {
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, sizeof(MeshGpuVertex),
                        reinterpret_cast<const void*>(offset));
}

}  // namespace

std::vector<MeshGpuVertex> interleaveMesh(const ModelMesh& mesh) {
  std::vector<MeshGpuVertex> out(mesh.positions.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    MeshGpuVertex& v = out[i];
    const Eigen::Vector3f n = i < mesh.normals.size() ? mesh.normals[i] : Eigen::Vector3f::UnitY();
    const Eigen::Vector2f uv = i < mesh.uvs.size() ? mesh.uvs[i] : Eigen::Vector2f::Zero();
    const Eigen::Vector3f c = i < mesh.colors.size() ? mesh.colors[i] : Eigen::Vector3f::Ones();
    for (int k = 0; k < 3; ++k) {
      v.position[k] = mesh.positions[i][k];
      v.normal[k] = n[k];
      v.color[k] = c[k];
    }
    v.uv[0] = uv.x();
    v.uv[1] = uv.y();
  }
  return out;
}

Status MeshPass::init() {
  auto program = buildProgram("mesh shader", shaders::kMeshVertex, shaders::kMeshFragment);
  if (!program) return makeError(program.error());
  m_program = std::move(*program);
  m_lit.locate(m_program);
  m_model = uniformLocation(m_program, "uModel");
  m_normalMatrix = uniformLocation(m_program, "uNormalMatrix");
  m_diffuse = uniformLocation(m_program, "uDiffuse");
  m_emissive = uniformLocation(m_program, "uEmissive");
  m_hasTexture = uniformLocation(m_program, "uHasTexture");
  m_texture = uniformLocation(m_program, "uTexture");
  auto depth = buildProgram("mesh shadow shader", shaders::kMeshVertex, shaders::kDepthFragment);
  if (!depth) return makeError(depth.error());
  m_depthProgram = std::move(*depth);
  m_depthViewProjection = uniformLocation(m_depthProgram, "uViewProjection");
  m_depthModel = uniformLocation(m_depthProgram, "uModel");
  return Ok{};
}

MeshPass::GpuModel& MeshPass::upload(const std::shared_ptr<const Model>& model) {
  auto [it, inserted] = m_models.try_emplace(model.get());
  GpuModel& gpu = it->second;
  if (!inserted) return gpu;
  gpu.model = model;
  for (const ModelMesh& mesh : model->meshes) {
    GpuMesh g;
    g.vao = makeVertexArray();
    g.vertices = makeBuffer();
    g.indices = makeBuffer();
    g.indexCount = static_cast<GLsizei>(mesh.triangles.size() * 3);
    const std::vector<MeshGpuVertex> vertices = interleaveMesh(mesh);
    glBindVertexArray(g.vao.get());
    glBindBuffer(GL_ARRAY_BUFFER, g.vertices.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(MeshGpuVertex)), vertices.data(),
                 GL_STATIC_DRAW);
    vertexAttribute(shaders::kAttribMeshPosition, 3, offsetof(MeshGpuVertex, position));
    vertexAttribute(shaders::kAttribMeshNormal, 3, offsetof(MeshGpuVertex, normal));
    vertexAttribute(shaders::kAttribMeshUv, 2, offsetof(MeshGpuVertex, uv));
    vertexAttribute(shaders::kAttribMeshColor, 3, offsetof(MeshGpuVertex, color));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.indices.get());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.triangles.size() * sizeof(mesh.triangles[0])),
                 mesh.triangles.data(), GL_STATIC_DRAW);
    gpu.meshes.push_back(std::move(g));
  }
  glBindVertexArray(0);
  for (const ModelImage& image : model->images) {
    GlTexture texture = makeTexture();
    glBindTexture(GL_TEXTURE_2D, texture.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Texture colours are sRGB; the GPU linearises them when sampling.
    glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 image.rgba.data());
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    gpu.textures.push_back(std::move(texture));
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  return gpu;
}

bool MeshPass::ready(const std::vector<ModelInstance>& instances) {
  if (instances.empty()) return false;
  if (!m_initialised) {
    m_initialised = true;
    if (Status s = init(); !s) m_error = s.error();
  }
  if (!m_program.get() || !m_depthProgram.get()) return false;
  for (const ModelInstance& instance : instances) {
    if (instance.model) upload(instance.model);
  }
  return true;
}

void MeshPass::drawDepth(const std::vector<ModelInstance>& instances, const Eigen::Matrix4f& lightViewProjection) {
  if (!ready(instances)) return;
  MeshStats ignored;
  buildMeshDrawList(instances, lightViewProjection, m_depthDraws, ignored);
  if (m_depthDraws.empty()) return;
  glUseProgram(m_depthProgram.get());
  glUniformMatrix4fv(m_depthViewProjection, 1, GL_FALSE, lightViewProjection.data());
  for (const MeshDraw& d : m_depthDraws) {
    glUniformMatrix4fv(m_depthModel, 1, GL_FALSE, d.toWorld.data());
    const GpuMesh& mesh = m_models.at(d.model).meshes[d.mesh];
    glBindVertexArray(mesh.vao.get());
    glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
}

void MeshPass::draw(const std::vector<ModelInstance>& instances, const FrameView& view,
                    const Environment& environment, MeshStats& stats) {
  // Free models nobody but this cache holds any more.
  for (auto it = m_models.begin(); it != m_models.end();) {
    it = it->second.model.use_count() == 1 ? m_models.erase(it) : std::next(it);
  }
  stats = MeshStats{};
  stats.modelsResident = static_cast<int>(m_models.size());
  if (!ready(instances)) return;
  stats.modelsResident = static_cast<int>(m_models.size());
  buildMeshDrawList(instances, view.viewProjection, m_draws, stats);
  if (m_draws.empty()) return;

  glUseProgram(m_program.get());
  m_lit.apply(view, environment);
  glUniform1i(m_texture, 0);
  glActiveTexture(GL_TEXTURE0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // Model files disagree on winding (3DS exports often mix it), so meshes are
  // two-sided; the fragment shader turns back-facing normals round.
  glDisable(GL_CULL_FACE);
  const MeshDraw* previous = nullptr;
  for (const MeshDraw& d : m_draws) {
    const GpuModel& gpu = m_models.at(d.model);
    const bool newMaterial = previous == nullptr || previous->model != d.model || previous->material != d.material ||
                             previous->tint != d.tint;
    if (newMaterial) {
      const ModelMaterial& material = d.model->materials[d.material];
      const Eigen::Vector3f diffuse = material.diffuse.cwiseProduct(d.tint);
      glUniform3fv(m_diffuse, 1, diffuse.data());
      glUniform3fv(m_emissive, 1, material.emissive.data());
      const bool textured = material.image >= 0 && material.image < static_cast<int>(gpu.textures.size());
      glUniform1i(m_hasTexture, textured ? 1 : 0);
      glBindTexture(GL_TEXTURE_2D, textured ? gpu.textures[material.image].get() : 0);
    }
    previous = &d;
    glUniformMatrix4fv(m_model, 1, GL_FALSE, d.toWorld.data());
    const Eigen::Matrix3f normalMatrix = d.toWorld.topLeftCorner<3, 3>().inverse().transpose();
    glUniformMatrix3fv(m_normalMatrix, 1, GL_FALSE, normalMatrix.data());
    const GpuMesh& mesh = gpu.meshes[d.mesh];
    glBindVertexArray(mesh.vao.get());
    glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace tumble::render
