#pragma once
// Small plain-data types shared by the terrain queries.
#include <array>
#include <cstdint>

#include "core/math.h"

namespace tumble::terrain {

/// Axis-aligned box in world space, metres.
struct Aabb {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  bool overlaps(const Aabb& o) const {
    return min.x() <= o.max.x() && o.min.x() <= max.x() && min.y() <= o.max.y() && o.min.y() <= max.y() &&
           min.z() <= o.max.z() && o.min.z() <= max.z();
  }
};

/// One terrain triangle in world space. Vertices wind counter-clockwise seen
/// from above (+Y), so (v1 - v0) x (v2 - v0) points along `normal` (up).
struct TerrainTriangle {
  std::array<Vec3, 3> vertices;
  Vec3 normal;                ///< unit face normal, y > 0
  std::uint32_t block = 0;    ///< bj * blocksX + bi
  std::uint8_t half = 0;      ///< 0: the u >= v half, 1: the u < v half (see terrain.h)
};

struct RayHit {
  Real distance_m = 0;       ///< along the normalised ray direction
  Vec3 point = Vec3::Zero(); ///< world-space hit point
  Vec3 normal = Vec3::UnitY(); ///< face normal of the triangle hit (always the upward face)
  std::uint32_t block = 0;
  std::uint8_t half = 0;
};

/// Six planes (a, b, c, d): a point p is inside when a*x + b*y + c*z + d >= 0
/// for every plane. Normals need not be unit length for culling.
struct Frustum {
  std::array<Vec4, 6> planes;

  /// Planes of an OpenGL-convention view-projection matrix (clip space
  /// -w <= x, y, z <= w), Gribb & Hartmann's method; normalised.
  static Frustum fromViewProjection(const Eigen::Matrix<Real, 4, 4>& viewProjection);
};

/// Memory held by a loaded terrain, from the containers' capacities.
struct TerrainMemory {
  std::size_t heights = 0;        ///< bytes of the uint16 sample array
  std::size_t tree = 0;           ///< bytes of the quad-tree node array and level tables
  std::size_t materials = 0;      ///< bytes of the material layers (0 until created)
  std::size_t staticObjects = 0;  ///< approximate bytes of the static-object registry
};

}  // namespace tumble::terrain
