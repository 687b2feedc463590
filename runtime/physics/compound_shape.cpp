#include "physics/compound_shape.h"

#include <algorithm>
#include <string>

#include "physics/convex_hull.h"
#include "physics/mass_properties.h"

namespace tumble::physics {

Result<Shape> makeCompoundShape(const std::vector<CompoundChild>& children, ShapeFrame* frame) {
  if (children.empty()) return makeError("a compound shape needs at least one child");
  if (children.size() > std::size_t(kMaxCompoundChildren))
    return makeError("a compound shape has at most " + std::to_string(kMaxCompoundChildren) + " children, got " +
                     std::to_string(children.size()));
  double volume = 0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < children.size(); ++i) {
    const CompoundChild& c = children[i];
    const std::string who = "compound child " + std::to_string(i + 1) + ": ";
    if (c.shape.type == ShapeType::Plane || c.shape.type == ShapeType::Compound)
      return makeError(who + "must be a sphere, box, capsule or hull, got " + shapeTypeName(c.shape.type));
    if (auto s = validateShape(c.shape); !s) return makeError(who + s.error());
    if (!c.position_m.allFinite()) return makeError(who + "position must be finite (metres)");
    if (!c.orientation.coeffs().allFinite() || c.orientation.norm() < Real(1e-6))
      return makeError(who + "orientation must be a finite, non-zero quaternion");
    volume += c.shape.volume();
    moment += double(c.shape.volume()) * c.position_m.cast<double>();
  }
  const Vec3 com = (moment / volume).cast<Real>();
  // Inertia per unit density about the common centre of mass.
  Mat3 inertia = Mat3::Zero();
  for (const CompoundChild& c : children)
    inertia += shiftedInertia(c.shape.volume() * c.shape.unitInertia(), c.orientation.normalized(),
                              c.shape.volume(), c.position_m - com);
  const PrincipalFrame pf = principalFrame(inertia);
  const Quat toBody = pf.rotation.conjugate();
  auto shape = std::make_shared<CompoundShape>();
  shape->volume_m3 = Real(volume);
  shape->unitInertia_m2 = pf.moments_kgm2 / Real(volume);
  for (const CompoundChild& c : children) {
    CompoundChild b = c;
    b.position_m = toBody * (c.position_m - com);
    b.orientation = (toBody * c.orientation.normalized()).normalized();
    shape->children.push_back(b);
    shape->boundingRadius_m = std::max(shape->boundingRadius_m, b.position_m.norm() + c.shape.boundingRadius());
    // A child containing the centre gives the inner radius (a sphere about
    // its own centre shrunk by the offset is a safe lower bound).
    shape->innerRadius_m = std::max(shape->innerRadius_m, c.shape.innerRadius() - b.position_m.norm());
  }
  if (frame) *frame = {com, pf.rotation};
  Shape s;
  s.type = ShapeType::Compound;
  s.compound = std::move(shape);
  return s;
}

Result<Shape> offsetCentreOfMass(const Shape& shape, const Vec3& offset_m) {
  if (!offset_m.allFinite()) return makeError("the centre of mass offset must be finite (metres)");
  if (shape.type == ShapeType::Plane || shape.type == ShapeType::Mesh)
    return makeError(std::string("a ") + shapeTypeName(shape.type) + " has no centre of mass to move (it is static)");
  if (auto s = validateShape(shape); !s) return makeError(s.error());
  // Inside the shape, with a relative margin for points on its surface.
  const Real slack = Real(1e-6) * std::max<Real>(shape.boundingRadius(), 1);
  bool inside = true;
  switch (shape.type) {
    case ShapeType::Sphere: inside = offset_m.norm() <= shape.radius_m + slack; break;
    case ShapeType::Box: inside = (offset_m.cwiseAbs() - shape.halfExtents_m).maxCoeff() <= slack; break;
    case ShapeType::Capsule: {
      const Real y = std::clamp(offset_m.y(), -shape.halfHeight_m, shape.halfHeight_m);
      inside = (offset_m - Vec3(0, y, 0)).norm() <= shape.radius_m + slack;
      break;
    }
    case ShapeType::Cylinder:
      inside = std::abs(offset_m.y()) <= shape.halfHeight_m + slack &&
               Vec3(offset_m.x(), 0, offset_m.z()).norm() <= shape.radius_m + slack;
      break;
    case ShapeType::Hull:
      for (const HullFace& f : shape.hull->faces) inside = inside && f.normal.dot(offset_m) <= f.offset_m + slack;
      break;
    case ShapeType::Compound: {
      Vec3 lo, hi;
      shape.bounds(Vec3::Zero(), Quat::Identity(), &lo, &hi);
      inside = (offset_m - hi).maxCoeff() <= slack && (lo - offset_m).maxCoeff() <= slack;
      break;
    }
    default: break;
  }
  if (!inside)
    return makeError("the centre of mass {" + std::to_string(offset_m.x()) + ", " + std::to_string(offset_m.y()) + ", " +
                     std::to_string(offset_m.z()) + "} m is outside the " + shapeTypeName(shape.type) +
                     " (a body's centre of mass lies within its shape)");
  auto out = std::make_shared<CompoundShape>();
  out->volume_m3 = shape.volume();
  out->unitInertia_m2 = shape.unitInertia();
  std::vector<CompoundChild> children;
  if (shape.type == ShapeType::Compound) children = shape.compound->children;
  else children.push_back(CompoundChild{shape, Vec3::Zero(), Quat::Identity()});
  for (CompoundChild& c : children) {
    c.position_m -= offset_m;
    out->boundingRadius_m = std::max(out->boundingRadius_m, c.position_m.norm() + c.shape.boundingRadius());
    out->innerRadius_m = std::max(out->innerRadius_m, c.shape.innerRadius() - c.position_m.norm());
  }
  out->children = std::move(children);
  Shape s;
  s.type = ShapeType::Compound;
  s.compound = std::move(out);
  return s;
}

}  // namespace tumble::physics
