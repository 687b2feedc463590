#pragma once
// What the shape queries (queries/overlap.cpp, queries/shape_cast.cpp)
// share: which query shapes are valid, and the kinematic probe body the
// narrow phase tests them as.
#include "physics/body.h"

namespace tumble::physics {

/// A query shape the narrow phase can take: valid, not a plane, at a finite pose.
inline bool queryShapeValid(const Shape& shape, const Vec3& p, const Quat& q) {
  return shape.type != ShapeType::Plane && validateShape(shape).ok() && p.allFinite() && q.coeffs().allFinite() &&
         q.norm() > Real(1e-6);
}

/// A kinematic body of the query shape at (p, q), for the narrow phase.
inline Body probeBody(const Shape& shape, const Vec3& p, const Quat& q) {
  Body b;
  b.type = BodyType::Kinematic;
  b.shape = shape;
  b.position_m = p;
  b.orientation = q.normalized();
  b.alive = true;
  return b;
}

}  // namespace tumble::physics
