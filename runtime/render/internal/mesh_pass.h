#pragma once
// Textured, lit meshes of loaded models (model.h). Each model is uploaded on
// first sight: one vertex / index buffer per mesh, one sRGB texture with
// mipmaps per image. Per frame the draw list (mesh_draw_list.h) culls with
// each model's node tree and sorts by material; the pass binds a material
// only when it changes. Models that only the pass still holds are freed at
// the start of the next frame.
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/result.h"
#include "render/internal/camera_math.h"
#include "render/internal/environment.h"
#include "render/internal/gl_util.h"
#include "render/internal/lit_uniforms.h"
#include "render/internal/mesh_draw_list.h"
#include "render/renderer.h"

namespace tumble::render {

/// What one vertex holds on the GPU (44 bytes).
struct MeshGpuVertex {
  float position[3];
  float normal[3];
  float uv[2];
  float color[3];  // linear vertex colour, white when the mesh has none
};
/// Interleaves a mesh's attributes as the mesh shader reads them.
std::vector<MeshGpuVertex> interleaveMesh(const ModelMesh& mesh);

class MeshPass {
 public:
  /// Compiles the shader lazily: a scene without models costs nothing.
  void draw(const std::vector<ModelInstance>& instances, const FrameView& view, const Environment& environment,
            MeshStats& stats);
  /// Depth only into the bound shadow map: every instance's meshes inside
  /// the light's box (uploads models seen for the first time).
  void drawDepth(const std::vector<ModelInstance>& instances, const Eigen::Matrix4f& lightViewProjection);
  /// The first GL or upload problem, reported once by the renderer.
  const std::string& lastError() const { return m_error; }

 private:
  struct GpuMesh {
    GlVertexArray vao;
    GlBuffer vertices, indices;
    GLsizei indexCount = 0;
  };
  struct GpuModel {
    std::shared_ptr<const Model> model;  // keeps the Model (and the cache key) alive
    std::vector<GpuMesh> meshes;
    std::vector<GlTexture> textures;     // by Model::images index
  };
  Status init();
  GpuModel& upload(const std::shared_ptr<const Model>& model);

  bool m_initialised = false;
  bool ready(const std::vector<ModelInstance>& instances);  // lazy init and uploads; false: cannot draw
  GlProgram m_program, m_depthProgram;
  LitUniforms m_lit;
  GLint m_depthViewProjection = -1, m_depthModel = -1;
  std::vector<MeshDraw> m_depthDraws;
  GLint m_model = -1, m_normalMatrix = -1, m_diffuse = -1, m_emissive = -1, m_hasTexture = -1, m_texture = -1;
  std::unordered_map<const Model*, GpuModel> m_models;
  std::vector<MeshDraw> m_draws;  // reused every frame
  std::string m_error;
};

}  // namespace tumble::render
