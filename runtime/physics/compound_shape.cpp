#include "physics/compound_shape.h"

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

}  // namespace tumble::physics
