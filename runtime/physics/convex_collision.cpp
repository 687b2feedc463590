// Contacts of cylinders: GJK, EPA and a manifold from the touching features.
//
// Why not the separating-axis test the boxes and hulls use
// (hull_collision.cpp): a cylinder's side is curved, so the axes that can
// separate it from another shape are infinitely many (every direction from
// its rim to a vertex or an edge of the other shape). Its support mapping,
// on the other hand, is exact and cheap: the point farthest along d is on
// the cap rim, at the cap on d's side of the axis, along d's component
// across the axis. So a cylinder against any convex shape goes through the
// support mappings (as in Jolt, Bullet and PhysX):
//
// 1. GJK (Gilbert, Johnson and Keerthi 1988; van den Bergen, Collision
//    Detection in Interactive 3D Environments, ch. 4) finds the distance
//    between the shapes and the direction between their closest points,
//    stopping early once a lower bound of the distance exceeds the margin.
//    The closest point of a simplex to the origin is found by Voronoi
//    regions (Ericson, Real-Time Collision Detection 5.1).
// 2. When they overlap, EPA (van den Bergen 2001) grows a polytope inside
//    the Minkowski difference A - B towards its boundary nearest the origin:
//    the penetration depth and the normal. Both run in double: their
//    tolerances (kDistanceTolerance_m, kDepthTolerance_m) decide when a
//    curved rim counts as found, and float round-off would be of their size.
// 3. One point is not enough for a resting contact (a cylinder on its cap
//    would tip about it, one on its side would spin about it). So the
//    supporting feature of each shape along the normal is taken - a face
//    (a box or hull face, a cap as an octagon of rim points at fixed body
//    angles), a line (the cylinder's side, a capsule's core, a box or hull
//    edge) or a point - and the one that is a face becomes the reference:
//    the other feature is clipped against its side planes (as boxBox does)
//    and each point keeps its separation from the reference plane. Two
//    parallel lines (cylinder on cylinder, side by side) give the two ends
//    of their overlap. Anything else is the single GJK / EPA point.
//    A feature counts as a face or a line when it is within kFeatureSin
//    (2 degrees) of perpendicular to the normal; a cylinder tipped more than
//    that rests on its rim, one point, which is what a real one does.
//    Feature ids follow hull_collision.cpp's layout (bit 31: b owns the
//    reference face; 0x200: a point made by clipping), so triangle meshes
//    treat cylinder rim points on a triangle as the piece's own vertices.
//
// Sphere against cylinder is the closest point (pointCylinderDistance), and
// a cylinder against a plane or the height field takes its candidate points
// from cylinderSurfacePoints (the deepest rim point of each cap, three more
// on the lower cap), as boxes take their corners.
#include "physics/internal/convex_collision.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace tumble::physics {
namespace {

using V3 = Eigen::Vector3d;

constexpr double kDistanceTolerance_m = 1e-6;  ///< GJK stops when the distance bound is this tight
constexpr double kDepthTolerance_m = 1e-5;     ///< EPA stops when the polytope is this close to the boundary
constexpr int kMaxGjkIterations = 64;
constexpr int kMaxEpaIterations = 64;
constexpr Real kClipTolerance_m = Real(1e-3);  ///< as in boxBox: points on a side plane count as inside
constexpr int kCapPoints = 8;                  ///< rim points that stand for a cap

struct SupportPoint {
  V3 w, a, b;  ///< w = a - b
};

SupportPoint supportOf(const ConvexPiece& A, const ConvexPiece& B, const V3& d) {
  const Vec3 df = d.cast<Real>();
  const Vec3 sa = A.support(df), sb = B.support(Vec3(-df));
  return {sa.cast<double>() - sb.cast<double>(), sa.cast<double>(), sb.cast<double>()};
}

/// Reduces simplex s (n points) to the smallest sub-simplex whose hull
/// holds the point closest to the origin; sets v and the weights. Returns
/// false when a tetrahedron contains the origin.
bool closestOnSimplex(SupportPoint* s, int& n, double* lambda, V3& v) {
  auto keep = [&](std::initializer_list<int> idx, std::initializer_list<double> w) {
    SupportPoint t[4];
    int k = 0;
    for (int i : idx) t[k++] = s[i];
    k = 0;
    for (double x : w) lambda[k++] = x;
    for (int i = 0; i < k; ++i) s[i] = t[i];
    n = k;
    v = V3::Zero();
    for (int i = 0; i < n; ++i) v += lambda[i] * s[i].w;
  };
  auto triangle = [&](int ia, int ib, int ic, SupportPoint* out, int& outN, double* outL) {
    const V3 &a = s[ia].w, &b = s[ib].w, &c = s[ic].w;
    const V3 ab = b - a, ac = c - a, ap = -a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    auto set = [&](std::initializer_list<int> idx, std::initializer_list<double> w) {
      int k = 0;
      for (int i : idx) out[k++] = s[i];
      outN = k;
      k = 0;
      for (double x : w) outL[k++] = x;
    };
    if (d1 <= 0 && d2 <= 0) return set({ia}, {1});
    const V3 bp = -b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return set({ib}, {1});
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
      const double t = d1 / (d1 - d3);
      return set({ia, ib}, {1 - t, t});
    }
    const V3 cp = -c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return set({ic}, {1});
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
      const double t = d2 / (d2 - d6);
      return set({ia, ic}, {1 - t, t});
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
      const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      return set({ib, ic}, {1 - t, t});
    }
    const double denom = 1 / (va + vb + vc);
    const double bw = vb * denom, cw = vc * denom;
    set({ia, ib, ic}, {1 - bw - cw, bw, cw});
  };
  auto adopt = [&](SupportPoint* t, int k, const double* l) {
    for (int i = 0; i < k; ++i) s[i] = t[i], lambda[i] = l[i];
    n = k;
    v = V3::Zero();
    for (int i = 0; i < n; ++i) v += lambda[i] * s[i].w;
  };
  switch (n) {
    case 1: keep({0}, {1}); return true;
    case 2: {
      const V3 ab = s[1].w - s[0].w;
      const double len2 = ab.squaredNorm();
      const double t = len2 > 0 ? -s[0].w.dot(ab) / len2 : 0;
      if (t <= 0) keep({0}, {1});
      else if (t >= 1) keep({1}, {1});
      else keep({0, 1}, {1 - t, t});
      return true;
    }
    case 3: {
      SupportPoint t[3];
      double l[3];
      int k = 0;
      triangle(0, 1, 2, t, k, l);
      adopt(t, k, l);
      return true;
    }
    default: {
      // Faces of the tetrahedron that the origin lies outside of.
      static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 3, 1, 2}, {0, 2, 3, 1}, {1, 3, 2, 0}};
      double best = std::numeric_limits<double>::max();
      SupportPoint bestT[3];
      double bestL[3];
      int bestK = 0;
      bool outside = false;
      for (const auto& f : kFaces) {
        const V3 &a = s[f[0]].w, &b = s[f[1]].w, &c = s[f[2]].w, &d = s[f[3]].w;
        const V3 nrm = (b - a).cross(c - a);
        const double sideOrigin = -a.dot(nrm), sideD = (d - a).dot(nrm);
        if (sideOrigin * sideD >= 0 && std::abs(sideD) > 1e-18) continue;  // origin on d's side
        outside = true;
        SupportPoint t[3];
        double l[3];
        int k = 0;
        triangle(f[0], f[1], f[2], t, k, l);
        V3 p = V3::Zero();
        for (int i = 0; i < k; ++i) p += l[i] * t[i].w;
        if (p.squaredNorm() < best) {
          best = p.squaredNorm();
          std::copy(t, t + k, bestT);
          std::copy(l, l + k, bestL);
          bestK = k;
        }
      }
      if (!outside) return false;
      adopt(bestT, bestK, bestL);
      return true;
    }
  }
}

struct GjkResult {
  bool overlap = false;
  double distance = 0;
  V3 pointA = V3::Zero(), pointB = V3::Zero();
  SupportPoint simplex[4];
  int n = 0;
};

/// GJK distance. Returns false when the shapes are provably more than margin apart.
bool gjk(const ConvexPiece& A, const ConvexPiece& B, double margin, GjkResult& r) {
  V3 d = (B.pose.p - A.pose.p).cast<double>();
  if (d.squaredNorm() < 1e-18) d = V3::UnitY();
  SupportPoint* s = r.simplex;
  double lambda[4] = {1, 0, 0, 0};
  s[0] = supportOf(A, B, -d);
  int n = 1;
  V3 v = s[0].w;
  for (int it = 0; it < kMaxGjkIterations; ++it) {
    const double vv = v.squaredNorm();
    if (vv < 1e-18) {
      r.overlap = true;
      break;
    }
    const SupportPoint w = supportOf(A, B, -v);
    const double vw = v.dot(w.w);
    const double vlen = std::sqrt(vv);
    if (vw > 0 && vw / vlen > margin) return false;  // a separating plane farther than the margin
    if (vlen - vw / vlen <= kDistanceTolerance_m) break;
    bool repeated = false;
    for (int i = 0; i < n; ++i) repeated |= (s[i].w - w.w).squaredNorm() < 1e-24;
    if (repeated) break;
    s[n++] = w;
    if (!closestOnSimplex(s, n, lambda, v)) {
      r.overlap = true;
      break;
    }
  }
  r.n = n;
  if (!r.overlap) {
    r.pointA = r.pointB = V3::Zero();
    for (int i = 0; i < n; ++i) r.pointA += lambda[i] * s[i].a, r.pointB += lambda[i] * s[i].b;
    r.distance = v.norm();
    if (r.distance < 1e-9) r.overlap = true;
  }
  return r.distance <= margin || r.overlap;
}

/// EPA from an overlapping GJK simplex: depth, normal (from A to B) and the
/// witness points. False if the polytope cannot be built (flat shapes).
bool epa(const ConvexPiece& A, const ConvexPiece& B, const GjkResult& g, double& depth, V3& normal, V3& pointA,
         V3& pointB) {
  thread_local std::vector<SupportPoint> verts;
  struct Face {
    int a, b, c;
    V3 n;
    double d;
  };
  thread_local std::vector<Face> faces;
  thread_local std::vector<std::pair<int, int>> edges;
  verts.assign(g.simplex, g.simplex + g.n);
  // Grow the simplex to a tetrahedron.
  static const V3 kAxes[6] = {V3::UnitX(), -V3::UnitX(), V3::UnitY(), -V3::UnitY(), V3::UnitZ(), -V3::UnitZ()};
  constexpr double kEps = 1e-10;
  if (verts.size() == 1) {
    for (const V3& ax : kAxes) {
      SupportPoint p = supportOf(A, B, ax);
      if ((p.w - verts[0].w).norm() > kEps) {
        verts.push_back(p);
        break;
      }
    }
  }
  if (verts.size() == 2) {
    const V3 line = (verts[1].w - verts[0].w).normalized();
    V3 perp = line.cross(std::abs(line.x()) < 0.6 ? V3::UnitX() : V3::UnitY()).normalized();
    for (int k = 0; k < 6; ++k) {
      const V3 dir = Eigen::AngleAxisd(k * kPi / 3, line) * perp;
      SupportPoint p = supportOf(A, B, dir);
      if ((p.w - verts[0].w).cross(line).norm() > kEps) {
        verts.push_back(p);
        break;
      }
    }
  }
  if (verts.size() == 3) {
    const V3 nrm = (verts[1].w - verts[0].w).cross(verts[2].w - verts[0].w).normalized();
    for (const V3& dir : {nrm, V3(-nrm)}) {
      SupportPoint p = supportOf(A, B, dir);
      if (std::abs((p.w - verts[0].w).dot(nrm)) > kEps) {
        verts.push_back(p);
        break;
      }
    }
  }
  if (verts.size() != 4) return false;
  const V3 inside = (verts[0].w + verts[1].w + verts[2].w + verts[3].w) / 4;
  faces.clear();
  auto addFace = [&](int a, int b, int c) {
    V3 nrm = (verts[b].w - verts[a].w).cross(verts[c].w - verts[a].w);
    const double len = nrm.norm();
    if (len < 1e-18) return false;
    nrm /= len;
    if (nrm.dot(verts[a].w - inside) < 0) {
      std::swap(b, c);
      nrm = -nrm;
    }
    faces.push_back({a, b, c, nrm, nrm.dot(verts[a].w)});
    return true;
  };
  if (!addFace(0, 1, 2) || !addFace(0, 3, 1) || !addFace(0, 2, 3) || !addFace(1, 3, 2)) return false;
  std::size_t best = 0;
  for (int it = 0; it < kMaxEpaIterations; ++it) {
    best = 0;
    for (std::size_t f = 1; f < faces.size(); ++f)
      if (faces[f].d < faces[best].d) best = f;
    const Face bf = faces[best];
    const SupportPoint w = supportOf(A, B, bf.n);
    if (bf.n.dot(w.w) - bf.d < kDepthTolerance_m || faces.size() > 512) break;
    const int wi = int(verts.size());
    verts.push_back(w);
    edges.clear();
    for (std::size_t f = 0; f < faces.size();) {
      const Face& fc = faces[f];
      if (fc.n.dot(w.w - verts[fc.a].w) > 1e-12) {
        for (auto e : {std::pair{fc.a, fc.b}, std::pair{fc.b, fc.c}, std::pair{fc.c, fc.a}}) {
          auto rev = std::find(edges.begin(), edges.end(), std::pair{e.second, e.first});
          if (rev != edges.end()) edges.erase(rev);
          else edges.push_back(e);
        }
        faces[f] = faces.back();
        faces.pop_back();
      } else {
        ++f;
      }
    }
    for (const auto& [ea, eb] : edges) addFace(ea, eb, wi);
    if (faces.empty()) return false;
  }
  best = 0;
  for (std::size_t f = 1; f < faces.size(); ++f)
    if (faces[f].d < faces[best].d) best = f;
  const Face& f = faces[best];
  depth = f.d;
  normal = f.n;
  // Barycentric weights of the origin's projection on the face.
  const V3 p = f.n * f.d;
  const V3 a = verts[f.a].w, b = verts[f.b].w, c = verts[f.c].w;
  const V3 v0 = b - a, v1 = c - a, v2 = p - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double den = d00 * d11 - d01 * d01;
  double lb = den != 0 ? (d11 * d20 - d01 * d21) / den : 0, lc = den != 0 ? (d00 * d21 - d01 * d20) / den : 0;
  lb = std::clamp(lb, 0.0, 1.0);
  lc = std::clamp(lc, 0.0, 1.0 - lb);
  const double la = 1 - lb - lc;
  pointA = la * verts[f.a].a + lb * verts[f.b].a + lc * verts[f.c].a;
  pointB = la * verts[f.a].b + lb * verts[f.b].b + lc * verts[f.c].b;
  return true;
}

// ---- features -------------------------------------------------------------------

/// The part of a piece that touches a plane with outward normal dir: a face
/// (>= 3 points, cyclic order, outward normal), a line (2 points) or a point.
struct Feature {
  std::array<Vec3, 16> p;
  std::array<std::uint32_t, 16> id{};
  int count = 0;
  Vec3 normal = Vec3::UnitY();  ///< faces: outward unit normal
  std::uint32_t key = 0;        ///< which face / line of the piece (10 bits)
  bool cap = false;             ///< a cylinder cap (an octagon standing for a disc)
  void add(const Vec3& q, std::uint32_t i) {
    if (count < int(p.size())) p[std::size_t(count)] = q, id[std::size_t(count++)] = i;
  }
};

void featureOf(const ConvexPiece& piece, const Vec3& dir, Feature& f) {
  f.count = 0;
  const Mat3& R = piece.pose.R;
  const Vec3& c = piece.pose.p;
  const Vec3 dl = R.transpose() * dir;
  const Real kFeatureCos = std::sqrt(1 - kFeatureSin * kFeatureSin);
  switch (piece.kind) {
    case ConvexPiece::Kind::Sphere: break;
    case ConvexPiece::Kind::Capsule:
      if (std::abs(dl.y()) < kFeatureSin) {
        const Vec3 off = dir.normalized() * piece.radius_m;
        f.add(c - R.col(1) * piece.halfHeight_m + off, 0);
        f.add(c + R.col(1) * piece.halfHeight_m + off, 1);
        f.key = 3;
      }
      break;
    case ConvexPiece::Kind::Cylinder: {
      const Real r = piece.radius_m, hh = piece.halfHeight_m;
      if (std::abs(dl.y()) >= kFeatureCos) {
        const Real sy = dl.y() > 0 ? 1 : -1;
        // A cap tipped a little reaches deepest between two octagon points,
        // up to r (1 - cos(pi / 8)) sin(tilt) beyond them: past EPA's own
        // tolerance, the exact rim point goes in too, in its place in the ring.
        const Real across = std::hypot(dl.x(), dl.z());
        const bool addDeepest = r * (1 - std::cos(kPi / kCapPoints)) * across > Real(kDepthTolerance_m);
        Real deepestAng = addDeepest ? std::atan2(dl.z(), dl.x()) : 0;
        if (deepestAng < 0) deepestAng += 2 * kPi;
        for (int k = 0; k < kCapPoints; ++k) {
          const Real ang = Real(2) * kPi * Real(k) / kCapPoints;
          f.add(c + R * Vec3(r * std::cos(ang), sy * hh, r * std::sin(ang)), std::uint32_t(k));
          const Real next = Real(2) * kPi * Real(k + 1) / kCapPoints;
          if (addDeepest && deepestAng > ang && deepestAng < next)
            f.add(c + R * Vec3(dl.x() * r / across, sy * hh, dl.z() * r / across), std::uint32_t(kCapPoints));
        }
        f.normal = R.col(1) * sy;
        f.key = sy > 0 ? 1 : 2;
        f.cap = true;
      } else if (std::abs(dl.y()) < kFeatureSin) {
        const Vec3 u = R * Vec3(dl.x(), 0, dl.z()).normalized() * r;
        f.add(c - R.col(1) * hh + u, 0);
        f.add(c + R.col(1) * hh + u, 1);
        f.key = 3;
      }
      break;
    }
    case ConvexPiece::Kind::Box: {
      const Vec3& h = piece.halfExtents_m;
      int i = 0;
      dl.cwiseAbs().maxCoeff(&i);
      if (std::abs(dl[i]) >= kFeatureCos) {
        const Real si = dl[i] > 0 ? 1 : -1;
        const int u = (i + 1) % 3, v = (i + 2) % 3;
        const Real su[4] = {1, -1, -1, 1}, sv[4] = {1, 1, -1, -1};
        for (int k = 0; k < 4; ++k) {
          Vec3 q;
          q[i] = si * h[i];
          q[u] = su[k] * h[u];
          q[v] = sv[k] * h[v];
          f.add(c + R * q, std::uint32_t(k));
        }
        f.normal = R.col(i) * si;
        f.key = std::uint32_t(i * 2 + (si > 0));
        break;
      }
      for (int k = 0; k < 3; ++k) {
        if (std::abs(dl[k]) >= kFeatureSin) continue;
        Vec3 q;
        for (int j = 0; j < 3; ++j) q[j] = (dl[j] >= 0 ? 1 : -1) * h[j];
        q[k] = -h[k];
        f.add(c + R * q, 0);
        q[k] = h[k];
        f.add(c + R * q, 1);
        f.key = std::uint32_t(8 + k);
        break;
      }
      break;
    }
    case ConvexPiece::Kind::Hull: {
      const ConvexHull& h = *piece.hull;
      std::size_t best = 0;
      for (std::size_t k = 1; k < h.faces.size(); ++k)
        if (h.faces[k].normal.dot(dl) > h.faces[best].normal.dot(dl)) best = k;
      if (h.faces[best].normal.dot(dl) >= kFeatureCos) {
        const HullFace& face = h.faces[best];
        for (std::uint32_t k = 0; k < face.count && k < 16; ++k)
          f.add(c + R * h.vertices_m[h.faceVertices[face.first + k]], k);
        f.normal = R * face.normal;
        f.key = std::uint32_t(best) & 0x3FFu;
        break;
      }
      std::uint32_t top = 0;
      for (std::uint32_t k = 1; k < h.vertices_m.size(); ++k)
        if (h.vertices_m[k].dot(dl) > h.vertices_m[top].dot(dl)) top = k;
      for (std::size_t e = 0; e < h.edges.size(); ++e) {
        const HullEdge& edge = h.edges[e];
        if (edge.v0 != top && edge.v1 != top) continue;
        const Vec3 along = h.vertices_m[edge.v1] - h.vertices_m[edge.v0];
        if (std::abs(along.dot(dl)) >= kFeatureSin * along.norm()) continue;
        f.add(c + R * h.vertices_m[edge.v0], 0);
        f.add(c + R * h.vertices_m[edge.v1], 1);
        f.key = 0x200u | (std::uint32_t(e) & 0x1FFu);
        break;
      }
      break;
    }
  }
}

/// Clips the incident feature against the side planes of face `ref`; the
/// points left, with their separations from the reference plane, go into m.
int clipAgainstFace(const Feature& ref, const Feature& inc, bool refIsB, Real margin, Manifold& m) {
  thread_local std::vector<std::pair<Vec3, std::uint32_t>> poly, tmp;
  poly.clear();
  for (int i = 0; i < inc.count; ++i) poly.emplace_back(inc.p[std::size_t(i)], inc.id[std::size_t(i)] & 0x1FFu);
  // Orientation of the reference polygon about its normal (Newell).
  Vec3 area = Vec3::Zero();
  for (int k = 0; k < ref.count; ++k) area += ref.p[std::size_t(k)].cross(ref.p[std::size_t((k + 1) % ref.count)]);
  const Real orient = area.dot(ref.normal) >= 0 ? 1 : -1;
  for (int k = 0; k < ref.count && !poly.empty(); ++k) {
    const Vec3& a = ref.p[std::size_t(k)];
    const Vec3& b = ref.p[std::size_t((k + 1) % ref.count)];
    Vec3 side = (b - a).cross(ref.normal) * orient;
    const Real len = side.norm();
    if (len <= 0) continue;
    side /= len;
    const Real d = side.dot(a) + kClipTolerance_m;
    tmp.clear();
    const std::size_t n = poly.size();
    if (n <= 2) {  // a point or a line: keep what is inside, cut a line where it leaves
      const Real d0 = side.dot(poly[0].first) - d;
      const Real d1 = n == 2 ? side.dot(poly[1].first) - d : d0;
      if (n == 1 || (d0 <= 0 && d1 <= 0)) {
        if (d0 <= 0) tmp = poly;
      } else if ((d0 <= 0) != (d1 <= 0)) {
        const Vec3 cut = poly[0].first + (poly[1].first - poly[0].first) * (d0 / (d0 - d1));
        const std::uint32_t cutId = 0x200u | ((std::uint32_t(k) & 0x1Fu) << 4);
        tmp.push_back(d0 <= 0 ? poly[0] : std::pair{cut, cutId});
        tmp.push_back(d0 <= 0 ? std::pair{cut, cutId} : poly[1]);
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        const auto& pa = poly[i];
        const auto& pb = poly[(i + 1) % n];
        const Real da = side.dot(pa.first) - d, db = side.dot(pb.first) - d;
        if (da <= 0) tmp.push_back(pa);
        if ((da <= 0) != (db <= 0))
          tmp.emplace_back(pa.first + (pb.first - pa.first) * (da / (da - db)),
                           0x200u | ((std::uint32_t(k) & 0x1Fu) << 4) | std::uint32_t(i & 0xF));
      }
    }
    poly.swap(tmp);
  }
  ContactCandidate cands[40];
  int k = 0;
  for (const auto& [q, id] : poly) {
    const Real sep = ref.normal.dot(q - ref.p[0]);
    if (sep <= margin && k < 40) cands[k++] = {q - ref.normal * (sep / 2), sep, id};
  }
  if (k == 0) return 0;
  k = reduceToFourCandidates(cands, k, ref.normal);
  m.normal = refIsB ? Vec3(-ref.normal) : ref.normal;
  const std::uint32_t key = (std::uint32_t(refIsB) << 31) | ((ref.key & 0x3FFu) << 20) | ((inc.key & 0x3FFu) << 10);
  for (int i = 0; i < k; ++i) addPoint(m, cands[i].p, cands[i].sep, key | (cands[i].id & 0x3FFu));
  return m.count;
}

/// Two lines (nearly) parallel and both across the normal n: the two ends of their overlap.
int parallelLines(const Feature& la, const Feature& lb, const Vec3& n, Real margin, Manifold& m) {
  const Vec3 a0 = la.p[0], da = la.p[1] - la.p[0], b0 = lb.p[0], db = lb.p[1] - lb.p[0];
  const Real lenA = da.norm(), lenB = db.norm();
  if (lenA <= 0 || lenB <= 0 || da.cross(db).norm() >= kFeatureSin * lenA * lenB) return 0;
  const Vec3 dir = da / lenA;
  const Real t0 = dir.dot(b0 - a0), t1 = dir.dot(b0 + db - a0);
  const Real lo = std::max<Real>(0, std::min(t0, t1)), hi = std::min(lenA, std::max(t0, t1));
  if (lo > hi) return 0;
  ContactCandidate c[2];
  int k = 0;
  for (Real t : {lo, hi}) {
    const Vec3 qa = a0 + dir * t;
    const Real s = std::clamp<Real>(db.dot(qa - b0) / (lenB * lenB), 0, 1);
    const Vec3 qb = b0 + db * s;
    const Real sep = n.dot(qb - qa);
    if (sep <= margin) c[k++] = {(qa + qb) / 2, sep, std::uint32_t(t == lo ? 0 : 1)};
  }
  if (k == 0) return 0;
  m.normal = n;
  const std::uint32_t key = ((la.key & 0x3FFu) << 20) | ((lb.key & 0x3FFu) << 10) | 0x100u;
  for (int i = 0; i < k; ++i) addPoint(m, c[i].p, c[i].sep, key | c[i].id);
  return m.count;
}

bool isRound(const ConvexPiece& p) {
  return p.kind == ConvexPiece::Kind::Cylinder || p.kind == ConvexPiece::Kind::Capsule;
}

/// The line a feature's contact lies on, moved to the piece's core: the
/// axis of a cylinder or capsule, the edge itself for a polytope.
void coreLine(const ConvexPiece& p, const Feature& f, Vec3& l0, Vec3& l1) {
  if (isRound(p)) {
    l0 = p.pose.p - p.pose.R.col(1) * p.halfHeight_m;
    l1 = p.pose.p + p.pose.R.col(1) * p.halfHeight_m;
  } else {
    l0 = f.p[0];
    l1 = f.p[1];
  }
}

/// Two parallel lines, one of them the side of a round piece: the normal is
/// the perpendicular from one core line to the other, exactly. EPA finds it
/// only to within sqrt(2 tolerance / radius) there (the Minkowski difference
/// of two round sides is round), which would tilt a log resting on a log.
bool refineLineNormal(const ConvexPiece& A, const Feature& fa, const ConvexPiece& B, const Feature& fb, Vec3& n) {
  Vec3 a0, a1, b0, b1;
  coreLine(A, fa, a0, a1);
  coreLine(B, fb, b0, b1);
  const Vec3 da = a1 - a0, db = b1 - b0;
  const Real la = da.norm(), lb = db.norm();
  if (la <= 0 || lb <= 0 || da.cross(db).norm() >= kFeatureSin * la * lb) return false;
  const Vec3 dir = da / la;
  Vec3 d = (b0 + b1) / 2 - a0;
  d -= dir * dir.dot(d);
  const Real len = d.norm();
  if (len < Real(1e-6)) return false;
  const Vec3 refined = d / len;
  if (refined.dot(n) < std::sqrt(1 - kFeatureSin * kFeatureSin)) return false;
  n = refined;
  return true;
}

}  // namespace

Vec3 ConvexPiece::support(const Vec3& dir) const {
  const Mat3& R = pose.R;
  const Vec3 dl = R.transpose() * dir;
  switch (kind) {
    case Kind::Sphere: {
      const Real len = dir.norm();
      return len > 0 ? Vec3(pose.p + dir * (radius_m / len)) : pose.p;
    }
    case Kind::Capsule: {
      const Real len = dir.norm();
      const Vec3 end = R.col(1) * (dl.y() >= 0 ? halfHeight_m : -halfHeight_m);
      return pose.p + end + (len > 0 ? Vec3(dir * (radius_m / len)) : Vec3::Zero());
    }
    case Kind::Box: {
      Vec3 q;
      for (int i = 0; i < 3; ++i) q[i] = dl[i] >= 0 ? halfExtents_m[i] : -halfExtents_m[i];
      return pose.p + R * q;
    }
    case Kind::Hull: return pose.p + R * hull->support(dl);
    case Kind::Cylinder: {
      const Real rho = std::hypot(dl.x(), dl.z());
      Vec3 q(0, dl.y() >= 0 ? halfHeight_m : -halfHeight_m, 0);
      if (rho > 0) q.x() = dl.x() * radius_m / rho, q.z() = dl.z() * radius_m / rho;
      return pose.p + R * q;
    }
  }
  return pose.p;
}

bool convexPiece(const Shape& s, const Pose& pose, ConvexPiece* out) {
  ConvexPiece p;
  p.pose = pose;
  switch (s.type) {
    case ShapeType::Sphere: p.kind = ConvexPiece::Kind::Sphere; break;
    case ShapeType::Capsule: p.kind = ConvexPiece::Kind::Capsule; break;
    case ShapeType::Box: p.kind = ConvexPiece::Kind::Box; break;
    case ShapeType::Hull: p.kind = ConvexPiece::Kind::Hull; break;
    case ShapeType::Cylinder: p.kind = ConvexPiece::Kind::Cylinder; break;
    default: return false;
  }
  p.radius_m = s.radius_m;
  p.halfHeight_m = s.halfHeight_m;
  p.halfExtents_m = s.halfExtents_m;
  p.hull = s.hull.get();
  *out = p;
  return true;
}

int collideConvex(const ConvexPiece& A, const ConvexPiece& B, Real margin, Manifold& m) {
  m.count = 0;
  GjkResult g;
  if (!gjk(A, B, margin, g)) return 0;
  V3 n;
  double sep;
  V3 pa, pb;
  if (!g.overlap) {
    n = (g.pointB - g.pointA) / g.distance;
    sep = g.distance;
    pa = g.pointA;
    pb = g.pointB;
  } else {
    double depth;
    if (!epa(A, B, g, depth, n, pa, pb)) return 0;
    // The boundary of A - B nearest the origin lies at depth along n: moving
    // B by depth n separates them, so n runs from A to B.
    sep = -depth;
  }
  if (sep > margin) return 0;
  Vec3 nf = n.cast<Real>().normalized();
  Feature fa, fb;
  featureOf(A, nf, fa);
  featureOf(B, Vec3(-nf), fb);
  if (fa.count == 2 && fb.count == 2 && (isRound(A) || isRound(B)) && refineLineNormal(A, fa, B, fb, nf)) {
    featureOf(A, nf, fa);
    featureOf(B, Vec3(-nf), fb);
  }
  // The reference face: the face whose normal lies closer to the contact
  // normal; a polytope's face before a cylinder's cap on a tie (its polygon
  // is exact, the cap's octagon is not).
  const Real scoreA = fa.count >= 3 ? fa.normal.dot(nf) - (fa.cap ? Real(1e-4) : 0) : -2;
  const Real scoreB = fb.count >= 3 ? -fb.normal.dot(nf) - (fb.cap ? Real(1e-4) : 0) : -2;
  if (scoreA > -2 || scoreB > -2) {
    const bool refIsB = scoreB > scoreA;
    const Feature& ref = refIsB ? fb : fa;
    Feature inc = refIsB ? fa : fb;
    if (inc.count == 0) inc.add((refIsB ? pa : pb).cast<Real>(), 0x1FFu);
    if (clipAgainstFace(ref, inc, refIsB, margin, m) > 0) return m.count;
  } else if (fa.count == 2 && fb.count == 2) {
    if (parallelLines(fa, fb, nf, margin, m) > 0) return m.count;
  }
  m.count = 0;
  m.normal = nf;
  addPoint(m, ((pa + pb) / 2).cast<Real>(), Real(sep), 0x40000000u | ((fa.key & 0x3FFu) << 10) | (fb.key & 0x3FFu));
  return m.count;
}

Real pointCylinderDistance(const Vec3& p, const Pose& P, Real r, Real hh, Vec3& closest, Vec3& normal) {
  const Vec3 q = P.R.transpose() * (p - P.p);
  const Real rho = std::hypot(q.x(), q.z());
  const Vec3 radial = rho > Real(1e-9) ? Vec3(q.x() / rho, 0, q.z() / rho) : Vec3::UnitX();
  const Real dr = rho - r, dy = std::abs(q.y()) - hh;
  const Real sy = q.y() >= 0 ? 1 : -1;
  if (dr <= 0 && dy <= 0) {  // inside: out through the nearer of the side and the cap
    if (dr > dy) {
      closest = P.p + P.R * Vec3(radial.x() * r, q.y(), radial.z() * r);
      normal = P.R * radial;
      return dr;
    }
    closest = P.p + P.R * Vec3(q.x(), sy * hh, q.z());
    normal = P.R.col(1) * sy;
    return dy;
  }
  const Real rc = std::min(rho, r), yc = std::clamp(q.y(), -hh, hh);
  const Vec3 c(radial.x() * rc, yc, radial.z() * rc);
  const Vec3 d = q - c;
  const Real dist = d.norm();
  closest = P.p + P.R * c;
  normal = P.R * (d / dist);
  return dist;
}

int cylinderSurfacePoints(const Pose& P, Real r, Real hh, const Vec3& n, Vec3* pts, std::uint32_t* ids) {
  const Vec3 a = P.R.col(1);
  const Vec3 across = n - a * n.dot(a);
  // The rim direction that reaches deepest; on a cap standing (nearly) flat
  // any direction does, and the body's own x keeps the points fixed to it.
  const Vec3 u = across.norm() > Real(1e-3) ? Vec3(-across.normalized()) : Vec3(P.R.col(0));
  const Vec3 w = a.cross(u);
  const Real lower = n.dot(a) > 0 ? -1 : 1;  // the cap nearer the surface
  const Vec3 low = P.p + a * (lower * hh);
  pts[0] = P.p - a * hh + u * r;
  pts[1] = P.p + a * hh + u * r;
  pts[2] = low + w * r;
  pts[3] = low - u * r;
  pts[4] = low - w * r;
  for (std::uint32_t i = 0; i < 5; ++i) ids[i] = i;
  return 5;
}

bool rayCylinder(const Vec3& o, const Vec3& d, Real maxT, const Pose& P, Real r, Real hh, Real inflate, Real& tHit,
                 Vec3& nHit) {
  const Vec3 lo = P.R.transpose() * (o - P.p), ld = P.R.transpose() * d;
  const Real R = r + inflate, H = hh + inflate;
  // Inside at the start.
  if (std::hypot(lo.x(), lo.z()) <= R && std::abs(lo.y()) <= H) {
    tHit = 0;
    nHit = -d;
    return true;
  }
  Real best = std::numeric_limits<Real>::max();
  Vec3 bestN = Vec3::UnitY();
  // Side: |(o + t d)_xz| = R with |y| <= H.
  const Real a = ld.x() * ld.x() + ld.z() * ld.z();
  if (a > Real(1e-12)) {
    const Real b = lo.x() * ld.x() + lo.z() * ld.z();
    const Real c = lo.x() * lo.x() + lo.z() * lo.z() - R * R;
    const Real disc = b * b - a * c;
    if (disc >= 0) {
      const Real t = (-b - std::sqrt(disc)) / a;
      const Vec3 q = lo + ld * t;
      if (t >= 0 && std::abs(q.y()) <= H) best = t, bestN = Vec3(q.x(), 0, q.z()).normalized();
    }
  }
  // Caps: y = +-H with |xz| <= R.
  if (std::abs(ld.y()) > Real(1e-12)) {
    for (Real sy : {Real(1), Real(-1)}) {
      if (sy * ld.y() >= 0) continue;  // only the cap the ray comes in through
      const Real t = (sy * H - lo.y()) / ld.y();
      const Vec3 q = lo + ld * t;
      if (t >= 0 && t < best && q.x() * q.x() + q.z() * q.z() <= R * R) best = t, bestN = Vec3(0, sy, 0);
    }
  }
  if (best > maxT) return false;
  tHit = best;
  nHit = P.R * bestN;
  return true;
}

}  // namespace tumble::physics
