#pragma once
// Narrow phase: contact manifolds between pairs of shapes.
#include <vector>

#include "physics/body.h"
#include "physics/internal/manifold.h"

namespace tumble::physics {

/// Fills m.normal (from a to b) and up to four points whose separation is at
/// most margin_m (speculative contacts). Returns the number of points.
int collideBodies(const Body& a, const Body& b, Real margin_m, Manifold& m);

/// The same for two shapes at world poses. Compounds are not handled here
/// (collidePair splits them into children).
int collideShapes(const Shape& a, const Vec3& pa_m, const Quat& qa, const Shape& b, const Vec3& pb_m, const Quat& qb,
                  Real margin_m, Manifold& m);

/// Every manifold of a body pair: one for simple shapes, one per touching
/// child pair when either is a compound (childA / childB set). out is
/// cleared first; a and b are not filled in.
int collidePair(const Body& a, const Body& b, Real margin_m, std::vector<Manifold>& out);

/// The shape of child `child` of a compound, or s itself.
const Shape& childShape(const Shape& s, std::uint16_t child);

/// Two spheres whose relative motion this step (b relative to a, m) is
/// large: one speculative point along the normal at their time of impact,
/// or none if they stay more than spec_m apart during the step. Pairs
/// already within spec_m get the ordinary contact.
int collideSpheresSwept(const Body& a, const Body& b, const Vec3& relativeMotion_m, Real spec_m, Manifold& m);

/// Closest points of segments p0-p1 and q0-q1: parameters s, t in [0, 1].
void closestSegmentPoints(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, Real& s, Real& t);

}  // namespace tumble::physics
