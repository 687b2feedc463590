#pragma once
// Contact manifolds shared by the narrow phase and the contact solver.
#include <algorithm>
#include <cstdint>

#include "core/math.h"

namespace tumble::physics {

constexpr int kMaxManifoldPoints = 4;

struct ContactPoint {
  // From the narrow phase:
  Vec3 point_m = Vec3::Zero();  ///< world, midway between the two surfaces
  Real separation_m = 0;        ///< negative when overlapping
  std::uint32_t id = 0;         ///< feature id, stable while the same features touch
  // Accumulated impulses (N s) of the last step, for warm starting and events.
  Real normalImpulse = 0, tangentImpulse[2] = {0, 0};
  /// Largest normal impulse (N s) of one substep in the last step, the
  /// restitution of an impact included (contact events). An impact's own
  /// impulse is not warm started, so normalImpulse can be 0 after one.
  Real impactImpulse = 0;
};

struct Manifold {
  std::uint32_t a = 0, b = 0;   ///< body indices, a < b
  Vec3 normal = Vec3::UnitY();  ///< from a to b
  int count = 0;
  ContactPoint points[kMaxManifoldPoints];
  Real friction = 0, restitution = 0;
  /// Rolling resistance as a lever arm (m): coefficient times the rolling
  /// radius. The rolling torque is at most this times the normal force.
  Real rollingArm_m = 0;
  bool touchedBefore = false;  ///< had points last step (for begin-contact events)
  /// Round shapes (spheres, capsules): the contact point slides over the
  /// surface instead of turning with the body, so substep separation
  /// updates must not rotate its anchor (a rolling ball would otherwise look
  /// lifted off the ground and lose its normal force, friction and rolling
  /// resistance).
  bool roundA = false, roundB = false;
  /// A cylinder touching with one point of its rim (tilted between lying
  /// on its side and standing on its cap): the point is the cylinder's
  /// support along the normal, which runs round the rim as the cylinder
  /// turns instead of turning with it. The substeps follow it: the lever,
  /// the separation (the support's height) and the body's inverse inertia
  /// are turned with the body (contact_solver.cpp, "Rim contacts").
  bool rimA = false, rimB = false;
  /// Compound bodies: which child of a and of b this manifold is between (0
  /// for simple shapes). A pair has one manifold per touching child pair.
  std::uint16_t childA = 0, childB = 0;
};

/// Appends a contact point (world point p, separation sep, feature id) to m;
/// a full manifold keeps the points it has.
inline void addPoint(Manifold& m, const Vec3& p, Real sep, std::uint32_t id) {
  if (m.count >= kMaxManifoldPoints) return;
  ContactPoint& c = m.points[m.count++];
  c.point_m = p;
  c.separation_m = sep;
  c.id = id;
}

/// A candidate contact point of a clipped feature: world point, separation
/// (m) and feature id.
struct ContactCandidate {
  Vec3 p;
  Real sep;
  std::uint32_t id;
};

/// Keeps at most four of the k candidates c (in place; returns how many):
/// the deepest, the one farthest from it, and the two that span the largest
/// area on either side of that line about `normal` (the support polygon).
inline int reduceToFourCandidates(ContactCandidate* c, int k, const Vec3& normal) {
  if (k <= 4) return k;
  int i0 = 0;
  for (int i = 1; i < k; ++i)
    if (c[i].sep < c[i0].sep) i0 = i;
  int i1 = -1;
  Real best = -1;
  for (int i = 0; i < k; ++i)
    if (Real d2 = (c[i].p - c[i0].p).squaredNorm(); i != i0 && d2 > best) best = d2, i1 = i;
  // No distance compares (non-finite points: a body so far out that its
  // corners overflow, or damaged state): the deepest point alone. Found by
  // the snapshot fuzzer, which read c[-1] here.
  if (i1 < 0) {
    c[0] = c[i0];
    return 1;
  }
  int i2 = -1, i3 = -1;
  Real maxPos = 0, maxNeg = 0;
  const Vec3 e = c[i1].p - c[i0].p;
  for (int i = 0; i < k; ++i) {
    if (i == i0 || i == i1) continue;
    const Real area = normal.dot(e.cross(c[i].p - c[i0].p));
    if (area > maxPos) maxPos = area, i2 = i;
    if (area < maxNeg) maxNeg = area, i3 = i;
  }
  ContactCandidate kept[4];
  int n = 0;
  for (int idx : {i0, i1, i2, i3})
    if (idx >= 0) kept[n++] = c[idx];
  std::copy(kept, kept + n, c);
  return n;
}

/// Pair key, order independent.
inline std::uint64_t pairKey(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(a) << 32) | b;
}

}  // namespace tumble::physics
