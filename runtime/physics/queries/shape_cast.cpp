// Shape cast (World::shapeCast): the first thing a shape swept along a line
// touches. It reuses the narrow phase, so every shape pair that can collide
// can be cast, compounds and the height field included.
//
// Shape cast by conservative advancement (Mirtich 1996; for a pure
// translation it is exact on planes): at the current position the narrow
// phase gives, for each manifold, a separating direction n (from the cast
// shape to the target) and the gap s along it. Nothing of the target lies
// closer than s in front of the plane through the cast shape's support along
// n, so the shape can move s / (d . n) along the unit direction d before it
// can touch; the smallest such step over all manifolds is safe. Repeat until
// the gap is below kQueryTolerance_m (a hit) or the shape moves away from
// every manifold or beyond maxDistance (a miss). A sphere onto a plane
// converges in one step; a grazing pass (d . n small) in a few.
// Rejected: sampling the path (misses thin objects, costs per sample) and a
// swept-volume GJK (Minkowski sum of the shape with a segment: needs a
// support-function narrow phase for every pair, including the height field).
#include <algorithm>
#include <limits>
#include <vector>

#include "physics/compound_shape.h"
#include "physics/internal/height_field_collision.h"
#include "physics/internal/narrow_phase.h"
#include "physics/internal/query_probe.h"
#include "physics/world.h"

namespace tumble::physics {
namespace {

constexpr int kMaxCastIterations = 48;

/// Manifolds of the probe against the height field, child by child for compounds.
void heightFieldManifolds(const Body& probe, const HeightField& field, const Vec3& lo, const Vec3& hi, Real margin,
                          HeightFieldScratch& scratch, std::vector<Manifold>& out) {
  out.clear();
  auto one = [&](const Body& part) {
    Manifold m[kMaxHeightFieldManifolds];
    const int k = collideHeightField(part, field, lo, hi, margin, scratch, m);
    out.insert(out.end(), m, m + k);
  };
  if (probe.shape.type != ShapeType::Compound) return one(probe);
  Body part = probe;
  for (const CompoundChild& c : probe.shape.compound->children) {
    part.shape = c.shape;
    part.position_m = probe.position_m + probe.orientation * c.position_m;
    part.orientation = probe.orientation * c.orientation;
    one(part);
  }
}

struct Gap {
  Real step = std::numeric_limits<Real>::max();  ///< safe advance along d (m); max: moving away from all
  Real minSeparation = std::numeric_limits<Real>::max();
  Vec3 point = Vec3::Zero(), normal = Vec3::Zero();  ///< of the closest point; normal from probe to target
};

Gap gapOf(const std::vector<Manifold>& ms, const Vec3& d) {
  Gap g;
  for (const Manifold& m : ms)
    for (int i = 0; i < m.count; ++i) {
      const ContactPoint& c = m.points[i];
      if (c.separation_m < g.minSeparation) g.minSeparation = c.separation_m, g.point = c.point_m, g.normal = m.normal;
      const Real approach = d.dot(m.normal);
      if (approach > Real(1e-9)) g.step = std::min(g.step, std::max<Real>(c.separation_m, 0) / approach);
    }
  return g;
}

}  // namespace

bool World::shapeCast(const Shape& shape, const Vec3& position, const Quat& orientation, const Vec3& dir,
                      Real maxDistance, ShapeCastHit* hit, BodyId ignore) const {
  const Real len = dir.norm();
  if (!queryShapeValid(shape, position, orientation) || !(len > 0) || !dir.allFinite() ||
      !std::isfinite(maxDistance) || maxDistance < 0)
    return false;
  const Vec3 d = dir / len;
  Body probe = probeBody(shape, position, orientation);
  Vec3 lo0, hi0;
  shape.bounds(probe.position_m, probe.orientation, &lo0, &hi0);
  const Vec3 travel = d * maxDistance;
  const Vec3 sweptLo = lo0 + travel.cwiseMin(Vec3::Zero()) - Vec3::Constant(kQueryTolerance_m);
  const Vec3 sweptHi = hi0 + travel.cwiseMax(Vec3::Zero()) + Vec3::Constant(kQueryTolerance_m);
  Real best = std::numeric_limits<Real>::infinity();
  ShapeCastHit bestHit;
  std::vector<Manifold> found;
  HeightFieldScratch hfScratch;
  // Advances the probe against one target until it touches (true, t set) or misses.
  auto cast = [&](auto&& manifoldsAt, Real& t, Gap& at) {
    t = 0;
    for (int it = 0; it < kMaxCastIterations; ++it) {
      probe.position_m = position + d * t;
      const Real remaining = std::min(best, maxDistance) - t;
      manifoldsAt(remaining + kQueryTolerance_m);
      at = gapOf(found, d);
      if (found.empty() || at.minSeparation == std::numeric_limits<Real>::max()) return false;
      if (at.minSeparation <= kQueryTolerance_m) return true;
      if (at.step == std::numeric_limits<Real>::max() || at.step > remaining) return false;
      t += std::max(at.step, kQueryTolerance_m / 4);
    }
    return false;
  };
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    const Body& b = m_bodies[i];
    if (!b.alive || (!ignore.isNull() && idOf(i) == ignore)) continue;
    Vec3 blo, bhi;
    b.shape.bounds(b.position_m, b.orientation, &blo, &bhi);
    if ((sweptLo.array() > bhi.array()).any() || (sweptHi.array() < blo.array()).any()) continue;
    Real t;
    Gap g;
    if (!cast([&](Real margin) { collidePair(probe, b, margin, found); }, t, g) || !(t < best)) continue;
    best = t;
    bestHit = {idOf(i), t, g.point, Vec3(-g.normal)};
  }
  if (m_heightField) {
    Real t;
    Gap g;
    auto manifolds = [&](Real margin) {
      Vec3 lo, hi;
      shape.bounds(probe.position_m, probe.orientation, &lo, &hi);
      const Vec3 rest = d * margin;
      heightFieldManifolds(probe, *m_heightField, lo + rest.cwiseMin(Vec3::Zero()), hi + rest.cwiseMax(Vec3::Zero()),
                           margin, hfScratch, found);
    };
    if (cast(manifolds, t, g) && t < best) {
      best = t;
      bestHit = {BodyId{}, t, g.point, Vec3(-g.normal)};
    }
  }
  if (!(best <= maxDistance)) return false;
  if (hit) *hit = bestHit;
  return true;
}

}  // namespace tumble::physics
