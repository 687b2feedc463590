// Contact generation for every pair of shapes.
//
// Conventions: the manifold normal points from body a to body b; a point's
// separation is the signed gap along the normal (negative = overlap); the
// point is midway between the two surfaces. Points are kept while their
// separation is at most `margin` so the solver can stop fast bodies before
// they meet (speculative contacts, see contact_solver.cpp).
//
// Box-box uses the separating-axis test over all 15 axes (3 + 3 face
// normals, 9 edge cross products; Gottschalk's OBB test, Eberly 5.3) and then
// builds a manifold by clipping the incident face against the side planes of
// the reference face (Sutherland-Hodgman), or one point for an edge-edge
// contact. Face axes are preferred over nearly-equal edge axes so that
// resting boxes keep a stable face manifold (as in Box2D).
#include "physics/internal/narrow_phase.h"

#include <algorithm>
#include <array>

#include "physics/compound_shape.h"
#include "physics/internal/convex_collision.h"
#include "physics/internal/hull_collision.h"
#include "physics/internal/mesh_collision.h"

namespace tumble::physics {
namespace {

struct Xf {
  Vec3 p;
  Mat3 R;
};

// Sphere of radius ra at ca against sphere rb at cb.
int spheres(const Vec3& ca, Real ra, const Vec3& cb, Real rb, Real margin, Manifold& m, std::uint32_t id) {
  Vec3 d = cb - ca;
  Real dist = d.norm();
  Real sep = dist - ra - rb;
  if (sep > margin) return 0;
  Vec3 n = dist > Real(1e-9) ? Vec3(d / dist) : Vec3::UnitY();
  if (m.count == 0) m.normal = n;
  addPoint(m, ca + n * (ra + sep / 2), sep, id);
  return m.count;
}

Vec3 capsuleEnd(const Xf& x, Real hh, int end) {
  return x.p + x.R.col(1) * (end == 0 ? -hh : hh);
}

// Point against box: closest point on the box surface and the outward normal.
// Returns signed distance (negative inside).
Real pointBox(const Vec3& pw, const Xf& box, const Vec3& h, Vec3& closest, Vec3& normal) {
  Vec3 local = box.R.transpose() * (pw - box.p);
  Vec3 q = local.cwiseMax(-h).cwiseMin(h);
  if (q != local) {
    Vec3 d = local - q;
    Real dist = d.norm();
    closest = box.p + box.R * q;
    normal = box.R * (d / dist);
    return dist;
  }
  // Inside: push out through the nearest face.
  Vec3 depth = h - local.cwiseAbs();
  int axis = 0;
  depth.minCoeff(&axis);
  Vec3 nLocal = Vec3::Zero();
  nLocal[axis] = local[axis] >= 0 ? 1 : -1;
  q = local;
  q[axis] = nLocal[axis] * h[axis];
  closest = box.p + box.R * q;
  normal = box.R * nLocal;
  return -depth[axis];
}

int sphereBox(const Vec3& c, Real r, const Xf& box, const Vec3& h, Real margin, Manifold& m, std::uint32_t id) {
  Vec3 closest, nBox;
  Real dist = pointBox(c, box, h, closest, nBox);
  Real sep = dist - r;
  if (sep > margin) return 0;
  // normal from sphere to box = -nBox
  if (m.count == 0) m.normal = -nBox;
  addPoint(m, closest + nBox * (sep / 2), sep, id);
  return m.count;
}

int planePoints(const Xf& plane, const Vec3* pts, int n, Real radius, Real margin, Manifold& m, bool planeIsA) {
  Vec3 normal = plane.R.col(1);
  // Keep the deepest four.
  std::pair<Real, int> cand[8];
  int k = 0;
  for (int i = 0; i < n && i < 8; ++i) {
    Real sep = normal.dot(pts[i] - plane.p) - radius;
    if (sep > margin) continue;
    // Insertion keeps cand sorted by separation, deepest first.
    int j = k++;
    while (j > 0 && cand[j - 1].first > sep) {
      cand[j] = cand[j - 1];
      --j;
    }
    cand[j] = {sep, i};
  }
  m.normal = planeIsA ? normal : Vec3(-normal);
  for (int j = 0; j < std::min(k, kMaxManifoldPoints); ++j) {
    auto [sep, i] = cand[j];
    Vec3 onShape = pts[i] - normal * radius;
    addPoint(m, onShape - normal * (sep / 2), sep, std::uint32_t(i));
  }
  return m.count;
}

std::array<Vec3, 8> boxVertices(const Xf& x, const Vec3& h) {
  std::array<Vec3, 8> v;
  for (int i = 0; i < 8; ++i) {
    Vec3 s((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
    v[i] = x.p + x.R * s;
  }
  return v;
}

// ---- box-box ---------------------------------------------------------------

struct ClipVertex {
  Vec3 p;
  std::uint32_t id;
};

// Clips polygon `in` against plane n.x <= d, recording which edge/plane
// created new vertices so their ids stay stable between steps. Vertices up to
// kClipTolerance outside still count as inside: stacked boxes of equal size
// have corners exactly on the side planes, and without the tolerance
// round-off flips them between "vertex" and "clipped" ids every step, which
// defeats warm starting and makes stacks jitter.
constexpr Real kClipTolerance = Real(1e-3);  // m
int clipPolygon(const ClipVertex* in, int n, const Vec3& normal, Real d, std::uint32_t planeId, ClipVertex* out) {
  int k = 0;
  d += kClipTolerance;
  for (int i = 0; i < n; ++i) {
    const ClipVertex& a = in[i];
    const ClipVertex& b = in[(i + 1) % n];
    Real da = normal.dot(a.p) - d, db = normal.dot(b.p) - d;
    if (da <= 0) out[k++] = a;
    if ((da <= 0) != (db <= 0)) {
      Real t = da / (da - db);
      out[k++] = {a.p + (b.p - a.p) * t, 0x100u | (planeId << 4) | std::uint32_t(i)};
    }
  }
  return k;
}

int boxBox(const Xf& A, const Vec3& hA, const Xf& B, const Vec3& hB, Real margin, Manifold& m) {
  const Vec3 d = B.p - A.p;
  const Mat3 C = A.R.transpose() * B.R;  // C(i,j) = Ai . Bj
  Mat3 absC = C.cwiseAbs().array() + Real(1e-6);
  const Vec3 dA = A.R.transpose() * d, dB = B.R.transpose() * d;

  // Face axes of A and B.
  Real bestA = -std::numeric_limits<Real>::max(), bestB = bestA, bestE = bestA;
  int faceA = 0, faceB = 0, edgeI = 0, edgeJ = 0;
  for (int i = 0; i < 3; ++i) {
    Real s = std::abs(dA[i]) - (hA[i] + absC.row(i).dot(hB));
    if (s > margin) return 0;
    if (s > bestA) bestA = s, faceA = i;
  }
  for (int j = 0; j < 3; ++j) {
    Real s = std::abs(dB[j]) - (hB[j] + absC.col(j).dot(hA));
    if (s > margin) return 0;
    if (s > bestB) bestB = s, faceB = j;
  }
  Vec3 edgeAxis = Vec3::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Vec3 axis = A.R.col(i).cross(B.R.col(j));
      Real len = axis.norm();
      if (len < Real(1e-4)) continue;  // parallel edges: covered by face axes
      axis /= len;
      Real ra = (A.R.transpose() * axis).cwiseAbs().dot(hA);
      Real rb = (B.R.transpose() * axis).cwiseAbs().dot(hB);
      Real s = std::abs(d.dot(axis)) - (ra + rb);
      if (s > margin) return 0;
      if (s > bestE) bestE = s, edgeI = i, edgeJ = j, edgeAxis = axis;
    }

  // Prefer faces unless an edge axis is clearly better (stable manifolds).
  constexpr Real kRel = Real(0.95), kAbs = Real(0.01);
  bool useB = bestB > kRel * bestA + kAbs * std::max(hA.minCoeff(), Real(0.01));
  Real bestFace = useB ? bestB : bestA;
  if (bestE > kRel * bestFace + kAbs * std::max(hA.minCoeff(), Real(0.01)) && edgeAxis != Vec3::Zero()) {
    Vec3 n = edgeAxis.dot(d) < 0 ? Vec3(-edgeAxis) : edgeAxis;
    // Support edges: on A the edge along Ai farthest along n, on B along Bj farthest along -n.
    Vec3 pa = A.p, pb = B.p;
    for (int k = 0; k < 3; ++k) {
      if (k != edgeI) pa += A.R.col(k) * (A.R.col(k).dot(n) > 0 ? hA[k] : -hA[k]);
      if (k != edgeJ) pb += B.R.col(k) * (B.R.col(k).dot(n) > 0 ? -hB[k] : hB[k]);
    }
    Vec3 a0 = pa - A.R.col(edgeI) * hA[edgeI], a1 = pa + A.R.col(edgeI) * hA[edgeI];
    Vec3 b0 = pb - B.R.col(edgeJ) * hB[edgeJ], b1 = pb + B.R.col(edgeJ) * hB[edgeJ];
    Real s, t;
    closestSegmentPoints(a0, a1, b0, b1, s, t);
    Vec3 qa = a0 + (a1 - a0) * s, qb = b0 + (b1 - b0) * t;
    m.normal = n;
    addPoint(m, (qa + qb) / 2, bestE, 0x10000u | std::uint32_t(edgeI * 3 + edgeJ));
    return m.count;
  }

  // Face contact. Reference box R owns the face; incident box I.
  const Xf& R = useB ? B : A;
  const Xf& I = useB ? A : B;
  const Vec3& hR = useB ? hB : hA;
  const Vec3& hI = useB ? hA : hB;
  int refAxis = useB ? faceB : faceA;
  Vec3 toI = I.p - R.p;
  Vec3 nRef = R.R.col(refAxis);
  if (nRef.dot(toI) < 0) nRef = -nRef;  // reference face normal, pointing at the incident box
  // Incident face: the face of I most anti-parallel to nRef.
  Vec3 dots = I.R.transpose() * nRef;
  int incAxis = 0;
  dots.cwiseAbs().maxCoeff(&incAxis);
  Real incSign = dots[incAxis] > 0 ? -1 : 1;
  Vec3 incCenter = I.p + I.R.col(incAxis) * (incSign * hI[incAxis]);
  int u = (incAxis + 1) % 3, v = (incAxis + 2) % 3;
  Vec3 eu = I.R.col(u) * hI[u], ev = I.R.col(v) * hI[v];
  ClipVertex poly[16], tmp[16];
  poly[0] = {incCenter + eu + ev, 0};
  poly[1] = {incCenter - eu + ev, 1};
  poly[2] = {incCenter - eu - ev, 2};
  poly[3] = {incCenter + eu - ev, 3};
  int n = 4;
  // Side planes of the reference face.
  int ru = (refAxis + 1) % 3, rv = (refAxis + 2) % 3;
  const int sideAxes[2] = {ru, rv};
  std::uint32_t plane = 0;
  for (int sa : sideAxes) {
    Vec3 ax = R.R.col(sa);
    Real c = ax.dot(R.p);
    n = clipPolygon(poly, n, ax, c + hR[sa], plane++, tmp);
    if (n == 0) return 0;
    n = clipPolygon(tmp, n, Vec3(-ax), -c + hR[sa], plane++, poly);
    if (n == 0) return 0;
  }
  Vec3 refCenter = R.p + nRef * hR[refAxis];
  // Collect points within the margin.

  ContactCandidate cands[16];
  int k = 0;
  for (int i = 0; i < n; ++i) {
    Real sep = nRef.dot(poly[i].p - refCenter);
    if (sep <= margin) cands[k++] = {poly[i].p - nRef * (sep / 2), sep, poly[i].id};
  }
  if (k == 0) return 0;
  k = reduceToFourCandidates(cands, k, nRef);
  m.normal = useB ? Vec3(-nRef) : nRef;
  std::uint32_t faceKey = (std::uint32_t(useB) << 15) | (std::uint32_t(refAxis) << 12) | (std::uint32_t(incAxis) << 10);
  for (int i = 0; i < k; ++i) addPoint(m, cands[i].p, cands[i].sep, faceKey | cands[i].id);
  return m.count;
}

// ---- capsules ----------------------------------------------------------------

int capsuleCapsule(const Xf& A, const Shape& a, const Xf& B, const Shape& b, Real margin, Manifold& m) {
  Vec3 p0 = capsuleEnd(A, a.halfHeight_m, 0), p1 = capsuleEnd(A, a.halfHeight_m, 1);
  Vec3 q0 = capsuleEnd(B, b.halfHeight_m, 0), q1 = capsuleEnd(B, b.halfHeight_m, 1);
  Vec3 da = p1 - p0, db = q1 - q0;
  Real la = da.norm(), lb = db.norm();
  // Nearly parallel segments: two points from the overlap of their extents,
  // so a capsule resting on another does not rock on a single point.
  if (la > Real(1e-6) && lb > Real(1e-6) && da.cross(db).norm() < Real(0.05) * la * lb) {
    Vec3 dir = da / la;
    Real t0 = dir.dot(q0 - p0), t1 = dir.dot(q1 - p0);
    Real lo = std::max<Real>(0, std::min(t0, t1)), hi = std::min<Real>(la, std::max(t0, t1));
    if (lo <= hi) {
      int n0 = m.count;
      for (int e = 0; e < 2; ++e) {
        Vec3 pa = p0 + dir * (e == 0 ? lo : hi);
        Real s, t;
        closestSegmentPoints(pa, pa, q0, q1, s, t);
        spheres(pa, a.radius_m, q0 + db * t, b.radius_m, margin, m, std::uint32_t(e));
      }
      if (m.count > n0) return m.count;
    }
  }
  Real s, t;
  closestSegmentPoints(p0, p1, q0, q1, s, t);
  return spheres(p0 + da * s, a.radius_m, q0 + db * t, b.radius_m, margin, m, 2);
}

// Capsule (as a) against box (as b): the segment's closest point to the box
// by alternating projection (both sets are convex, so it converges), plus
// the two end caps, so a capsule lying on a box gets two points.
int capsuleBox(const Xf& A, const Shape& a, const Xf& B, const Vec3& hB, Real margin, Manifold& m) {
  Vec3 p0 = capsuleEnd(A, a.halfHeight_m, 0), p1 = capsuleEnd(A, a.halfHeight_m, 1);
  for (int e = 0; e < 2; ++e) sphereBox(e == 0 ? p0 : p1, a.radius_m, B, hB, margin, m, std::uint32_t(e));
  if (m.count == 2) return m.count;
  Vec3 seg = p1 - p0;
  Real len2 = seg.squaredNorm();
  Real t = Real(0.5);
  for (int it = 0; it < 8; ++it) {
    Vec3 onSeg = p0 + seg * t;
    Vec3 local = B.R.transpose() * (onSeg - B.p);
    Vec3 onBox = B.p + B.R * local.cwiseMax(-hB).cwiseMin(hB);
    t = len2 > 0 ? std::clamp<Real>(seg.dot(onBox - p0) / len2, 0, 1) : 0;
  }
  if (t > Real(0.02) && t < Real(0.98)) {
    Manifold mid = m;
    mid.count = 0;
    if (sphereBox(p0 + seg * t, a.radius_m, B, hB, margin, mid, 2)) {
      // Use the middle point when it is deeper than what the caps found.
      bool deeper = m.count == 0 || mid.points[0].separation_m < m.points[0].separation_m - Real(1e-4);
      if (deeper) {
        if (m.count == 0) m.normal = mid.normal;
        addPoint(m, mid.points[0].point_m, mid.points[0].separation_m, 2);
      }
    }
  }
  return m.count;
}

// ---- cylinders (convex_collision.cpp) ------------------------------------------

/// Any convex shape (as a) against a cylinder (as b), through their support mappings.
int convexCylinder(const Shape& a, const Xf& A, const Shape& b, const Xf& B, Real margin, Manifold& m) {
  ConvexPiece pa, pb;
  if (!convexPiece(a, Pose{A.p, A.R}, &pa) || !convexPiece(b, Pose{B.p, B.R}, &pb)) return 0;
  return collideConvex(pa, pb, margin, m);
}

int sphereCylinder(const Vec3& c, Real r, const Xf& B, const Shape& cyl, Real margin, Manifold& m) {
  Vec3 closest, nOut;
  const Real sep = pointCylinderDistance(c, Pose{B.p, B.R}, cyl.radius_m, cyl.halfHeight_m, closest, nOut) - r;
  if (sep > margin) return 0;
  m.normal = -nOut;  // from the sphere to the cylinder
  addPoint(m, closest + nOut * (sep / 2), sep, 0);
  return m.count;
}

int planeCylinder(const Xf& plane, const Xf& B, const Shape& cyl, Real margin, Manifold& m) {
  Vec3 pts[5];
  std::uint32_t ids[5];
  const int n = cylinderSurfacePoints(Pose{B.p, B.R}, cyl.radius_m, cyl.halfHeight_m, plane.R.col(1), pts, ids);
  return planePoints(plane, pts, n, 0, margin, m, true);
}

}  // namespace

void closestSegmentPoints(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, Real& s, Real& t) {
  // Ericson, Real-Time Collision Detection 5.1.9.
  Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  Real a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr Real eps = Real(1e-12);
  if (a <= eps && e <= eps) {
    s = t = 0;
    return;
  }
  if (a <= eps) {
    s = 0;
    t = std::clamp<Real>(f / e, 0, 1);
    return;
  }
  Real c = d1.dot(r);
  if (e <= eps) {
    t = 0;
    s = std::clamp<Real>(-c / a, 0, 1);
    return;
  }
  Real b = d1.dot(d2), denom = a * e - b * b;
  s = denom > eps ? std::clamp<Real>((b * f - c * e) / denom, 0, 1) : 0;
  t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp<Real>(-c / a, 0, 1);
  } else if (t > 1) {
    t = 1;
    s = std::clamp<Real>((b - c) / a, 0, 1);
  }
}

int collideSpheresSwept(const Body& a, const Body& b, const Vec3& motion, Real spec, Manifold& m) {
  // Speculative contacts take the normal from the positions at the start of
  // the step. For two fast spheres that only graze each other, that normal
  // points along the line of centres now, not at impact, so the pair would
  // bounce back as if head-on (and pairs that pass each other would be
  // stopped by a contact that never happens). Instead solve
  //   |d + s D| = R,  s in [0, 1],  d = cb - ca, D = relative motion,
  // for the first touch s*, and use n = (d + s* D) / R. Along that n the
  // separation now is n.d - R = -s* n.D, so the solver's speculative bias
  // (separation / h) lets them approach exactly until the impact.
  m.count = 0;
  const Real ra = a.shape.radius_m, rb = b.shape.radius_m, R = ra + rb;
  const Vec3 d = b.position_m - a.position_m;
  const Real c = d.squaredNorm() - R * R;
  if (d.norm() - R <= spec) return spheres(a.position_m, ra, b.position_m, rb, spec, m, 0);
  const Real qa = motion.squaredNorm(), qb = d.dot(motion);
  if (qb >= 0 || qa <= 0) return 0;  // moving apart
  const Real disc = qb * qb - qa * c;
  if (disc < 0) return 0;  // they pass each other
  const Real s = (-qb - std::sqrt(disc)) / qa;
  if (s > 1) return 0;  // not this step
  Vec3 n = d + motion * std::max<Real>(s, 0);
  n.normalize();
  const Real sep = std::max<Real>(n.dot(d) - R, 0);
  m.normal = n;
  addPoint(m, a.position_m + n * (ra + sep / 2), sep, 0);
  return m.count;
}

int collideShapes(const Shape& shapeA, const Vec3& pa, const Quat& qa, const Shape& shapeB, const Vec3& pb,
                  const Quat& qb, Real margin, Manifold& m) {
  m.count = 0;
  // Order by shape type so each pair has one routine; flip the normal back.
  const bool swapped = shapeA.type > shapeB.type;
  const Shape& sa = swapped ? shapeB : shapeA;
  const Shape& sb = swapped ? shapeA : shapeB;
  const Xf A = swapped ? Xf{pb, qb.toRotationMatrix()} : Xf{pa, qa.toRotationMatrix()};
  const Xf B = swapped ? Xf{pa, qa.toRotationMatrix()} : Xf{pb, qb.toRotationMatrix()};
  const Pose PA{A.p, A.R}, PB{B.p, B.R};
  switch (sa.type) {
    case ShapeType::Sphere:
      switch (sb.type) {
        case ShapeType::Sphere: spheres(A.p, sa.radius_m, B.p, sb.radius_m, margin, m, 0); break;
        case ShapeType::Box: sphereBox(A.p, sa.radius_m, B, sb.halfExtents_m, margin, m, 0); break;
        case ShapeType::Capsule: {
          Vec3 q0 = capsuleEnd(B, sb.halfHeight_m, 0), q1 = capsuleEnd(B, sb.halfHeight_m, 1);
          Real s, t;
          closestSegmentPoints(A.p, A.p, q0, q1, s, t);
          spheres(A.p, sa.radius_m, q0 + (q1 - q0) * t, sb.radius_m, margin, m, 0);
          break;
        }
        case ShapeType::Hull: collideSphereHull(A.p, sa.radius_m, PB, *sb.hull, margin, m, 0); break;
        case ShapeType::Plane: planePoints(B, &A.p, 1, sa.radius_m, margin, m, false); break;
        case ShapeType::Compound: break;
        case ShapeType::Mesh: break;
        case ShapeType::Cylinder: sphereCylinder(A.p, sa.radius_m, B, sb, margin, m); break;
      }
      break;
    case ShapeType::Box:
      switch (sb.type) {
        case ShapeType::Box: boxBox(A, sa.halfExtents_m, B, sb.halfExtents_m, margin, m); break;
        case ShapeType::Capsule:
          capsuleBox(B, sb, A, sa.halfExtents_m, margin, m);
          m.normal = -m.normal;  // computed capsule -> box
          break;
        case ShapeType::Hull:
          collidePolytopes(PA, unitCubeHull(), sa.halfExtents_m, PB, *sb.hull, Vec3::Ones(), margin, m);
          break;
        case ShapeType::Plane: {
          auto v = boxVertices(A, sa.halfExtents_m);
          planePoints(B, v.data(), 8, 0, margin, m, false);
          break;
        }
        case ShapeType::Cylinder: convexCylinder(sa, A, sb, B, margin, m); break;
        default: break;
      }
      break;
    case ShapeType::Capsule:
      switch (sb.type) {
        case ShapeType::Capsule: capsuleCapsule(A, sa, B, sb, margin, m); break;
        case ShapeType::Hull:
          collideCapsuleHull(capsuleEnd(A, sa.halfHeight_m, 0), capsuleEnd(A, sa.halfHeight_m, 1), sa.radius_m, PB,
                             *sb.hull, margin, m);
          break;
        case ShapeType::Plane: {
          Vec3 ends[2] = {capsuleEnd(A, sa.halfHeight_m, 0), capsuleEnd(A, sa.halfHeight_m, 1)};
          planePoints(B, ends, 2, sa.radius_m, margin, m, false);
          break;
        }
        case ShapeType::Cylinder: convexCylinder(sa, A, sb, B, margin, m); break;
        default: break;
      }
      break;
    case ShapeType::Hull:
      switch (sb.type) {
        case ShapeType::Hull: collidePolytopes(PA, *sa.hull, Vec3::Ones(), PB, *sb.hull, Vec3::Ones(), margin, m); break;
        case ShapeType::Plane: collideHullPlane(PA, *sa.hull, B.p, B.R.col(1), margin, m); break;
        case ShapeType::Cylinder: convexCylinder(sa, A, sb, B, margin, m); break;
        default: break;
      }
      break;
    case ShapeType::Plane:  // plane-plane never collides
      if (sb.type == ShapeType::Cylinder) planeCylinder(A, B, sb, margin, m);
      break;
    case ShapeType::Compound: break;  // children are handled by collidePair
    case ShapeType::Mesh: break;      // collidePair hands meshes to collideMeshPair
    case ShapeType::Cylinder: convexCylinder(sa, A, sb, B, margin, m); break;  // cylinder-cylinder
  }
  if (swapped && m.count > 0) m.normal = -m.normal;
  return m.count;
}

int collideBodies(const Body& a, const Body& b, Real margin, Manifold& m) {
  return collideShapes(a.shape, a.position_m, a.orientation, b.shape, b.position_m, b.orientation, margin, m);
}

const Shape& childShape(const Shape& s, std::uint16_t child) {
  return s.type == ShapeType::Compound ? s.compound->children[child].shape : s;
}

int collidePair(const Body& a, const Body& b, Real margin, std::vector<Manifold>& out) {
  out.clear();
  if (a.shape.type == ShapeType::Mesh || b.shape.type == ShapeType::Mesh)
    return collideMeshPair(a, b, margin, out, nullptr);
  const bool ca = a.shape.type == ShapeType::Compound, cb = b.shape.type == ShapeType::Compound;
  if (!ca && !cb) {
    Manifold m;
    if (collideBodies(a, b, margin, m) > 0) out.push_back(m);
    return int(out.size());
  }
  // Child by child; children whose boxes (grown by the margin) miss the other
  // body's box are skipped.
  auto children = [](const Body& body, auto&& fn) {
    if (body.shape.type != ShapeType::Compound) {
      fn(std::uint16_t(0), body.shape, body.position_m, body.orientation);
      return;
    }
    const auto& kids = body.shape.compound->children;
    for (std::size_t i = 0; i < kids.size(); ++i)
      fn(std::uint16_t(i), kids[i].shape, Vec3(body.position_m + body.orientation * kids[i].position_m),
         Quat(body.orientation * kids[i].orientation));
  };
  Vec3 loA, hiA, loB, hiB;
  a.shape.bounds(a.position_m, a.orientation, &loA, &hiA);
  b.shape.bounds(b.position_m, b.orientation, &loB, &hiB);
  const Vec3 grow = Vec3::Constant(margin);
  children(a, [&](std::uint16_t ia, const Shape& sa, const Vec3& pa, const Quat& qa) {
    Vec3 l, h;
    sa.bounds(pa, qa, &l, &h);
    if (sa.type != ShapeType::Plane &&
        ((l.array() - margin > hiB.array()).any() || (h.array() + margin < loB.array()).any()))
      return;
    children(b, [&](std::uint16_t ib, const Shape& sb, const Vec3& pb, const Quat& qb) {
      Vec3 l2, h2;
      sb.bounds(pb, qb, &l2, &h2);
      if (sa.type != ShapeType::Plane && sb.type != ShapeType::Plane &&
          ((l.array() - grow.array() > h2.array()).any() || (h.array() + grow.array() < l2.array()).any()))
        return;
      Manifold m;
      if (collideShapes(sa, pa, qa, sb, pb, qb, margin, m) == 0) return;
      m.childA = ia;
      m.childB = ib;
      out.push_back(m);
    });
  });
  return int(out.size());
}

}  // namespace tumble::physics
