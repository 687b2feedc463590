#pragma once
// Terrain geometry on the CPU (no GL, tested on its own): the chunk grid,
// geomipmap vertex and index lists with skirts, the level-of-detail rule and
// chunk-versus-frustum culling.
//
// Geomipmapping. The map is cut into chunks of kTerrainChunkBlocks^2 blocks
// (the last row / column of chunks may be narrower). Level `lod` keeps every
// 2^lod-th sample of the chunk plus its last row and column, so neighbouring
// chunks always share their border positions whatever their levels. Where
// two levels meet, the finer chunk's border has samples the coarser one
// skips, and the two border polylines differ: a crack. Rather than stitching
// (index lists per neighbour combination, and the LOD of neighbours must
// differ by at most one), every chunk hangs a skirt: a vertical strip from
// its border down by more than any such difference can be. The skirt is
// hidden behind the neighbour's surface except exactly where a crack would
// show sky. Simple, works for any level difference, costs 8 n triangles on
// top of 2 n^2.
//
// Vertices are world positions plus a packed normal (central differences on
// the full-resolution grid, so shading does not jump when a chunk changes
// level and both sides of a chunk border agree). Index lists depend only on
// the vertex grid shape, so chunks of the same shape share one.
#include <array>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "render/renderer.h"

namespace tumble::render {

/// Coarsest level: one block per chunk side (2^6 = 64).
inline constexpr int kTerrainMaxLod = 6;
static_assert((1 << kTerrainMaxLod) == kTerrainChunkBlocks);

struct TerrainVertex {
  float position[3];     // m, world
  std::uint32_t normal;  // GL_INT_2_10_10_10_REV, signed normalised x, y, z
};
static_assert(sizeof(TerrainVertex) == 16);

/// Packs a unit vector as GL_INT_2_10_10_10_REV (x in the low 10 bits).
std::uint32_t packNormal(const Eigen::Vector3f& n);
Eigen::Vector3f unpackNormal(std::uint32_t packed);

/// The chunk grid of a surface.
struct TerrainChunkGrid {
  int chunksX = 0, chunksZ = 0;
  int blocksX = 0, blocksZ = 0;
};
TerrainChunkGrid chunkGrid(const TerrainSurface& surface);

/// Sample offsets (from the chunk's first sample) kept along one axis of a
/// chunk `blocks` wide at `lod`: 0, s, 2s, ... and always `blocks` itself.
std::vector<int> lodSampleOffsets(int blocks, int lod);

/// Vertices of chunk (cx, cz) at `lod`: the (nx x nz) grid row-major, then
/// the skirt: bottom copies of the border, in the order of skirtBorder().
void buildChunkVertices(const TerrainSurface& surface, int cx, int cz, int lod,
                        std::vector<TerrainVertex>& out);

/// Triangle list (counter-clockwise seen from above / from outside) for a
/// vertex grid of nx x nz plus skirt, as buildChunkVertices lays it out.
/// Blocks are cut along their p00-p11 diagonal, like the collision triangles.
std::vector<std::uint16_t> buildChunkIndices(int nx, int nz);
/// Triangles in that list: 2 (nx-1)(nz-1) surface + 4 per border segment.
int chunkTriangleCount(int nx, int nz);

/// World bounds of a chunk's surface (heights read from the samples).
struct ChunkBounds {
  Eigen::Vector3f min, max;
};
ChunkBounds chunkBounds(const TerrainSurface& surface, int cx, int cz);

/// Level for a chunk whose nearest point is `distance_m` from the eye: the
/// coarsest with blocks of 2^lod * spacing at most `lodPixels` pixels wide on
/// screen, where `pixelsPerRadian` = viewport height / (2 tan(fovY / 2)).
int chooseLod(float distance_m, float spacing_m, float pixelsPerRadian, float lodPixels);

/// Distance from a point to a box (0 inside).
float distanceToBox(const Eigen::Vector3f& p, const ChunkBounds& box);

/// The six planes (a, b, c, d; inside where a x + b y + c z + d >= 0) of an
/// OpenGL view-projection matrix (Gribb / Hartmann).
using FrustumPlanes = std::array<Eigen::Vector4f, 6>;
FrustumPlanes frustumPlanes(const Eigen::Matrix4f& viewProjection);
/// False only when the box is entirely outside one plane (conservative).
bool boxInFrustum(const FrustumPlanes& planes, const ChunkBounds& box);

}  // namespace tumble::render
