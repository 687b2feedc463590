// Ray casts: a ray against each kind of shape (rayShapeAt, also the sweep of
// continuous collision, ccd.cpp), and the World's ray queries over every
// body and the height field (World::rayCast, rayCastAll, rayCastBody).
#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/compound_shape.h"
#include "physics/internal/convex_collision.h"
#include "physics/internal/hull_collision.h"
#include "physics/internal/mesh_collision.h"
#include "physics/internal/ray_shape.h"
#include "physics/world.h"

namespace tumble::physics {

namespace {

/// origin o + t * d, d unit, 0 <= t <= maxT.
struct Ray {
  const Vec3& o;
  const Vec3& d;
  Real maxT;
};

bool raySphere(const Ray& ray, const Vec3& c, Real r, Real& t, Vec3& n) {
  const Vec3& o = ray.o;
  const Vec3& d = ray.d;
  Vec3 m = o - c;
  Real bq = m.dot(d), cq = m.squaredNorm() - r * r;
  if (cq > 0 && bq > 0) return false;
  Real disc = bq * bq - cq;
  if (disc < 0) return false;
  t = std::max<Real>(-bq - std::sqrt(disc), 0);
  if (t > ray.maxT) return false;
  n = (o + d * t - c).normalized();
  return true;
}

/// The plane through position with normal orientation * +Y, pushed out by inflate.
bool rayPlane(const Ray& ray, const Vec3& position, const Quat& orientation, Real inflate, Real& tHit, Vec3& nHit) {
  Vec3 n = orientation * Vec3::UnitY();
  Real denom = n.dot(ray.d);
  Real dist = n.dot(ray.o - position) - inflate;
  if (dist < 0) return false;  // starts behind the plane
  if (denom >= 0) return false;
  Real t = -dist / denom;
  if (t > ray.maxT) return false;
  tHit = t;
  nHit = n;
  return true;
}

/// Slabs in the box's frame; the box grown by inflate keeps sharp corners.
bool rayBox(const Ray& ray, const Vec3& position, const Quat& orientation, const Vec3& halfExtents, Real inflate,
            Real& tHit, Vec3& nHit) {
  Mat3 R = orientation.toRotationMatrix();
  Vec3 lo = R.transpose() * (ray.o - position), ld = R.transpose() * ray.d;
  const Vec3 he = halfExtents + Vec3::Constant(inflate);
  Real tmin = 0, tmax = ray.maxT;
  int axis = -1;
  Real sign = 1;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(ld[i]) < Real(1e-12)) {
      if (std::abs(lo[i]) > he[i]) return false;
      continue;
    }
    Real inv = 1 / ld[i];
    Real t1 = (-he[i] - lo[i]) * inv, t2 = (he[i] - lo[i]) * inv;
    Real sg = -1;
    if (t1 > t2) std::swap(t1, t2), sg = 1;
    if (t1 > tmin) tmin = t1, axis = i, sign = sg;
    tmax = std::min(tmax, t2);
    if (tmin > tmax) return false;
  }
  tHit = tmin;
  Vec3 nl = Vec3::Zero();
  if (axis >= 0) nl[axis] = sign;
  else nl = -ld;  // started inside
  nHit = (R * nl).normalized();
  return true;
}

/// The infinite cylinder about the axis, then the two end spheres.
bool rayCapsule(const Ray& ray, const Vec3& position, const Quat& orientation, Real halfHeight, Real radius,
                Real& tHit, Vec3& nHit) {
  const Vec3& o = ray.o;
  const Vec3& d = ray.d;
  Vec3 axis = orientation * Vec3::UnitY();
  Vec3 p0 = position - axis * halfHeight, p1 = position + axis * halfHeight;
  Real best = std::numeric_limits<Real>::max();
  Vec3 bestN = Vec3::UnitY();
  Vec3 m = o - p0, dperp = d - axis * d.dot(axis), mperp = m - axis * m.dot(axis);
  const Real rad = radius;
  Real a = dperp.squaredNorm(), bq = mperp.dot(dperp), c = mperp.squaredNorm() - rad * rad;
  if (a > Real(1e-12)) {
    Real disc = bq * bq - a * c;
    if (disc >= 0) {
      Real t = (-bq - std::sqrt(disc)) / a;
      if (c < 0) t = 0;
      Real along = (o + d * t - p0).dot(axis);
      if (t >= 0 && t <= ray.maxT && along >= 0 && along <= 2 * halfHeight) {
        best = t;
        Vec3 q = o + d * t;
        bestN = (q - (p0 + axis * along)).normalized();
      }
    }
  }
  for (const Vec3& c2 : {p0, p1}) {
    Real t;
    Vec3 n;
    if (raySphere(ray, c2, radius, t, n) && t < best) best = t, bestN = n;
  }
  if (best > ray.maxT) return false;
  tHit = best;
  nHit = bestN;
  return true;
}

}  // namespace

bool rayShapeAt(const Shape& s, const Vec3& position, const Quat& orientation, const Vec3& o, const Vec3& d,
                Real maxT, Real& tHit, Vec3& nHit, Real inflate, MeshStats* meshStats) {
  // d is unit length here.
  const Ray ray{o, d, maxT};
  switch (s.type) {
    case ShapeType::Sphere: return raySphere(ray, position, s.radius_m + inflate, tHit, nHit);
    case ShapeType::Plane: return rayPlane(ray, position, orientation, inflate, tHit, nHit);
    case ShapeType::Box: return rayBox(ray, position, orientation, s.halfExtents_m, inflate, tHit, nHit);
    case ShapeType::Capsule:
      return rayCapsule(ray, position, orientation, s.halfHeight_m, s.radius_m + inflate, tHit, nHit);
    case ShapeType::Hull:
      return rayHull(o, d, maxT, Pose{position, orientation.toRotationMatrix()}, *s.hull, inflate, tHit, nHit);
    case ShapeType::Mesh: return rayMesh(o, d, maxT, position, orientation, *s.mesh, inflate, tHit, nHit, meshStats);
    case ShapeType::Cylinder:
      return rayCylinder(o, d, maxT, Pose{position, orientation.toRotationMatrix()}, s.radius_m, s.halfHeight_m, inflate,
                         tHit, nHit);
    case ShapeType::Compound: {
      bool any = false;
      for (const CompoundChild& c : s.compound->children) {
        Real t;
        Vec3 n;
        if (rayShapeAt(c.shape, position + orientation * c.position_m, orientation * c.orientation, o, d, maxT, t, n,
                       inflate) &&
            (!any || t < tHit))
          any = true, tHit = t, nHit = n;
      }
      return any;
    }
  }
  return false;
}

std::vector<RayHit> World::rayCastAll(const Vec3& origin, const Vec3& dir, Real maxDistance) const {
  std::vector<RayHit> hits;
  Real len = dir.norm();
  if (!(len > 0) || !origin.allFinite() || !std::isfinite(maxDistance)) return hits;
  Vec3 d = dir / len;
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    const Body& b = m_bodies[i];
    if (!b.alive) continue;
    Real t;
    Vec3 n;
    if (rayShape(b, origin, d, maxDistance, t, n, 0, &m_meshStats)) hits.push_back({idOf(i), t, origin + d * t, n});
  }
  HeightFieldHit fh;
  if (m_heightField && m_heightField->rayCast(origin, d, maxDistance, &fh))
    hits.push_back({BodyId{}, fh.distance_m, fh.point_m, fh.normal});
  std::sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) { return a.distance_m < b.distance_m; });
  return hits;
}

bool World::rayCast(const Vec3& origin, const Vec3& dir, Real maxDistance, RayHit* hit) const {
  auto hits = rayCastAll(origin, dir, maxDistance);
  if (hits.empty()) return false;
  if (hit) *hit = hits.front();
  return true;
}

bool World::rayCastBody(BodyId id, const Vec3& origin, const Vec3& dir, Real maxDistance, RayHit* hit) const {
  if (!isValid(id)) return false;
  const Real len = dir.norm();
  if (!(len > 0) || !origin.allFinite() || !std::isfinite(maxDistance)) return false;
  const Vec3 d = dir / len;
  Real t;
  Vec3 n;
  if (!rayShape(m_bodies[id.index], origin, d, maxDistance, t, n, 0, &m_meshStats)) return false;
  if (hit) *hit = {id, t, origin + d * t, n};
  return true;
}

}  // namespace tumble::physics
