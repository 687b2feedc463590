#pragma once
// Contacts and rays against static triangle meshes (mesh_collision.cpp
// explains the method; mesh_shape.h the data and the one-sided choice).
#include <vector>

#include "physics/body.h"
#include "physics/internal/manifold.h"
#include "physics/mesh_shape.h"

namespace tumble::physics {

/// At most this many manifolds (distinct contact normals) per convex piece
/// against one mesh: a compound gets up to this many per child.
constexpr int kMaxMeshManifolds = 4;

/// Every manifold between a and b, one of which has a mesh shape (the other
/// a sphere, box, capsule, hull or compound; a plane or another mesh gives
/// none). Normals from a to b as everywhere; a compound's manifolds carry
/// its child index (childA or childB), the mesh side's child index is 0.
/// useTree = false tests every triangle's box (the brute force the
/// benchmark compares with). stats (optional) gathers the work done.
/// Appends to out; returns the number appended.
int collideMeshPair(const Body& a, const Body& b, Real margin_m, std::vector<Manifold>& out, MeshStats* stats,
                    bool useTree = true);

/// The deepest overlap of a sphere (centre, radius) with the front of a mesh
/// placed at (position, orientation): unit normal out of the mesh and depth
/// (m, > 0). Seam contacts are dropped as for bodies. For particles of
/// ropes and cloth (deformable.cpp).
bool sphereMeshContact(const Vec3& centre_m, Real radius_m, const Vec3& position_m, const Quat& orientation,
                       const MeshShape& mesh, Vec3* normal, Real* depth_m);

/// Ray origin + t * dir (dir unit), 0 <= t <= maxT, against the front faces
/// of a mesh placed at (position, orientation), each face pushed out along
/// its normal by inflate_m (continuous collision of a body of that radius).
/// The tree's boxes skip subtrees the ray misses.
bool rayMesh(const Vec3& origin_m, const Vec3& dir, Real maxT_m, const Vec3& position_m, const Quat& orientation,
             const MeshShape& mesh, Real inflate_m, Real& t_m, Vec3& normal, MeshStats* stats = nullptr);

}  // namespace tumble::physics
