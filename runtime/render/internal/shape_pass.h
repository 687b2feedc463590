#pragma once
// Lit shapes: one shared mesh per ShapeKind, drawn with one instanced call per
// kind. Per-instance data (position, rotation, scale, capsule half height,
// colour) is rebuilt from the snapshot each frame into vectors that keep
// their capacity, so a steady scene allocates nothing per frame.
#include <array>
#include <utility>
#include <vector>

#include "core/result.h"
#include "render/internal/camera_math.h"
#include "render/internal/environment.h"
#include "render/internal/gl_util.h"
#include "render/internal/lit_uniforms.h"
#include "render/renderer.h"

namespace tumble::render {

// Half size of the square drawn for an infinite Plane. Far enough that fog
// has fully swallowed the edge (see Environment::fogDensity_per_m).
inline constexpr float kPlaneHalfSize_m = 1000.0f;
// Sleeping bodies are drawn at this fraction of their colour.
inline constexpr float kSleepingShade = 0.6f;

struct ShapeInstance {
  float position[3];
  float rotation[4];  // x, y, z, w
  float scale[3];
  float halfHeight;
  float color[3];
};

/// Converts one DrawShape into the instance the shader expects; exposed for
/// tests. Non-finite or non-positive sizes are clamped to a tiny positive
/// size so one bad body cannot poison the normals of the whole batch.
ShapeInstance makeInstance(const DrawShape& shape);

class ShapePass {
 public:
  Status init();
  /// Collects this frame's instances per kind and uploads them (once per
  /// frame, before drawDepth and draw).
  void prepare(const std::vector<DrawShape>& shapes);
  /// Depth only into the bound shadow map (planes excluded: they only receive).
  void drawDepth(const Eigen::Matrix4f& lightViewProjection) const;
  void draw(const FrameView& view, const Environment& environment);

 private:
  static constexpr std::size_t kKindCount = 5;  // every ShapeKind before ConvexMesh
  struct Batch {
    GlVertexArray vao;
    GlBuffer vertices, indices, instances;
    GLsizei indexCount = 0;
    std::vector<ShapeInstance> pending;
  };
  std::array<Batch, kKindCount> m_batches;
  // Planes are sorted by ground texture; each run of one texture is one draw.
  struct PlaneRun {
    int groundTexture;  // -1: checkerboard
    std::size_t first, count;
  };
  std::vector<PlaneRun> m_planeRuns;
  std::vector<std::pair<int, ShapeInstance>> m_planes;  // this frame's planes by texture (kept for its capacity)
  GlTexture m_groundTextures;  // made when a plane first asks for a ground texture
  GlProgram m_program, m_depthProgram;
  LitUniforms m_lit;
  GLint m_checker = -1, m_groundLayer = -1, m_ground = -1, m_groundPerMetre = -1, m_depthViewProjection = -1;
};

}  // namespace tumble::render
