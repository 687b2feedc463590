#pragma once
// Contacts between convex shapes seen through their support mappings (GJK
// distance, EPA penetration, then a manifold from the touching features);
// convex_collision.cpp explains the method. Used wherever a cylinder takes
// part: cylinders have no faces and edges to run the separating-axis test on.
#include <cstdint>

#include "physics/convex_hull.h"
#include "physics/internal/hull_collision.h"
#include "physics/internal/manifold.h"

namespace tumble::physics {

/// Sine of the angle within which a face or a line lies in the contact plane
/// and touches with all of it (~2 degrees): a cylinder's cap with its
/// ring, its side with a line; between the two it touches with one rim point.
constexpr Real kFeatureSin = Real(0.035);

/// A convex shape at a world pose (p, R): what GJK and EPA need of it.
struct ConvexPiece {
  enum class Kind { Sphere, Capsule, Box, Hull, Cylinder };
  Kind kind = Kind::Sphere;
  Pose pose;
  Real radius_m = 0;      ///< Sphere, Capsule, Cylinder
  Real halfHeight_m = 0;  ///< Capsule (core segment), Cylinder (caps at +-halfHeight_m along local Y)
  Vec3 halfExtents_m = Vec3::Zero();  ///< Box
  const ConvexHull* hull = nullptr;   ///< Hull (in the pose's frame; a mesh triangle passes its two-faced hull)

  /// The point of the shape farthest along dir (world, m).
  Vec3 support(const Vec3& dir) const;
};

/// The piece of a sphere, box, capsule, hull or cylinder at (p, R); false for other shapes.
bool convexPiece(const Shape& shape, const Pose& pose, ConvexPiece* out);

/// Contact manifold (normal from a to b, up to four points within margin_m)
/// between two convex pieces. Returns the number of points.
int collideConvex(const ConvexPiece& a, const ConvexPiece& b, Real margin_m, Manifold& m);

/// Signed distance (m, negative inside) from world point p to the surface of
/// the cylinder (radius r, half height hh, axis = local Y of pose), the
/// closest surface point and the outward unit normal there.
Real pointCylinderDistance(const Vec3& p, const Pose& cylinder, Real r_m, Real hh_m, Vec3& closest, Vec3& normal);

/// Candidate contact points of a cylinder against a surface whose normal
/// (pointing out of the surface, towards the cylinder) is n: the deepest
/// point of each cap rim and, on the lower cap, three more rim points a
/// quarter turn apart (a cylinder on its cap stands on four points, one on
/// its side lies on the two ends of its lowest line). Writes up to 5 points
/// and their feature ids; returns the count.
int cylinderSurfacePoints(const Pose& cylinder, Real r_m, Real hh_m, const Vec3& n, Vec3* points, std::uint32_t* ids);

/// Ray origin + t dir (dir unit), 0 <= t <= maxT, against the cylinder grown
/// by `inflate` (radius and half height; the rims stay sharp). Starting
/// inside gives t = 0 and the normal -dir.
bool rayCylinder(const Vec3& origin, const Vec3& dir, Real maxT, const Pose& cylinder, Real r_m, Real hh_m,
                 Real inflate_m, Real& t, Vec3& normal);

}  // namespace tumble::physics
