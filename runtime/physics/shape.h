#pragma once
// Collision shapes and their mass properties.
//
// Every shape is described in its body's local frame, centred on the body's
// centre of mass, with its principal axes along the body's axes, so the body
// inertia tensor is diagonal in the body frame. Hulls and compounds are
// moved into that frame when they are made (makeHullShape, makeCompoundShape),
// which say where it lies in the frame the caller described them in.
#include <memory>

#include "core/math.h"
#include "core/result.h"

namespace tumble::physics {

/// The order matters: the narrow phase handles each pair once, as (lower, higher).
/// Cylinder comes last so that the pairs of the older shapes keep their order.
enum class ShapeType { Sphere, Box, Capsule, Hull, Plane, Compound, Mesh, Cylinder };

struct ConvexHull;     // physics/convex_hull.h
struct CompoundShape;  // physics/compound_shape.h
struct MeshShape;      // physics/mesh_shape.h

/// Where a shape's body frame (centre of mass, principal axes) sits in the
/// frame its data was given in: x_given = centre_m + rotation * x_body.
struct ShapeFrame {
  Vec3 centre_m = Vec3::Zero();
  Quat rotation = Quat::Identity();
};

struct Shape {
  ShapeType type = ShapeType::Sphere;
  Real radius_m = Real(0.5);                    ///< Sphere, Capsule, Cylinder
  Vec3 halfExtents_m = Vec3::Constant(Real(0.5));  ///< Box: half size along local x, y, z
  Real halfHeight_m = Real(0.5);  ///< Capsule: half length of the core segment along local Y, caps excluded;
                                  ///< Cylinder: half its height along local Y (the caps are flat discs at +-halfHeight_m)
  // Plane: the body's local +Y is the plane normal; the plane passes through
  // the body position. Planes are always static and infinite.
  /// Hull: vertices and faces in the body frame (shared, immutable; see makeHullShape).
  std::shared_ptr<const ConvexHull> hull;
  /// Compound: children in the body frame (shared, immutable; see makeCompoundShape).
  std::shared_ptr<const CompoundShape> compound;
  /// Mesh: a static triangle tree in the body frame (shared, immutable; see
  /// makeMeshShape). Static bodies only.
  std::shared_ptr<const MeshShape> mesh;

  static Shape sphere(Real radius_m);
  static Shape box(const Vec3& halfExtents_m);
  static Shape capsule(Real radius_m, Real halfHeight_m);
  /// A solid cylinder whose axis is the body's local Y, centred on the body.
  static Shape cylinder(Real radius_m, Real halfHeight_m);
  static Shape plane();

  /// Volume in m^3 (0 for planes).
  Real volume() const;
  /// Principal moments of inertia per kg of mass (m^2), in the local frame.
  Vec3 unitInertia() const;
  /// Radius of a sphere around the centre that contains the shape (m).
  Real boundingRadius() const;
  /// Radius of the largest sphere about the centre inside the shape (m; 0
  /// for planes, and for compounds whose centre lies outside every child).
  Real innerRadius() const;
  /// Axis-aligned box (m) of the shape at pose (p, q).
  void bounds(const Vec3& p_m, const Quat& q, Vec3* lo_m, Vec3* hi_m) const;
};

/// Refuses sizes that are not finite and positive; the message names the field.
Status validateShape(const Shape& shape);

const char* shapeTypeName(ShapeType type);

}  // namespace tumble::physics
