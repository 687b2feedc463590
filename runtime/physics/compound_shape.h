#pragma once
// Compound shapes: several child shapes (sphere, box, capsule, hull) fixed
// to one rigid body at local poses (ShapeType::Compound).
//
// Index
//   CompoundChild        one child and its pose
//   CompoundShape        the children in the body frame, with mass data
//   makeCompoundShape    builds one from children given in any frame
//
// Mass: uniform density over the union of the children (overlaps count
// twice; keep children apart or accept it). Each child's inertia is rotated
// into the common frame and moved to the common centre of mass with the
// parallel-axis theorem (Eberly, Game Physics 2.5), then the sum is
// diagonalised; the children are stored in that principal frame so the body
// keeps a diagonal inertia like every other shape (shape.h).
//
// Collision runs child by child against the other shape (narrow_phase.cpp);
// the broad phase uses the box around all children.
#include <vector>

#include "physics/shape.h"

namespace tumble::physics {

struct CompoundChild {
  Shape shape;                        ///< sphere, box, capsule or hull (not plane, not compound)
  Vec3 position_m = Vec3::Zero();     ///< of the child's centre (its body-frame origin)
  Quat orientation = Quat::Identity();  ///< child frame to compound frame
};

struct CompoundShape {
  std::vector<CompoundChild> children;  ///< in the body frame (centre of mass, principal axes)
  Real volume_m3 = 0;
  Vec3 unitInertia_m2 = Vec3::Zero();  ///< principal moments per kg
  Real boundingRadius_m = 0;
  Real innerRadius_m = 0;
};

/// A compound from children posed in some frame. Refuses (message names the
/// child, 1-based): no children, more than kMaxCompoundChildren, a plane or
/// compound child, a child that fails validateShape, a non-finite pose.
/// `frame` (if not null) says where the body frame lies in that frame (see
/// ShapeFrame).
Result<Shape> makeCompoundShape(const std::vector<CompoundChild>& children, ShapeFrame* frame = nullptr);

/// Children per compound; each child pair is a manifold, keyed by child index.
constexpr int kMaxCompoundChildren = 64;

}  // namespace tumble::physics
