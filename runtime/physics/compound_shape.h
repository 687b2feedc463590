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

/// The same shape with its centre of mass moved to `offset_m` (in the
/// shape's own frame): ballast low in a hull, a weighted toy, a car whose
/// engine sits forward. The principal moments and axes are kept, now taken
/// about the new centre, as Jolt's OffsetCenterOfMassShape does (the
/// geometry cannot tell the moments of a body whose density is not
/// uniform; set them with World::setPrincipalInertia). The result is a
/// compound whose children sit at -offset_m from the body's origin, so
/// the body's position is the new centre of mass. Refused: a non-finite
/// offset, a plane or mesh, and an offset outside the shape (no mass
/// distribution of one sign puts the centre outside a convex body; for a
/// compound, outside the box around its children).
Result<Shape> offsetCentreOfMass(const Shape& shape, const Vec3& offset_m);

/// Children per compound; each child pair is a manifold, keyed by child index.
constexpr int kMaxCompoundChildren = 64;

}  // namespace tumble::physics
