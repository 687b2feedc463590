#include "physics/shape.h"

#include <cmath>
#include <string>

#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/mesh_shape.h"

namespace tumble::physics {

Shape Shape::sphere(Real r) {
  Shape s;
  s.type = ShapeType::Sphere;
  s.radius_m = r;
  return s;
}
Shape Shape::box(const Vec3& h) {
  Shape s;
  s.type = ShapeType::Box;
  s.halfExtents_m = h;
  return s;
}
Shape Shape::capsule(Real r, Real hh) {
  Shape s;
  s.type = ShapeType::Capsule;
  s.radius_m = r;
  s.halfHeight_m = hh;
  return s;
}
Shape Shape::cylinder(Real r, Real hh) {
  Shape s;
  s.type = ShapeType::Cylinder;
  s.radius_m = r;
  s.halfHeight_m = hh;
  return s;
}
Shape Shape::plane() {
  Shape s;
  s.type = ShapeType::Plane;
  return s;
}

Real Shape::volume() const {
  switch (type) {
    case ShapeType::Sphere: return Real(4.0 / 3.0) * kPi * radius_m * radius_m * radius_m;
    case ShapeType::Box: return 8 * halfExtents_m.prod();
    case ShapeType::Capsule: {
      Real r = radius_m;
      return kPi * r * r * (2 * halfHeight_m) + Real(4.0 / 3.0) * kPi * r * r * r;
    }
    case ShapeType::Hull: return hull ? hull->volume_m3 : 0;
    case ShapeType::Compound: return compound ? compound->volume_m3 : 0;
    case ShapeType::Plane: return 0;
    case ShapeType::Cylinder: return kPi * radius_m * radius_m * 2 * halfHeight_m;
    case ShapeType::Mesh: return 0;  // a surface: no inside, no mass (static bodies only)
  }
  return 0;
}

Vec3 Shape::unitInertia() const {
  switch (type) {
    case ShapeType::Sphere: return Vec3::Constant(Real(0.4) * radius_m * radius_m);
    case ShapeType::Box: {
      Vec3 s = 2 * halfExtents_m;
      Vec3 s2 = s.cwiseProduct(s);
      return Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()) / Real(12);
    }
    case ShapeType::Capsule: {
      // Cylinder of height h plus two hemispheres, mass split by volume.
      // Hemisphere about its own centre of mass, shifted by the parallel-axis
      // theorem to the capsule centre (Eberly, Game Physics 2.5; the
      // hemisphere's centroid sits 3r/8 from its flat face).
      Real r = radius_m, h = 2 * halfHeight_m;
      Real vCyl = kPi * r * r * h, vCaps = Real(4.0 / 3.0) * kPi * r * r * r;
      Real mCyl = vCyl / (vCyl + vCaps), mCaps = vCaps / (vCyl + vCaps);
      Real iyCyl = mCyl * r * r / 2;
      Real ixCyl = mCyl * (3 * r * r + h * h) / 12;
      Real iyCaps = mCaps * Real(0.4) * r * r;
      Real ixCaps = mCaps * (Real(0.4) * r * r + h * h / 4 + Real(3.0 / 8.0) * h * r);
      return Vec3(ixCyl + ixCaps, iyCyl + iyCaps, ixCyl + ixCaps);
    }
    case ShapeType::Hull: return hull ? Vec3(hull->unitInertia_m2.diagonal()) : Vec3::Zero();
    case ShapeType::Compound: return compound ? compound->unitInertia_m2 : Vec3::Zero();
    case ShapeType::Plane: return Vec3::Zero();
    case ShapeType::Mesh: return Vec3::Zero();
    case ShapeType::Cylinder: {
      // Solid cylinder of height h: m r^2 / 2 about its axis, m (3 r^2 + h^2) / 12 across it.
      const Real r2 = radius_m * radius_m, h = 2 * halfHeight_m;
      const Real across = (3 * r2 + h * h) / 12;
      return Vec3(across, r2 / 2, across);
    }
  }
  return Vec3::Zero();
}

Real Shape::boundingRadius() const {
  switch (type) {
    case ShapeType::Sphere: return radius_m;
    case ShapeType::Box: return halfExtents_m.norm();
    case ShapeType::Capsule: return radius_m + halfHeight_m;
    case ShapeType::Hull: return hull ? hull->boundingRadius_m : 0;
    case ShapeType::Compound: return compound ? compound->boundingRadius_m : 0;
    case ShapeType::Plane: return std::numeric_limits<Real>::infinity();
    case ShapeType::Mesh: return mesh ? mesh->boundingRadius_m : 0;
    case ShapeType::Cylinder: return std::hypot(radius_m, halfHeight_m);
  }
  return 0;
}

Real Shape::innerRadius() const {
  switch (type) {
    case ShapeType::Sphere: return radius_m;
    case ShapeType::Box: return halfExtents_m.minCoeff();
    case ShapeType::Capsule: return radius_m;
    case ShapeType::Hull: return hull ? std::max<Real>(hull->innerRadius_m, 0) : 0;
    case ShapeType::Compound: return compound ? std::max<Real>(compound->innerRadius_m, 0) : 0;
    case ShapeType::Plane: return 0;
    case ShapeType::Mesh: return 0;
    case ShapeType::Cylinder: return std::min(radius_m, halfHeight_m);
  }
  return 0;
}

void Shape::bounds(const Vec3& p, const Quat& q, Vec3* lo, Vec3* hi) const {
  Vec3 centre = p, ext = Vec3::Zero();
  switch (type) {
    case ShapeType::Sphere: ext = Vec3::Constant(radius_m); break;
    case ShapeType::Box: ext = q.toRotationMatrix().cwiseAbs() * halfExtents_m; break;
    case ShapeType::Capsule: ext = (q * Vec3(0, halfHeight_m, 0)).cwiseAbs() + Vec3::Constant(radius_m); break;
    case ShapeType::Hull: {
      const Mat3 R = q.toRotationMatrix();
      centre = p + R * ((hull->boundsLo_m + hull->boundsHi_m) / 2);
      ext = R.cwiseAbs() * ((hull->boundsHi_m - hull->boundsLo_m) / 2);
      break;
    }
    case ShapeType::Compound: {
      Vec3 l = Vec3::Constant(std::numeric_limits<Real>::max()), h = -l;
      for (const CompoundChild& c : compound->children) {
        Vec3 cl, ch;
        c.shape.bounds(p + q * c.position_m, q * c.orientation, &cl, &ch);
        l = l.cwiseMin(cl);
        h = h.cwiseMax(ch);
      }
      *lo = l;
      *hi = h;
      return;
    }
    case ShapeType::Plane: ext = Vec3::Constant(std::numeric_limits<Real>::infinity()); break;
    case ShapeType::Cylinder: {
      // Each cap disc spans r sqrt(1 - a_i^2) = r sqrt(a_j^2 + a_k^2) along
      // world axis i (a the unit axis; the second form has no cancellation).
      const Vec3 a = q * Vec3::UnitY();
      const Vec3 disc = Vec3(std::hypot(a.y(), a.z()), std::hypot(a.x(), a.z()), std::hypot(a.x(), a.y())) * radius_m;
      ext = a.cwiseAbs() * halfHeight_m + disc;
      break;
    }
    case ShapeType::Mesh: {
      const MeshNode& root = mesh->nodes[0];
      const Mat3 R = q.toRotationMatrix();
      centre = p + R * ((root.coverLo_m + root.coverHi_m) / 2);
      ext = R.cwiseAbs() * ((root.coverHi_m - root.coverLo_m) / 2);
      break;
    }
  }
  *lo = centre - ext;
  *hi = centre + ext;
}

static bool positiveFinite(Real v) { return std::isfinite(v) && v > 0; }

Status validateShape(const Shape& s) {
  auto bad = [](const char* field, Real v) {
    return makeError(std::string("shape field '") + field + "' must be a finite number > 0 (metres), got " +
                     std::to_string(v));
  };
  switch (s.type) {
    case ShapeType::Sphere:
      if (!positiveFinite(s.radius_m)) return bad("radius", s.radius_m);
      break;
    case ShapeType::Box:
      for (int i = 0; i < 3; ++i)
        if (!positiveFinite(s.halfExtents_m[i])) return bad("half_extents", s.halfExtents_m[i]);
      break;
    case ShapeType::Capsule:
      if (!positiveFinite(s.radius_m)) return bad("radius", s.radius_m);
      if (!std::isfinite(s.halfHeight_m) || s.halfHeight_m < 0) return bad("half_height", s.halfHeight_m);
      break;
    case ShapeType::Hull:
      if (!s.hull || s.hull->faces.size() < 4 || !(s.hull->volume_m3 > 0))
        return makeError("a hull shape must be made with makeHullShape (it has no faces or no volume)");
      break;
    case ShapeType::Compound:
      if (!s.compound || s.compound->children.empty() || !(s.compound->volume_m3 > 0))
        return makeError("a compound shape must be made with makeCompoundShape (it has no children or no volume)");
      break;
    case ShapeType::Cylinder:
      if (!positiveFinite(s.radius_m)) return bad("radius", s.radius_m);
      if (!positiveFinite(s.halfHeight_m)) return bad("half_height", s.halfHeight_m);
      break;
    case ShapeType::Plane: break;
    case ShapeType::Mesh:
      if (!s.mesh || s.mesh->nodes.empty() || s.mesh->triangles.empty())
        return makeError("a mesh shape must be made with makeMeshShape (it has no triangles)");
      break;
  }
  return Ok{};
}

const char* shapeTypeName(ShapeType t) {
  switch (t) {
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Box: return "box";
    case ShapeType::Capsule: return "capsule";
    case ShapeType::Hull: return "hull";
    case ShapeType::Plane: return "plane";
    case ShapeType::Compound: return "compound";
    case ShapeType::Mesh: return "mesh";
    case ShapeType::Cylinder: return "cylinder";
  }
  return "?";
}

}  // namespace tumble::physics
