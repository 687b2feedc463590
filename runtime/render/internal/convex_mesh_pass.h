#pragma once
// Convex meshes (physics hulls, ShapeKind::ConvexMesh): flat shaded with the
// lit shape shader, one instanced draw per distinct mesh. Each mesh is
// uploaded once, keyed by ConvexMeshData::id, with its triangles' vertices
// duplicated so every triangle carries its own face normal (flat shading
// without a geometry shader). A mesh no shape has used for kEvictFrames
// frames is released, so spawning and removing hulls does not grow GPU
// memory without bound.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/result.h"
#include "render/internal/camera_math.h"
#include "render/internal/environment.h"
#include "render/internal/gl_util.h"
#include "render/internal/lit_uniforms.h"
#include "render/internal/shape_pass.h"
#include "render/renderer.h"

namespace tumble::render {

class ConvexMeshPass {
 public:
  static constexpr std::uint64_t kEvictFrames = 300;

  Status init();
  /// Collects and uploads this frame's instances (once per frame, before drawDepth and draw).
  void prepare(const std::vector<DrawShape>& shapes);
  /// Depth only into the bound shadow map.
  void drawDepth(const Eigen::Matrix4f& lightViewProjection) const;
  void draw(const FrameView& view, const Environment& environment);
  /// Meshes resident on the GPU (for tests).
  std::size_t residentMeshes() const { return m_meshes.size(); }

 private:
  struct Mesh {
    GlVertexArray vao;
    GlBuffer vertices, instances;
    GLsizei vertexCount = 0;
    std::vector<ShapeInstance> pending;
    std::uint64_t lastUsedFrame = 0;
  };
  Mesh upload(const ConvexMeshData& data);

  std::unordered_map<std::uint64_t, Mesh> m_meshes;
  GlProgram m_program, m_depthProgram;
  LitUniforms m_lit;
  GLint m_checker = -1, m_depthViewProjection = -1;
  std::uint64_t m_frame = 0;
  bool m_any = false;  // this frame has convex meshes
};

}  // namespace tumble::render
