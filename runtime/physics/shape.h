#pragma once
// Collision shapes and their mass properties.
//
// Every shape is described in its body's local frame, centred on the body's
// centre of mass, with its principal axes along the body's axes, so the body
// inertia tensor is diagonal in the body frame.
#include "core/math.h"
#include "core/result.h"

namespace tumble::physics {

enum class ShapeType { Sphere, Box, Capsule, Plane };

struct Shape {
  ShapeType type = ShapeType::Sphere;
  Real radius_m = Real(0.5);                    ///< Sphere, Capsule
  Vec3 halfExtents_m = Vec3::Constant(Real(0.5));  ///< Box: half size along local x, y, z
  Real halfHeight_m = Real(0.5);  ///< Capsule: half length of the core segment along local Y, caps excluded
  // Plane: the body's local +Y is the plane normal; the plane passes through
  // the body position. Planes are always static and infinite.

  static Shape sphere(Real radius_m);
  static Shape box(const Vec3& halfExtents_m);
  static Shape capsule(Real radius_m, Real halfHeight_m);
  static Shape plane();

  /// Volume in m^3 (0 for planes).
  Real volume() const;
  /// Principal moments of inertia per kg of mass (m^2), in the local frame.
  Vec3 unitInertia() const;
  /// Radius of a sphere around the centre that contains the shape (m).
  Real boundingRadius() const;
};

/// Refuses sizes that are not finite and positive; the message names the field.
Status validateShape(const Shape& shape);

const char* shapeTypeName(ShapeType type);

}  // namespace tumble::physics
