#include "render/internal/shape_pass.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "render/internal/mesh_builder.h"
#include "render/internal/shaders.h"
#include "render/internal/terrain_pass.h"
#include "render/internal/terrain_textures.h"

namespace tumble::render {

namespace {

// Mesh resolution: smooth enough for a sphere filling a third of a 720p
// frame, cheap enough for a few hundred instances on a software rasteriser.
constexpr int kRoundSlices = 32;
constexpr int kSphereStacks = 16;
constexpr int kCapsuleStacksPerCap = 8;
constexpr float kMinSize_m = 1e-4f;
// Texture unit of the ground textures (0 is left to other passes, the
// shadow map has LitUniforms::kShadowUnit).
constexpr int kGroundUnit = 1;

std::size_t kindIndex(ShapeKind kind) { return static_cast<std::size_t>(kind); }

float safeSize(float size) { return std::isfinite(size) ? std::max(size, kMinSize_m) : kMinSize_m; }

MeshData meshFor(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::Box: return buildBoxMesh();
    case ShapeKind::Sphere: return buildSphereMesh(kRoundSlices, kSphereStacks);
    case ShapeKind::Capsule: return buildCapsuleMesh(kRoundSlices, kCapsuleStacksPerCap);
    case ShapeKind::Plane: return buildPlaneMesh();
    case ShapeKind::Cylinder: return buildCylinderMesh(kRoundSlices);
    case ShapeKind::ConvexMesh: break;  // drawn by ConvexMeshPass
  }
  return buildBoxMesh();
}

void instanceAttribute(GLuint location, GLint components, std::size_t offset) {
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, sizeof(ShapeInstance),
                        reinterpret_cast<const void*>(offset));
  glVertexAttribDivisor(location, 1);
}

// Points the bound vertex array's instance attributes at the bound instance
// buffer from instance `first` on (GL 3.3 has no base instance).
void instanceAttributesFrom(std::size_t first) {
  const std::size_t base = first * sizeof(ShapeInstance);
  instanceAttribute(shaders::kAttribInstancePosition, 3, base + offsetof(ShapeInstance, position));
  instanceAttribute(shaders::kAttribInstanceRotation, 4, base + offsetof(ShapeInstance, rotation));
  instanceAttribute(shaders::kAttribInstanceScale, 3, base + offsetof(ShapeInstance, scale));
  instanceAttribute(shaders::kAttribInstanceHalfHeight, 1, base + offsetof(ShapeInstance, halfHeight));
  instanceAttribute(shaders::kAttribInstanceColor, 3, base + offsetof(ShapeInstance, color));
}

void meshAttribute(GLuint location, GLint components, std::size_t offset) {
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                        reinterpret_cast<const void*>(offset));
}

}  // namespace

ShapeInstance makeInstance(const DrawShape& shape) {
  ShapeInstance instance{};
  Eigen::Quaternionf q = shape.orientation;
  // The shader assumes a unit quaternion; callers renormalise, but a
  // zero or NaN quaternion from a broken body must not blank the batch.
  const float norm = q.norm();
  q = (std::isfinite(norm) && norm > 1e-6f) ? Eigen::Quaternionf(q.coeffs() / norm)
                                            : Eigen::Quaternionf::Identity();
  for (int i = 0; i < 3; ++i) instance.position[i] = shape.position[i];
  instance.rotation[0] = q.x();
  instance.rotation[1] = q.y();
  instance.rotation[2] = q.z();
  instance.rotation[3] = q.w();
  instance.halfHeight = 0.0f;
  switch (shape.kind) {
    case ShapeKind::Box:
      for (int i = 0; i < 3; ++i) instance.scale[i] = safeSize(shape.halfExtents[i]);
      break;
    case ShapeKind::Sphere:
    case ShapeKind::Capsule: {
      const float r = safeSize(shape.radius_m);
      instance.scale[0] = instance.scale[1] = instance.scale[2] = r;
      if (shape.kind == ShapeKind::Capsule) {
        instance.halfHeight = std::isfinite(shape.halfHeight_m) ? std::max(shape.halfHeight_m, 0.0f)
                                                                : 0.0f;
      }
      break;
    }
    case ShapeKind::Cylinder:
      instance.scale[0] = instance.scale[2] = safeSize(shape.radius_m);
      instance.scale[1] = safeSize(shape.halfHeight_m);
      break;
    case ShapeKind::Plane:
      instance.scale[0] = instance.scale[2] = kPlaneHalfSize_m;
      instance.scale[1] = 1.0f;
      break;
    case ShapeKind::ConvexMesh:
      instance.scale[0] = instance.scale[1] = instance.scale[2] = 1.0f;
      break;
  }
  const float shade = shape.sleeping ? kSleepingShade : 1.0f;
  for (int i = 0; i < 3; ++i) instance.color[i] = std::clamp(shape.color[i], 0.0f, 1.0f) * shade;
  return instance;
}

Status ShapePass::init() {
  auto program = buildProgram("shape shader", shaders::kShapeVertex, shaders::kShapeFragment);
  if (!program) return makeError(program.error());
  m_program = std::move(*program);
  m_lit.locate(m_program);
  m_checker = uniformLocation(m_program, "uChecker");
  m_groundLayer = uniformLocation(m_program, "uGroundLayer");
  m_ground = uniformLocation(m_program, "uGround");
  m_groundPerMetre = uniformLocation(m_program, "uGroundPerMetre");
  auto depth = buildProgram("shape shadow shader", shaders::kShapeVertex, shaders::kDepthFragment);
  if (!depth) return makeError(depth.error());
  m_depthProgram = std::move(*depth);
  m_depthViewProjection = uniformLocation(m_depthProgram, "uViewProjection");

  for (ShapeKind kind : {ShapeKind::Box, ShapeKind::Sphere, ShapeKind::Capsule, ShapeKind::Plane, ShapeKind::Cylinder}) {
    Batch& batch = m_batches[kindIndex(kind)];
    const MeshData mesh = meshFor(kind);
    batch.vao = makeVertexArray();
    batch.vertices = makeBuffer();
    batch.indices = makeBuffer();
    batch.instances = makeBuffer();
    batch.indexCount = static_cast<GLsizei>(mesh.indices.size());
    glBindVertexArray(batch.vao.get());

    glBindBuffer(GL_ARRAY_BUFFER, batch.vertices.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(MeshVertex)),
                 mesh.vertices.data(), GL_STATIC_DRAW);
    meshAttribute(shaders::kAttribPosition, 3, offsetof(MeshVertex, position));
    meshAttribute(shaders::kAttribNormal, 3, offsetof(MeshVertex, normal));
    meshAttribute(shaders::kAttribCapOffset, 1, offsetof(MeshVertex, capOffset));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, batch.indices.get());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                 mesh.indices.data(), GL_STATIC_DRAW);

    glBindBuffer(GL_ARRAY_BUFFER, batch.instances.get());
    instanceAttributesFrom(0);
  }
  glBindVertexArray(0);
  return Ok{};
}

void ShapePass::prepare(const std::vector<DrawShape>& shapes) {
  for (Batch& batch : m_batches) batch.pending.clear();
  m_planeRuns.clear();
  std::vector<std::pair<int, ShapeInstance>>& planes = m_planes;
  planes.clear();
  for (const DrawShape& shape : shapes) {
    if (kindIndex(shape.kind) >= kKindCount) continue;  // ConvexMesh: ConvexMeshPass
    if (shape.kind == ShapeKind::Plane) {
      const bool textured = shape.groundTexture >= 0 && shape.groundTexture < kTerrainTextureCount;
      planes.emplace_back(textured ? shape.groundTexture : -1, makeInstance(shape));
      continue;
    }
    m_batches[kindIndex(shape.kind)].pending.push_back(makeInstance(shape));
  }
  std::stable_sort(planes.begin(), planes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  Batch& planeBatch = m_batches[kindIndex(ShapeKind::Plane)];
  for (std::size_t i = 0; i < planes.size(); ++i) {
    if (m_planeRuns.empty() || m_planeRuns.back().groundTexture != planes[i].first) m_planeRuns.push_back({planes[i].first, i, 0});
    ++m_planeRuns.back().count;
    planeBatch.pending.push_back(planes[i].second);
  }
  for (Batch& batch : m_batches) {
    if (batch.pending.empty()) continue;
    glBindBuffer(GL_ARRAY_BUFFER, batch.instances.get());
    // Re-specifying the whole store each frame lets the driver hand out fresh
    // memory instead of waiting for last frame's draw to finish reading it.
    glBufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(batch.pending.size() * sizeof(ShapeInstance)),
                 batch.pending.data(), GL_STREAM_DRAW);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void ShapePass::drawDepth(const Eigen::Matrix4f& lightViewProjection) const {
  glUseProgram(m_depthProgram.get());
  glUniformMatrix4fv(m_depthViewProjection, 1, GL_FALSE, lightViewProjection.data());
  for (std::size_t k = 0; k < kKindCount; ++k) {
    const Batch& batch = m_batches[k];
    if (batch.pending.empty() || k == kindIndex(ShapeKind::Plane)) continue;
    glBindVertexArray(batch.vao.get());
    glDrawElementsInstanced(GL_TRIANGLES, batch.indexCount, GL_UNSIGNED_INT, nullptr,
                            static_cast<GLsizei>(batch.pending.size()));
  }
  glBindVertexArray(0);
}

void ShapePass::draw(const FrameView& view, const Environment& environment) {
  glUseProgram(m_program.get());
  m_lit.apply(view, environment);

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glUniform1i(m_groundLayer, 0);
  for (std::size_t k = 0; k < kKindCount; ++k) {
    Batch& batch = m_batches[k];
    if (batch.pending.empty()) continue;
    glBindVertexArray(batch.vao.get());
    if (k != kindIndex(ShapeKind::Plane)) {
      glUniform1i(m_checker, 0);
      glDrawElementsInstanced(GL_TRIANGLES, batch.indexCount, GL_UNSIGNED_INT, nullptr,
                              static_cast<GLsizei>(batch.pending.size()));
      continue;
    }
    // Planes, a run per ground texture (the checkerboard first).
    glUniform1i(m_checker, 1);
    glBindBuffer(GL_ARRAY_BUFFER, batch.instances.get());
    for (const PlaneRun& run : m_planeRuns) {
      if (run.groundTexture >= 0) {
        if (!m_groundTextures.get()) m_groundTextures = makeGroundTextureArray();
        glActiveTexture(GL_TEXTURE0 + kGroundUnit);
        glBindTexture(GL_TEXTURE_2D_ARRAY, m_groundTextures.get());
        glActiveTexture(GL_TEXTURE0);
        glUniform1i(m_ground, kGroundUnit);
        glUniform1f(m_groundPerMetre, 1.0f / kTerrainTextureSize_m);
      }
      glUniform1i(m_groundLayer, run.groundTexture + 1);
      instanceAttributesFrom(run.first);
      glDrawElementsInstanced(GL_TRIANGLES, batch.indexCount, GL_UNSIGNED_INT, nullptr,
                              static_cast<GLsizei>(run.count));
    }
    instanceAttributesFrom(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
  }
  glBindVertexArray(0);
  glDisable(GL_CULL_FACE);
}

}  // namespace tumble::render
