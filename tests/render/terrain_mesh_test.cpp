// Terrain geometry without GL: geomipmap layouts, skirts that face outwards
// and hang low enough, normals from central differences, the LOD rule,
// frustum culling and the generated textures.
#include <gtest/gtest.h>

#include "core/hash.h"

#include <cmath>
#include <set>
#include <vector>

#include "render/internal/camera_math.h"
#include "render/internal/terrain_mesh.h"
#include "render/internal/terrain_textures.h"

namespace tumble::render {
namespace {

struct Field {
  std::vector<std::uint16_t> heights;
  TerrainSurface surface;
  Field(int nx, int nz, auto&& height) : heights(static_cast<std::size_t>(nx * nz)) {
    for (int j = 0; j < nz; ++j)
      for (int i = 0; i < nx; ++i) heights[static_cast<std::size_t>(j * nx + i)] = height(i, j);
    surface.samplesX = nx;
    surface.samplesZ = nz;
    surface.heights = heights.data();
  }
};

Eigen::Vector3f pos(const TerrainVertex& v) { return {v.position[0], v.position[1], v.position[2]}; }

TEST(TerrainMesh, LevelsKeepEveryStepAndTheChunkBorder) {
  EXPECT_EQ(lodSampleOffsets(64, 0).size(), 65u);
  EXPECT_EQ(lodSampleOffsets(64, 3), (std::vector<int>{0, 8, 16, 24, 32, 40, 48, 56, 64}));
  EXPECT_EQ(lodSampleOffsets(64, 6), (std::vector<int>{0, 64}));
  // A narrower last chunk still ends on the map border.
  EXPECT_EQ(lodSampleOffsets(10, 2), (std::vector<int>{0, 4, 8, 10}));
}

TEST(TerrainMesh, ChunkGridCoversTheMapWithPartialLastChunks) {
  Field f(200, 65, [](int, int) { return std::uint16_t(0); });
  const TerrainChunkGrid grid = chunkGrid(f.surface);
  EXPECT_EQ(grid.chunksX, 4);  // 199 blocks: 64 + 64 + 64 + 7
  EXPECT_EQ(grid.chunksZ, 1);
  std::vector<TerrainVertex> v;
  buildChunkVertices(f.surface, 3, 0, 0, v);
  EXPECT_EQ(v.size(), std::size_t(8 * 65 + 2 * (8 + 65)));
  EXPECT_FLOAT_EQ(v[7].position[0], 199.0f);  // last vertex of the first row: the map's edge
}

TEST(TerrainMesh, TriangleCountFallsFourfoldPerLevel) {
  // Surface 2 n^2 plus skirts 8 n for n blocks per side at that level.
  EXPECT_EQ(chunkTriangleCount(65, 65), 2 * 64 * 64 + 8 * 64);
  EXPECT_EQ(chunkTriangleCount(33, 33), 2 * 32 * 32 + 8 * 32);
  EXPECT_EQ(chunkTriangleCount(2, 2), 2 + 8);
  EXPECT_EQ(buildChunkIndices(17, 9).size(), std::size_t(3 * chunkTriangleCount(17, 9)));
}

TEST(TerrainMesh, SurfaceFacesUpAndSkirtsFaceOutwardsBelowTheChunk) {
  Field f(65, 65, [](int i, int j) { return std::uint16_t(100 * ((i * 7 + j * 3) % 11)); });
  for (int lod : {0, 2, 6}) {
    std::vector<TerrainVertex> v;
    buildChunkVertices(f.surface, 0, 0, lod, v);
    const int n = static_cast<int>(lodSampleOffsets(64, lod).size());
    const std::vector<std::uint16_t> idx = buildChunkIndices(n, n);
    const Eigen::Vector3f centre(32, 0, 32);
    const int surfaceTriangles = 2 * (n - 1) * (n - 1);
    const float minHeight = 0.0f;  // values start at 0
    for (std::size_t t = 0; t < idx.size() / 3; ++t) {
      const Eigen::Vector3f a = pos(v[idx[3 * t]]), b = pos(v[idx[3 * t + 1]]), c = pos(v[idx[3 * t + 2]]);
      const Eigen::Vector3f normal = (b - a).cross(c - a);
      if (static_cast<int>(t) < surfaceTriangles) {
        EXPECT_GT(normal.y(), 0) << "lod " << lod << " triangle " << t;
      } else {
        Eigen::Vector3f out = (a + b + c) / 3 - centre;
        out.y() = 0;
        EXPECT_GT(normal.dot(out), 0) << "skirt faces inwards: lod " << lod << " triangle " << t;
        EXPECT_LT(std::min({a.y(), b.y(), c.y()}), minHeight) << "skirt does not reach below the chunk";
      }
    }
  }
}

TEST(TerrainMesh, NormalsOfARampMatchItsSlope) {
  // y = 0.5 x (value * 0.01 m, 1 m spacing): normal (-0.5, 1, 0) normalised.
  Field f(65, 65, [](int i, int) { return std::uint16_t(50 * i); });
  std::vector<TerrainVertex> v;
  buildChunkVertices(f.surface, 0, 0, 0, v);
  const Eigen::Vector3f expected = Eigen::Vector3f(-0.5f, 1, 0).normalized();
  for (std::size_t k : {std::size_t(0), std::size_t(33 * 65 + 20), std::size_t(64 * 65 + 64)}) {
    EXPECT_LT((unpackNormal(v[k].normal) - expected).norm(), 0.01f) << "vertex " << k;
    EXPECT_NEAR(v[k].position[1], 0.5f * v[k].position[0], 1e-4f);
  }
}

TEST(TerrainMesh, ChunkBoundsHoldEveryHeight) {
  Field f(130, 70, [](int i, int j) { return std::uint16_t((i * 37 + j * 101) % 5000); });
  f.surface.baseHeight_m = -5;
  f.surface.originX_m = 10;
  const ChunkBounds b = chunkBounds(f.surface, 1, 0);
  EXPECT_FLOAT_EQ(b.min.x(), 74.0f);
  EXPECT_FLOAT_EQ(b.max.x(), 138.0f);
  std::vector<TerrainVertex> v;
  buildChunkVertices(f.surface, 1, 0, 0, v);
  const int surfaceVertices = 65 * 65;
  for (int k = 0; k < surfaceVertices; ++k) {
    EXPECT_GE(v[k].position[1], b.min.y());
    EXPECT_LE(v[k].position[1], b.max.y());
  }
}

TEST(TerrainMesh, FarChunksGetCoarserLevels) {
  const float ppr = 720.0f / (2.0f * std::tan(0.5f));
  EXPECT_EQ(chooseLod(0.0f, 1.0f, ppr, 8.0f), 0);
  EXPECT_EQ(chooseLod(50.0f, 1.0f, ppr, 8.0f), 0);
  int previous = 0;
  for (float d = 10; d < 20000; d *= 1.3f) {
    const int lod = chooseLod(d, 1.0f, ppr, 8.0f);
    EXPECT_GE(lod, previous);
    // A coarser level's blocks stay within the pixel budget (level 0 is as
    // fine as the map gets).
    if (lod > 0) {
      EXPECT_LE(float(1 << lod) * ppr / d, 8.0f + 1e-3f);
    }
    previous = lod;
  }
  EXPECT_EQ(previous, kTerrainMaxLod);
}

TEST(TerrainMesh, BoxBehindTheCameraIsCulledBoxInFrontIsNot) {
  Camera camera;
  camera.target = {0, 0, 0};
  camera.yaw_rad = 0;
  camera.pitch_rad = 0.2f;
  const FrameView view = makeFrameView(camera, 16.0f / 9.0f);
  const FrustumPlanes planes = frustumPlanes(view.viewProjection);
  const auto around = [](Eigen::Vector3f c) {
    return ChunkBounds{c - Eigen::Vector3f::Constant(2), c + Eigen::Vector3f::Constant(2)};
  };
  EXPECT_TRUE(boxInFrustum(planes, around(camera.target)));
  EXPECT_FALSE(boxInFrustum(planes, around(view.eye - 20.0f * view.forward)));
  EXPECT_FALSE(boxInFrustum(planes, around(view.eye + 30.0f * view.forward + 200.0f * view.right)));
  EXPECT_FALSE(boxInFrustum(planes, around(view.eye + 3000.0f * view.forward)));  // beyond the far plane
  EXPECT_FLOAT_EQ(distanceToBox({5, 0, 0}, around({0, 0, 0})), 3.0f);
  EXPECT_FLOAT_EQ(distanceToBox({1, 0, 0}, around({0, 0, 0})), 0.0f);
}

TEST(TerrainTextures, DeterministicTileableAndDistinct) {
  // Distinct textures, compared by a hash of their bytes.
  std::set<std::uint64_t> distinct;
  for (int layer = 0; layer < kTerrainTextureCount; ++layer) {
    const std::vector<std::uint8_t> a = generateTerrainTexture(layer, 64);
    EXPECT_EQ(a, generateTerrainTexture(layer, 64)) << terrainTextureName(layer);
    Hasher h;
    h.bytes(a.data(), a.size());
    distinct.insert(h.digest());
    // Tileable: the jump across the wrap is no bigger than between
    // neighbouring texels inside (average over a row).
    double wrapJump = 0, innerJump = 0;
    for (int y = 0; y < 64; ++y) {
      const auto at = [&](int x) { return int(a[std::size_t((y * 64 + x) * 4 + 1)]); };
      wrapJump += std::abs(at(63) - at(0));
      innerJump += std::abs(at(31) - at(32));
    }
    EXPECT_LT(wrapJump, 2.0 * innerJump + 64 * 4) << terrainTextureName(layer);
  }
  EXPECT_EQ(distinct.size(), std::size_t(kTerrainTextureCount));
  // Grass is green, sand is yellow, snow is bright.
  const Eigen::Vector3f grass = terrainTextureMeanColor(0), sand = terrainTextureMeanColor(2);
  EXPECT_GT(grass.y(), grass.x());
  EXPECT_GT(sand.x(), sand.z() + 0.1f);
  EXPECT_GT(terrainTextureMeanColor(4).minCoeff(), 0.7f);
}

}  // namespace
}  // namespace tumble::render
