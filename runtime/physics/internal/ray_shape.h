#pragma once
// A ray against one shape (queries/ray_cast.cpp): what World::rayCast and
// its kin use, and what continuous collision (ccd.cpp) sweeps a body's
// inner sphere with (the shape grown by the sphere's radius).
#include "physics/body.h"
#include "physics/mesh_shape.h"

namespace tumble::physics {

/// Ray origin + t * dir (dir unit), 0 <= t <= maxT, against `shape` placed at
/// (position, orientation) and grown by `inflate` (m; boxes and hulls keep
/// sharp corners). On a hit sets t and the unit surface normal there.
/// meshStats (optional) gathers the work done against triangle meshes.
bool rayShapeAt(const Shape& shape, const Vec3& position_m, const Quat& orientation, const Vec3& origin_m,
                const Vec3& dir, Real maxT_m, Real& t_m, Vec3& normal, Real inflate_m,
                MeshStats* meshStats = nullptr);

/// The same against a body's shape at its pose.
inline bool rayShape(const Body& b, const Vec3& origin_m, const Vec3& dir, Real maxT_m, Real& t_m, Vec3& normal,
                     Real inflate_m = 0, MeshStats* meshStats = nullptr) {
  return rayShapeAt(b.shape, b.position_m, b.orientation, origin_m, dir, maxT_m, t_m, normal, inflate_m, meshStats);
}

}  // namespace tumble::physics
