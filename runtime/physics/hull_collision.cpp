// Convex hull contacts.
//
// Hull-hull (and hull-box, the box taken as a scaled cube hull) uses the
// separating-axis test, not GJK/EPA: SAT gives the contact normal and the
// face pair directly, and clipping the incident face against the reference
// face's side planes then gives a full manifold in one pass, with feature
// ids (reference face, incident face, clip plane / vertex) that stay the
// same while the same faces touch - what warm starting and resting stacks
// need. GJK/EPA gives one point per step and needs a persistent manifold
// cache that adds and drops points as bodies roll, which is the source of
// jitter in resting contact; it wins only for curved shapes, which we do not
// have here (spheres and capsules use their closest points below). Axes:
// every face normal of both hulls, and the edge pairs whose arcs cross on the
// Gauss map (Gregorius, "The Separating Axis Test between Convex Polyhedra",
// GDC 2013): only those edge pairs form a face of the Minkowski difference,
// so only their cross products can be separating axes, and the separation
// along one is the distance between the edges' lines (no support search).
// Face axes win over nearly equal edge axes (kFaceBias) so resting hulls keep
// a stable face manifold, as boxBox does (narrow_phase.cpp).
//
// Sphere-hull: the exact closest point (inside: the least deep face). Capsule-
// hull: the two end caps as spheres plus the segment's closest point found by
// alternating projection, like capsuleBox. Hull-plane: every vertex within
// the margin, reduced to four that keep the support polygon.
#include "physics/internal/hull_collision.h"

#include <algorithm>
#include <array>
#include <vector>

#include "physics/internal/narrow_phase.h"

namespace tumble::physics {
namespace {

constexpr Real kClipTolerance_m = Real(1e-3);  // as in boxBox: corners on side planes count as inside
constexpr Real kFaceBiasRel = Real(0.95), kFaceBiasAbs_m = Real(0.005);

/// A hull in world space (scratch reused between calls).
struct WorldHull {
  const ConvexHull* h = nullptr;
  std::vector<Vec3> v, n;
  std::vector<Real> d;
  Vec3 centre = Vec3::Zero();
  void set(const Pose& P, const ConvexHull& hull, const Vec3& scale) {
    h = &hull;
    v.resize(hull.vertices_m.size());
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = P.p + P.R * hull.vertices_m[i].cwiseProduct(scale);
    n.resize(hull.faces.size());
    d.resize(hull.faces.size());
    for (std::size_t f = 0; f < n.size(); ++f) {
      const HullFace& face = hull.faces[f];
      n[f] = (P.R * face.normal.cwiseQuotient(scale)).normalized();
      d[f] = n[f].dot(v[hull.faceVertices[face.first]]);
    }
    centre = P.p;
  }
  const Vec3& faceVertex(std::uint32_t f, std::uint32_t k) const {
    const HullFace& face = h->faces[f];
    return v[h->faceVertices[face.first + (k % face.count)]];
  }
};

struct Scratch {
  WorldHull a, b;
  std::vector<std::pair<Vec3, std::uint32_t>> poly, tmp;
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

/// Largest separation over the face normals of `ref` (minimum of the other's vertices along each).
Real faceQuery(const WorldHull& ref, const WorldHull& other, int& bestFace) {
  Real best = -std::numeric_limits<Real>::max();
  for (std::size_t f = 0; f < ref.n.size(); ++f) {
    Real lo = std::numeric_limits<Real>::max();
    for (const Vec3& v : other.v) lo = std::min(lo, ref.n[f].dot(v));
    const Real s = lo - ref.d[f];
    if (s > best) best = s, bestFace = int(f);
  }
  return best;
}

// Gregorius: edges A (faces with normals a, b) and B (c, d) build a face of
// the Minkowski difference when the arcs ab and (-c)(-d) cross on the unit sphere.
bool minkowskiFace(const Vec3& a, const Vec3& b, const Vec3& bxa, const Vec3& c, const Vec3& d, const Vec3& dxc) {
  const Real cba = c.dot(bxa), dba = d.dot(bxa), adc = a.dot(dxc), bdc = b.dot(dxc);
  return cba * dba < 0 && adc * bdc < 0 && cba * bdc > 0;
}

Real edgeQuery(const WorldHull& A, const WorldHull& B, int& bestA, int& bestB, Vec3& bestAxis) {
  Real best = -std::numeric_limits<Real>::max();
  for (std::size_t i = 0; i < A.h->edges.size(); ++i) {
    const HullEdge& ea = A.h->edges[i];
    const Vec3 &a = A.n[ea.face0], &b = A.n[ea.face1];
    const Vec3 pa = A.v[ea.v0], da = A.v[ea.v1] - pa;
    for (std::size_t j = 0; j < B.h->edges.size(); ++j) {
      const HullEdge& eb = B.h->edges[j];
      const Vec3 c = -B.n[eb.face0], d = -B.n[eb.face1];
      if (!minkowskiFace(a, b, b.cross(a), c, d, d.cross(c))) continue;
      const Vec3 pb = B.v[eb.v0], db = B.v[eb.v1] - pb;
      Vec3 axis = da.cross(db);
      const Real len = axis.norm();
      if (len < Real(1e-5) * da.norm() * db.norm()) continue;  // parallel: covered by the face axes
      axis /= len;
      if (axis.dot(pa - A.centre) < 0) axis = -axis;
      const Real s = axis.dot(pb - pa);
      if (s > best) best = s, bestA = int(i), bestB = int(j), bestAxis = axis;
    }
  }
  return best;
}

int clip(const std::vector<std::pair<Vec3, std::uint32_t>>& in, const Vec3& n, Real d, std::uint32_t plane,
         std::vector<std::pair<Vec3, std::uint32_t>>& out) {
  out.clear();
  d += kClipTolerance_m;
  const std::size_t k = in.size();
  for (std::size_t i = 0; i < k; ++i) {
    const auto& a = in[i];
    const auto& b = in[(i + 1) % k];
    const Real da = n.dot(a.first) - d, db = n.dot(b.first) - d;
    if (da <= 0) out.push_back(a);
    if ((da <= 0) != (db <= 0))
      out.emplace_back(a.first + (b.first - a.first) * (da / (da - db)),
                       0x200u | ((plane & 0x1Fu) << 4) | std::uint32_t(i & 0xF));
  }
  return int(out.size());
}

int faceContact(const WorldHull& R, int refFace, const WorldHull& I, bool refIsB, Real margin, Manifold& m) {
  Scratch& s = scratch();
  const Vec3 nRef = R.n[refFace];
  // Incident face: the face of I most anti-parallel to the reference normal.
  int inc = 0;
  Real lowest = std::numeric_limits<Real>::max();
  for (std::size_t f = 0; f < I.n.size(); ++f)
    if (Real dd = I.n[f].dot(nRef); dd < lowest) lowest = dd, inc = int(f);
  const HullFace& incFace = I.h->faces[inc];
  s.poly.clear();
  for (std::uint32_t k = 0; k < incFace.count; ++k) s.poly.emplace_back(I.faceVertex(inc, k), k & 0xFF);
  const HullFace& refF = R.h->faces[refFace];
  for (std::uint32_t k = 0; k < refF.count; ++k) {
    const Vec3 a = R.faceVertex(refFace, k), b = R.faceVertex(refFace, k + 1);
    Vec3 side = (b - a).cross(nRef);
    const Real len = side.norm();
    if (len <= 0) continue;
    side /= len;
    if (clip(s.poly, side, side.dot(a), k, s.tmp) == 0) return 0;
    s.poly.swap(s.tmp);
  }
  thread_local std::vector<ContactCandidate> cands;
  cands.clear();
  for (const auto& [p, id] : s.poly) {
    const Real sep = nRef.dot(p) - R.d[refFace];
    if (sep <= margin) cands.push_back({p - nRef * (sep / 2), sep, id});
  }
  if (cands.empty()) return 0;
  const int k = reduceToFourCandidates(cands.data(), int(cands.size()), nRef);
  m.normal = refIsB ? Vec3(-nRef) : nRef;
  const std::uint32_t key =
      (std::uint32_t(refIsB) << 31) | ((std::uint32_t(refFace) & 0x3FFu) << 20) | ((std::uint32_t(inc) & 0x3FFu) << 10);
  for (int i = 0; i < k; ++i) addPoint(m, cands[i].p, cands[i].sep, key | (cands[i].id & 0x3FFu));
  return m.count;
}

}  // namespace

const ConvexHull& unitCubeHull() {
  static const ConvexHull cube = [] {
    std::array<Vec3, 8> p;
    for (int i = 0; i < 8; ++i) p[i] = Vec3((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    return computeConvexHull(p).value();
  }();
  return cube;
}

int collidePolytopes(const Pose& PA, const ConvexHull& ha, const Vec3& scaleA, const Pose& PB, const ConvexHull& hb,
                     const Vec3& scaleB, Real margin, Manifold& m) {
  Scratch& s = scratch();
  s.a.set(PA, ha, scaleA);
  s.b.set(PB, hb, scaleB);
  int faceA = 0, faceB = 0, edgeA = -1, edgeB = -1;
  const Real sepA = faceQuery(s.a, s.b, faceA);
  if (sepA > margin) return 0;
  const Real sepB = faceQuery(s.b, s.a, faceB);
  if (sepB > margin) return 0;
  Vec3 axis = Vec3::Zero();
  const Real sepE = edgeQuery(s.a, s.b, edgeA, edgeB, axis);
  if (sepE > margin) return 0;
  const bool useB = sepB > kFaceBiasRel * sepA + kFaceBiasAbs_m;
  const Real sepFace = useB ? sepB : sepA;
  if (edgeA >= 0 && sepE > kFaceBiasRel * sepFace + kFaceBiasAbs_m) {
    const HullEdge& ea = ha.edges[edgeA];
    const HullEdge& eb = hb.edges[edgeB];
    const Vec3 a0 = s.a.v[ea.v0], a1 = s.a.v[ea.v1], b0 = s.b.v[eb.v0], b1 = s.b.v[eb.v1];
    Real u, w;
    closestSegmentPoints(a0, a1, b0, b1, u, w);
    m.normal = axis;
    addPoint(m, (a0 + (a1 - a0) * u + b0 + (b1 - b0) * w) / 2, sepE,
             0x40000000u | ((std::uint32_t(edgeA) & 0x7FFFu) << 15) | (std::uint32_t(edgeB) & 0x7FFFu));
    return m.count;
  }
  return useB ? faceContact(s.b, faceB, s.a, true, margin, m) : faceContact(s.a, faceA, s.b, false, margin, m);
}

Real pointHullDistance(const Vec3& pw, const Pose& P, const ConvexHull& h, Vec3& closest, Vec3& normal) {
  const Vec3 q = P.R.transpose() * (pw - P.p);
  int deepest = 0;
  Real maxSep = -std::numeric_limits<Real>::max();
  for (std::size_t f = 0; f < h.faces.size(); ++f)
    if (Real sf = h.faces[f].normal.dot(q) - h.faces[f].offset_m; sf > maxSep) maxSep = sf, deepest = int(f);
  if (maxSep <= 0) {  // inside: out through the least deep face
    const Vec3& n = h.faces[deepest].normal;
    closest = P.p + P.R * (q - n * maxSep);
    normal = P.R * n;
    return maxSep;
  }
  // Outside: the closest point lies on a face that faces the point.
  Real best2 = std::numeric_limits<Real>::max();
  Vec3 bestQ = q;
  for (const HullFace& f : h.faces) {
    const Real sf = f.normal.dot(q) - f.offset_m;
    if (sf <= 0) continue;
    const Vec3 onPlane = q - f.normal * sf;
    bool inside = true;
    for (std::uint32_t k = 0; k < f.count && inside; ++k) {
      const Vec3& a = h.vertices_m[h.faceVertices[f.first + k]];
      const Vec3& b = h.vertices_m[h.faceVertices[f.first + (k + 1) % f.count]];
      inside = (b - a).cross(f.normal).dot(onPlane - a) <= 0;
    }
    if (inside) {
      if (sf * sf < best2) best2 = sf * sf, bestQ = onPlane;
      continue;
    }
    for (std::uint32_t k = 0; k < f.count; ++k) {
      const Vec3& a = h.vertices_m[h.faceVertices[f.first + k]];
      const Vec3& b = h.vertices_m[h.faceVertices[f.first + (k + 1) % f.count]];
      const Vec3 ab = b - a;
      const Real t = std::clamp<Real>(ab.dot(q - a) / ab.squaredNorm(), 0, 1);
      const Vec3 c = a + ab * t;
      if (Real d2 = (q - c).squaredNorm(); d2 < best2) best2 = d2, bestQ = c;
    }
  }
  const Real dist = std::sqrt(best2);
  closest = P.p + P.R * bestQ;
  normal = dist > 0 ? Vec3(P.R * ((q - bestQ) / dist)) : Vec3(P.R * h.faces[deepest].normal);
  return dist;
}

int collideSphereHull(const Vec3& c, Real r, const Pose& B, const ConvexHull& h, Real margin, Manifold& m,
                      std::uint32_t id) {
  Vec3 closest, nHull;
  const Real sep = pointHullDistance(c, B, h, closest, nHull) - r;
  if (sep > margin) return 0;
  if (m.count == 0) m.normal = -nHull;  // from the sphere to the hull
  addPoint(m, closest + nHull * (sep / 2), sep, id);
  return m.count;
}

int collideCapsuleHull(const Vec3& p0, const Vec3& p1, Real r, const Pose& B, const ConvexHull& h, Real margin,
                       Manifold& m) {
  collideSphereHull(p0, r, B, h, margin, m, 0);
  collideSphereHull(p1, r, B, h, margin, m, 1);
  if (m.count == 2) return m.count;
  const Vec3 seg = p1 - p0;
  const Real len2 = seg.squaredNorm();
  Real t = Real(0.5);
  Vec3 closest, n;
  for (int it = 0; it < 8; ++it) {
    pointHullDistance(p0 + seg * t, B, h, closest, n);
    t = len2 > 0 ? std::clamp<Real>(seg.dot(closest - p0) / len2, 0, 1) : 0;
  }
  if (t > Real(0.02) && t < Real(0.98)) {
    Manifold mid;
    if (collideSphereHull(p0 + seg * t, r, B, h, margin, mid, 2)) {
      const bool deeper = m.count == 0 || mid.points[0].separation_m < m.points[0].separation_m - Real(1e-4);
      if (deeper) {
        if (m.count == 0) m.normal = mid.normal;
        addPoint(m, mid.points[0].point_m, mid.points[0].separation_m, 2);
      }
    }
  }
  return m.count;
}

int collideHullPlane(const Pose& A, const ConvexHull& h, const Vec3& planePoint, const Vec3& normal, Real margin,
                     Manifold& m) {
  thread_local std::vector<ContactCandidate> cands;
  cands.clear();
  for (std::size_t i = 0; i < h.vertices_m.size(); ++i) {
    const Vec3 v = A.p + A.R * h.vertices_m[i];
    const Real sep = normal.dot(v - planePoint);
    if (sep <= margin) cands.push_back({v - normal * (sep / 2), sep, std::uint32_t(i)});
  }
  if (cands.empty()) return 0;
  const int k = reduceToFourCandidates(cands.data(), int(cands.size()), normal);
  m.normal = -normal;  // from the hull to the plane
  for (int i = 0; i < k; ++i) addPoint(m, cands[i].p, cands[i].sep, cands[i].id);
  return m.count;
}

bool rayHull(const Vec3& o, const Vec3& d, Real maxT, const Pose& P, const ConvexHull& h, Real inflate, Real& tHit,
             Vec3& nHit) {
  const Vec3 lo = P.R.transpose() * (o - P.p), ld = P.R.transpose() * d;
  Real tEnter = 0, tExit = maxT;
  int enterFace = -1;
  for (std::size_t f = 0; f < h.faces.size(); ++f) {
    const HullFace& face = h.faces[f];
    const Real denom = face.normal.dot(ld);
    const Real dist = face.offset_m + inflate - face.normal.dot(lo);  // > 0: origin inside this plane
    if (std::abs(denom) < Real(1e-12)) {
      if (dist < 0) return false;
      continue;
    }
    const Real t = dist / denom;
    if (denom < 0) {
      if (t > tEnter) tEnter = t, enterFace = int(f);
    } else {
      tExit = std::min(tExit, t);
    }
    if (tEnter > tExit) return false;
  }
  tHit = tEnter;
  nHit = enterFace >= 0 ? Vec3(P.R * h.faces[enterFace].normal) : Vec3(-d);
  return true;
}

}  // namespace tumble::physics
