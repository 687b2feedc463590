#pragma once
// Convex hulls: a polyhedron built from a point cloud, used as a collision
// shape (ShapeType::Hull).
//
// Index
//   HullFace, HullEdge, ConvexHull   the polyhedron (faces, edges, vertices)
//   computeConvexHull                hull of a point cloud, in the points' frame
//   ShapeFrame                       where a shape's body frame sits in its input frame
//   makeHullShape                    a Shape in its principal frame, and that frame
//
// The hull is built incrementally (de Berg et al., Computational Geometry,
// ch. 11; the same horizon step as quickhull, without its point order): start
// from the largest tetrahedron of extreme points, then add one point at a
// time, removing the triangles it sees and closing the hole with a fan from
// the horizon to the point. Points within a tolerance (1e-7 of the cloud's
// size) of the hull count as inside, so near-coplanar points do not create
// sliver triangles. Coplanar triangles are then merged into polygon faces
// (a convex polytope has one face per outward normal), which the narrow
// phase needs: clipping against a whole face gives a box-like hull resting on
// the ground four corner contacts, not those of one triangle.
// O(n F) for n points and F faces: fine for the tens to hundreds of points a
// collision hull has (keep hulls small; the narrow phase is O(F V + E^2)).
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "physics/shape.h"

namespace tumble::physics {

/// A face: plane normal . x = offset_m, vertices faceVertices[first ..
/// first + count) counter-clockwise seen from outside.
struct HullFace {
  Vec3 normal = Vec3::UnitY();  ///< unit, outward
  Real offset_m = 0;            ///< distance of the plane from the origin along normal
  std::uint32_t first = 0, count = 0;
};

/// An edge and the two faces that meet there.
struct HullEdge {
  std::uint32_t v0 = 0, v1 = 0;
  std::uint32_t face0 = 0, face1 = 0;
};

struct ConvexHull {
  std::vector<Vec3> vertices_m;
  std::vector<HullFace> faces;
  std::vector<std::uint32_t> faceVertices;
  std::vector<HullEdge> edges;
  /// Faces as a triangle fan each, counter-clockwise from outside (rendering, mass).
  std::vector<std::array<std::uint32_t, 3>> triangles;
  Real volume_m3 = 0;
  Vec3 centroid_m = Vec3::Zero();        ///< centre of volume in the hull's frame
  Mat3 unitInertia_m2 = Mat3::Zero();    ///< inertia per kg about the centroid (m^2)
  Vec3 boundsLo_m = Vec3::Zero(), boundsHi_m = Vec3::Zero();
  Real boundingRadius_m = 0;  ///< largest |vertex| (about the frame origin)
  Real innerRadius_m = 0;     ///< distance from the origin to the nearest face plane (<= 0 if outside)

  /// Support point: the vertex farthest along dir.
  const Vec3& support(const Vec3& dir) const;
};

/// Largest point cloud computeConvexHull accepts (its cost is O(n F)).
constexpr int kMaxHullPoints = 4096;

/// The hull of `points_m`, in their frame. Refuses (message says why): fewer
/// than 4 points, more than kMaxHullPoints, a non-finite coordinate (names the point, 1-based), and
/// points that are all (nearly) on one plane, line or point.
Result<ConvexHull> computeConvexHull(std::span<const Vec3> points_m);

/// Hull data moved to its centroid and principal axes (body frame), plus
/// volume, inertia and bounds filled in.
ConvexHull toPrincipalFrame(ConvexHull hull, ShapeFrame* frame);

/// A ShapeType::Hull shape from a point cloud. The body frame is the hull's
/// centre of mass and principal axes; `frame` (if not null) says where that
/// is in the points' frame, so a body meant to sit at pose (P, Q) in the
/// points' frame goes to P + Q frame.centre_m with orientation Q frame.rotation.
Result<Shape> makeHullShape(std::span<const Vec3> points_m, ShapeFrame* frame = nullptr);

}  // namespace tumble::physics
