#pragma once
// Contacts and rays for convex hulls (hull_collision.cpp explains the method).
// Boxes take part as hulls when they meet one (boxPolytope).
#include <cstdint>

#include "physics/convex_hull.h"
#include "physics/internal/manifold.h"

namespace tumble::physics {

struct Pose {
  Vec3 p = Vec3::Zero();  ///< m, world
  Mat3 R = Mat3::Identity();
};

/// The unit-cube hull scaled to half extents h (topology shared, no allocation).
const ConvexHull& unitCubeHull();

/// Polytope against polytope (hull or box: a box passes unitCubeHull() and
/// its half extents as scale, a hull Vec3::Ones()). Normal from a to b.
int collidePolytopes(const Pose& A, const ConvexHull& a, const Vec3& scaleA, const Pose& B, const ConvexHull& b,
                     const Vec3& scaleB, Real margin, Manifold& m);

/// Signed distance (m, negative inside) from world point p to the hull's
/// surface, the closest surface point and the outward unit normal there.
Real pointHullDistance(const Vec3& p, const Pose& hullPose, const ConvexHull& h, Vec3& closest, Vec3& normal);

/// Sphere (as a) against hull (as b).
int collideSphereHull(const Vec3& c, Real r, const Pose& B, const ConvexHull& h, Real margin, Manifold& m,
                      std::uint32_t id);
/// Capsule segment p0-p1 of radius r (as a) against hull (as b).
int collideCapsuleHull(const Vec3& p0, const Vec3& p1, Real r, const Pose& B, const ConvexHull& h, Real margin,
                       Manifold& m);
/// Hull (as a) against the plane n.x = n.planePoint (as b).
int collideHullPlane(const Pose& A, const ConvexHull& h, const Vec3& planePoint, const Vec3& planeNormal, Real margin,
                     Manifold& m);

/// Ray origin + t dir (dir unit), 0 <= t <= maxT, against the hull grown by
/// `inflate` (planes pushed out; corners stay sharp). Starting inside gives
/// t = 0 and the normal -dir.
bool rayHull(const Vec3& origin, const Vec3& dir, Real maxT, const Pose& P, const ConvexHull& h, Real inflate,
             Real& t, Vec3& normal);

}  // namespace tumble::physics
