#include "render/internal/terrain_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::render {

namespace {

int packComponent(float v) {
  return static_cast<int>(std::lround(std::clamp(v, -1.0f, 1.0f) * 511.0f));
}

float unpackComponent(std::uint32_t bits) {
  int v = static_cast<int>(bits & 0x3ffu);
  if (v >= 512) v -= 1024;  // sign-extend 10 bits
  return std::max(static_cast<float>(v) / 511.0f, -1.0f);
}

float sampleHeight_m(const TerrainSurface& s, int i, int j) {
  return s.baseHeight_m + static_cast<float>(s.heights[static_cast<std::size_t>(j) * s.samplesX + i]) *
                              s.heightScale_m;
}

// Central differences on the full grid (one-sided at the map border).
Eigen::Vector3f sampleNormal(const TerrainSurface& s, int i, int j) {
  const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, s.samplesX - 1);
  const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, s.samplesZ - 1);
  const float dhdx = (sampleHeight_m(s, i1, j) - sampleHeight_m(s, i0, j)) /
                     (static_cast<float>(i1 - i0) * s.spacing_m);
  const float dhdz = (sampleHeight_m(s, i, j1) - sampleHeight_m(s, i, j0)) /
                     (static_cast<float>(j1 - j0) * s.spacing_m);
  return Eigen::Vector3f(-dhdx, 1.0f, -dhdz).normalized();
}

// Grid index of the k-th skirt vertex's top vertex, and the outward
// direction of its edge. Edges: first row (-Z), last row (+Z), first column
// (-X), last column (+X); each lists its vertices in increasing order.
struct SkirtEdge {
  int first, count, stride;  // grid indices first, first + stride, ...
  Eigen::Vector3f outward;
};
std::array<SkirtEdge, 4> skirtEdges(int nx, int nz) {
  return {{{0, nx, 1, -Eigen::Vector3f::UnitZ()},
           {(nz - 1) * nx, nx, 1, Eigen::Vector3f::UnitZ()},
           {0, nz, nx, -Eigen::Vector3f::UnitX()},
           {nx - 1, nz, nx, Eigen::Vector3f::UnitX()}}};
}

}  // namespace

std::uint32_t packNormal(const Eigen::Vector3f& n) {
  const auto bits = [](int v) { return static_cast<std::uint32_t>(v) & 0x3ffu; };
  return bits(packComponent(n.x())) | (bits(packComponent(n.y())) << 10) |
         (bits(packComponent(n.z())) << 20);
}

Eigen::Vector3f unpackNormal(std::uint32_t packed) {
  return {unpackComponent(packed), unpackComponent(packed >> 10), unpackComponent(packed >> 20)};
}

TerrainChunkGrid chunkGrid(const TerrainSurface& surface) {
  TerrainChunkGrid grid;
  if (surface.samplesX < 2 || surface.samplesZ < 2 || surface.heights == nullptr) return grid;
  grid.blocksX = surface.samplesX - 1;
  grid.blocksZ = surface.samplesZ - 1;
  grid.chunksX = (grid.blocksX + kTerrainChunkBlocks - 1) / kTerrainChunkBlocks;
  grid.chunksZ = (grid.blocksZ + kTerrainChunkBlocks - 1) / kTerrainChunkBlocks;
  return grid;
}

std::vector<int> lodSampleOffsets(int blocks, int lod) {
  const int step = 1 << lod;
  std::vector<int> offsets;
  for (int k = 0; k < blocks; k += step) offsets.push_back(k);
  offsets.push_back(blocks);
  return offsets;
}

void buildChunkVertices(const TerrainSurface& surface, int cx, int cz, int lod,
                        std::vector<TerrainVertex>& out) {
  const TerrainChunkGrid grid = chunkGrid(surface);
  const int i0 = cx * kTerrainChunkBlocks, j0 = cz * kTerrainChunkBlocks;
  const std::vector<int> xs = lodSampleOffsets(std::min(kTerrainChunkBlocks, grid.blocksX - i0), lod);
  const std::vector<int> zs = lodSampleOffsets(std::min(kTerrainChunkBlocks, grid.blocksZ - j0), lod);
  const int nx = static_cast<int>(xs.size()), nz = static_cast<int>(zs.size());

  out.clear();
  out.reserve(static_cast<std::size_t>(nx * nz + 2 * (nx + nz)));
  for (int b : zs) {
    for (int a : xs) {
      const int i = i0 + a, j = j0 + b;
      TerrainVertex v;
      v.position[0] = surface.originX_m + static_cast<float>(i) * surface.spacing_m;
      v.position[1] = sampleHeight_m(surface, i, j);
      v.position[2] = surface.originZ_m + static_cast<float>(j) * surface.spacing_m;
      v.normal = packNormal(sampleNormal(surface, i, j));
      out.push_back(v);
    }
  }
  // Skirt depth: the border polylines of any two levels both lie inside the
  // chunk's height range, so hanging below its minimum covers every crack.
  const ChunkBounds bounds = chunkBounds(surface, cx, cz);
  const float bottom = bounds.min.y() - 0.5f * surface.spacing_m - 0.01f;
  for (const SkirtEdge& edge : skirtEdges(nx, nz)) {
    for (int k = 0; k < edge.count; ++k) {
      TerrainVertex v = out[static_cast<std::size_t>(edge.first + k * edge.stride)];
      v.position[1] = bottom;
      out.push_back(v);
    }
  }
}

std::vector<std::uint16_t> buildChunkIndices(int nx, int nz) {
  std::vector<std::uint16_t> indices;
  indices.reserve(static_cast<std::size_t>(chunkTriangleCount(nx, nz)) * 3);
  const auto add = [&](int a, int b, int c) {
    indices.push_back(static_cast<std::uint16_t>(a));
    indices.push_back(static_cast<std::uint16_t>(b));
    indices.push_back(static_cast<std::uint16_t>(c));
  };
  // Surface: (p00, p11, p10) and (p00, p01, p11), counter-clockwise from +Y.
  for (int b = 0; b + 1 < nz; ++b) {
    for (int a = 0; a + 1 < nx; ++a) {
      const int p00 = b * nx + a, p10 = p00 + 1, p01 = p00 + nx, p11 = p01 + 1;
      add(p00, p11, p10);
      add(p00, p01, p11);
    }
  }
  // Skirts: the winding is picked from the flat layout (grid index a, b at
  // x = a, z = b; bottom one unit lower) so the face looks outwards.
  const auto flat = [nx](int gridIndex, float y) {
    return Eigen::Vector3f(static_cast<float>(gridIndex % nx), y, static_cast<float>(gridIndex / nx));
  };
  int skirtBase = nx * nz;
  for (const SkirtEdge& edge : skirtEdges(nx, nz)) {
    for (int k = 0; k + 1 < edge.count; ++k) {
      const int t0 = edge.first + k * edge.stride, t1 = t0 + edge.stride;
      const int b0 = skirtBase + k, b1 = b0 + 1;
      const Eigen::Vector3f n = (flat(t1, 0) - flat(t0, 0)).cross(flat(t0, -1) - flat(t0, 0));
      if (n.dot(edge.outward) > 0) {
        add(t0, t1, b0);
        add(t1, b1, b0);
      } else {
        add(t0, b0, t1);
        add(t1, b0, b1);
      }
    }
    skirtBase += edge.count;
  }
  return indices;
}

int chunkTriangleCount(int nx, int nz) {
  return 2 * (nx - 1) * (nz - 1) + 4 * (nx - 1) + 4 * (nz - 1);
}

ChunkBounds chunkBounds(const TerrainSurface& surface, int cx, int cz) {
  const TerrainChunkGrid grid = chunkGrid(surface);
  const int i0 = cx * kTerrainChunkBlocks, j0 = cz * kTerrainChunkBlocks;
  const int i1 = std::min(i0 + kTerrainChunkBlocks, grid.blocksX);
  const int j1 = std::min(j0 + kTerrainChunkBlocks, grid.blocksZ);
  std::uint16_t lo = std::numeric_limits<std::uint16_t>::max(), hi = 0;
  for (int j = j0; j <= j1; ++j) {
    const std::uint16_t* row = surface.heights + static_cast<std::size_t>(j) * surface.samplesX;
    for (int i = i0; i <= i1; ++i) {
      lo = std::min(lo, row[i]);
      hi = std::max(hi, row[i]);
    }
  }
  // A negative height scale flips which sample value is lowest.
  const float ya = surface.baseHeight_m + static_cast<float>(lo) * surface.heightScale_m;
  const float yb = surface.baseHeight_m + static_cast<float>(hi) * surface.heightScale_m;
  ChunkBounds box;
  box.min = {surface.originX_m + static_cast<float>(i0) * surface.spacing_m, std::min(ya, yb),
             surface.originZ_m + static_cast<float>(j0) * surface.spacing_m};
  box.max = {surface.originX_m + static_cast<float>(i1) * surface.spacing_m, std::max(ya, yb),
             surface.originZ_m + static_cast<float>(j1) * surface.spacing_m};
  return box;
}

int chooseLod(float distance_m, float spacing_m, float pixelsPerRadian, float lodPixels) {
  // A block of 2^lod * spacing seen at distance d spans about
  // 2^lod * spacing / d * pixelsPerRadian pixels (at most: seen face-on).
  const float denominator = spacing_m * pixelsPerRadian;
  if (!(denominator > 0) || !(distance_m > 0) || !(lodPixels > 0)) return 0;
  const float maxStep = lodPixels * distance_m / denominator;
  if (!(maxStep >= 2.0f)) return 0;
  const int lod = static_cast<int>(std::floor(std::log2(maxStep)));
  return std::clamp(lod, 0, kTerrainMaxLod);
}

float distanceToBox(const Eigen::Vector3f& p, const ChunkBounds& box) {
  const Eigen::Vector3f nearest = p.cwiseMax(box.min).cwiseMin(box.max);
  return (p - nearest).norm();
}

FrustumPlanes frustumPlanes(const Eigen::Matrix4f& m) {
  const Eigen::Vector4f r0 = m.row(0).transpose(), r1 = m.row(1).transpose();
  const Eigen::Vector4f r2 = m.row(2).transpose(), r3 = m.row(3).transpose();
  return {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};
}

bool boxInFrustum(const FrustumPlanes& planes, const ChunkBounds& box) {
  for (const Eigen::Vector4f& plane : planes) {
    // The box corner furthest along the plane normal.
    const Eigen::Vector3f p(plane.x() >= 0 ? box.max.x() : box.min.x(),
                            plane.y() >= 0 ? box.max.y() : box.min.y(),
                            plane.z() >= 0 ? box.max.z() : box.min.z());
    if (plane.head<3>().dot(p) + plane.w() < 0) return false;
  }
  return true;
}

}  // namespace tumble::render
