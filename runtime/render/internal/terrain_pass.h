#pragma once
// Terrain drawing: per-chunk geomipmaps built lazily and cached on the GPU,
// culled per chunk against the view frustum and the fog, drawn front to back
// with per-block textures, bump detail and fog (see terrain_mesh.h for the
// geometry, shaders.cpp for the shading).
//
// Culling is done here, per chunk, rather than taken from the app's
// quad-tree: the renderer alone knows the final camera of the frame (after
// mouse input and clamping) and the fog distance, chunk boxes are computed
// once per revision, and a linear pass over 64 x 64 chunks (a 4097^2 map)
// costs a few microseconds, so a hierarchy would not pay for itself.
//
// Memory: nothing is created until the first frame with a terrain. A chunk's
// vertex buffer for a level is built only when that level is drawn; when the
// cache passes kTerrainResidentBudget, levels not drawn this frame are freed.
// So a 4097^2 map holds fine levels only near the eye, never the whole map.
#include <array>
#include <cstdint>
#include <vector>

#include "core/result.h"
#include "render/internal/camera_math.h"
#include "render/internal/environment.h"
#include "render/internal/gl_util.h"
#include "render/internal/lit_uniforms.h"
#include "render/internal/terrain_mesh.h"
#include "render/renderer.h"

namespace tumble::render {

inline constexpr std::size_t kTerrainResidentBudget = 96u << 20;  // bytes of chunk vertices

/// The terrain's ground textures (render/internal/terrain_textures.h) as one
/// sRGB texture array with mipmaps, repeating; generated on the call (a few
/// ms), so callers make it on first need. The terrain and textured planes
/// use it.
GlTexture makeGroundTextureArray();

class TerrainPass {
 public:
  /// Draws `surface`; fills `stats`. Creates the shader and textures on the
  /// first call, re-uploads when the surface's revision (or shape) changed.
  Status draw(const TerrainSurface& surface, const FrameView& view, const Environment& environment,
              float pixelsPerRadian, float lodPixels, bool detail, bool blend, TerrainStats& stats);
  /// Depth only into the bound shadow map: the chunks inside the light's box,
  /// each at the level draw gives it (the same rule, from the eye), so the
  /// ground's shadow depth matches the drawn ground.
  Status drawDepth(const TerrainSurface& surface, const Eigen::Matrix4f& lightViewProjection,
                   const Eigen::Vector3f& eye, float pixelsPerRadian, float lodPixels);

 private:
  struct ChunkLevel {
    GlVertexArray vao;
    GlBuffer vertices;
    int triangles = 0;
    std::size_t bytes = 0;
    std::uint64_t lastUsedFrame = 0;
  };
  struct Chunk {
    ChunkBounds bounds;
    std::array<ChunkLevel, kTerrainMaxLod + 1> levels;
  };
  struct IndexSet {
    int nx = 0, nz = 0, count = 0;
    GlBuffer buffer;
  };
  // Everything that, when changed, invalidates the uploaded data.
  struct SurfaceKey {
    int samplesX = 0, samplesZ = 0;
    float spacing_m = 0, heightScale_m = 0, baseHeight_m = 0, originX_m = 0, originZ_m = 0;
    const void* heights = nullptr;
    const void* textureIndex = nullptr;
    const void* bump = nullptr;
    std::uint64_t revision = 0;
    bool operator==(const SurfaceKey&) const = default;
  };
  struct Visible {
    int chunk;
    int lod;
    float distance_m;
  };

  Status init();
  /// Creates the GPU objects on the first call and resets when the surface changed.
  Status sync(const TerrainSurface& surface, TerrainStats& stats);
  void reset(const TerrainSurface& surface);
  /// Only the surface's dirty rectangle changed since the last sync: frees
  /// the touched chunks' levels (rebuilt when drawn), recomputes their
  /// bounds and re-uploads their blocks' materials.
  void updateDirty(const TerrainSurface& surface, TerrainStats& stats);
  void uploadMaterialRect(const TerrainSurface& surface, int bi0, int bj0, int bi1, int bj1);
  void uploadMaterials(const TerrainSurface& surface);
  ChunkLevel& ensureLevel(const TerrainSurface& surface, int chunk, int lod, TerrainStats& stats);
  const IndexSet& indexSet(int nx, int nz);
  void evictUnused();

  /// A terrain shader and its uniforms: the detailed one (per pixel light,
  /// bump detail, shadows) or the simple one (per vertex light).
  struct Program {
    GlProgram program;
    LitUniforms lit;
    GLint origin = -1, spacing = -1, blocks = -1, texturePerMetre = -1, layerCount = -1;
    GLint detailSlope = -1;  // -1 in the simple one
    GLint blend = -1;        // -1 in the simple one
  };
  static Result<Program> buildTerrainProgram(const char* name, const char* vertex, const char* fragment);

  bool m_initialised = false;
  Program m_detailed, m_simple;
  GlProgram m_depthProgram;
  GLint m_depthViewProjection = -1;
  GlTexture m_textures;  // 2D array, one layer per material
  GlTexture m_materials; // RG8UI, one texel per block

  bool m_hasSurface = false;
  SurfaceKey m_key;
  TerrainChunkGrid m_grid;
  std::vector<Chunk> m_chunks;
  std::vector<IndexSet> m_indexSets;  // one per chunk grid shape (few)
  std::vector<Visible> m_visible;
  std::vector<TerrainVertex> m_scratch;
  std::vector<std::uint8_t> m_materialScratch;
  std::uint64_t m_frame = 0;
  std::size_t m_residentBytes = 0;
  TerrainStats m_depthUploads;  // uploads drawDepth made, reported by the next draw
};

}  // namespace tumble::render
