// Body against height field.
//
// Round shapes (spheres, the end caps of capsules): for every triangle near
// the body, the closest point q on the triangle to the centre c (Ericson,
// Real-Time Collision Detection 5.1.5) and the feature it lies on (face,
// edge, vertex). Face: normal = the face normal, separation = signed distance
// of c from the plane minus r. Edge / vertex: normal = (c - q) / |c - q|.
//
// Seams (internal edges). A triangle whose closest point lies on its edge
// or vertex gives a tilted normal even when the surface there is flat: a
// sphere resting on triangle T1 is 1 cm from T1's neighbour T2, whose
// closest point is on the shared edge, and that speculative contact (normal
// tilted towards the sphere's motion) pushes back when the sphere rolls
// over the seam - the "internal edge" bump. The cure used here needs no
// adjacency: an edge or vertex contact is a real contact only if its point q
// is a local minimum of the distance over the whole surface, not only over
// its own triangle. So it is dropped when another triangle contains q (q
// within 1 mm of it) and comes closer to the centre. On a flat or concave
// seam the neighbour is closer, so only face contacts survive; on a convex
// ridge both triangles touch q at the same distance and the edge contact
// stays, with its true normal. Rejected: Bullet's btAdjustInternalEdgeContacts
// (needs a triangle-info map built for the whole mesh: terrain memory in
// physics) and Jolt's vertex voiding (keeps edge contacts of triangles that
// share only a vertex with the face contact; measured as bumps).
//
// Boxes: each of the 8 vertices against the triangle under it (vertical
// look-up; normal = that face normal, separation = vertical gap times n.y,
// exact for a plane), so a box on flat ground gets its 4 bottom corners with
// one normal however many triangles lie under it, and keeps its feature ids
// (0..7) while sliding: no seam ever appears in its contacts. A bump of the
// terrain under the middle of a face is caught by the terrain's vertices
// against the box's lowest face, used only where they reach deeper (by
// kPeakTolerance_m) than every corner.
// Capsules: the two end caps as spheres, plus terrain vertices against the
// core segment where they reach deeper than the caps.
// Hulls: as boxes - every vertex against the triangle under it, and terrain
// vertices against the hull's lowest face (the face whose normal points most
// downwards) where they reach deeper than every vertex.
//
// Cylinders: as boxes, with the rim points of cylinderSurfacePoints for
// corners (the deepest rim point of each cap for the terrain normal under the
// centre, three more on the lower cap), and terrain vertices against the
// cylinder (pointCylinderDistance) where they reach deeper than every rim point.
//
// Contacts are then grouped by normal (within kSameNormalCos) into at most
// kMaxHeightFieldManifolds manifolds of at most 4 points each, deepest first.
#include "physics/internal/height_field_collision.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "physics/convex_hull.h"
#include "physics/internal/convex_collision.h"

namespace tumble::physics {
namespace {

constexpr Real kOnTriangle_m = Real(1e-3);       ///< q counts as on a triangle within this distance
constexpr Real kCloser_m = Real(1e-5);           ///< "comes closer" means by at least this much
constexpr Real kPeakTolerance_m = Real(0.01);    ///< terrain vertices must reach this much deeper than corners
constexpr Real kEdgeTolerance_m = Real(0.002);   ///< terrain edges must reach this much deeper than corners and vertices
constexpr Real kSameNormalCos = Real(0.999);     ///< normals within ~2.6 degrees share a manifold

enum class Feature { Face, Edge, Vertex };

/// Closest point of triangle abc to p and the feature it lies on (Ericson 5.1.5).
Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Feature& f) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const Real d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return f = Feature::Vertex, a;
  const Vec3 bp = p - b;
  const Real d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return f = Feature::Vertex, b;
  const Real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return f = Feature::Edge, Vec3(a + ab * (d1 / (d1 - d3)));
  const Vec3 cp = p - c;
  const Real d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return f = Feature::Vertex, c;
  const Real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return f = Feature::Edge, Vec3(a + ac * (d2 / (d2 - d6)));
  const Real va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return f = Feature::Edge, Vec3(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const Real denom = 1 / (va + vb + vc);
  f = Feature::Face;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

/// Contacts of a sphere (centre c, radius r) with the gathered triangles;
/// appends to s.contacts with the given id.
/// True if (x, z) of p lies under triangle t's X/Z projection and p is below
/// its plane: p is inside the ground there.
bool belowTriangle(const Vec3& p, const HeightFieldTriangle& t) {
  const Real ax = t.v[0].x(), az = t.v[0].z();
  const Real e1x = t.v[1].x() - ax, e1z = t.v[1].z() - az, e2x = t.v[2].x() - ax, e2z = t.v[2].z() - az;
  const Real det = e1x * e2z - e2x * e1z;
  if (det == 0) return false;  // vertical triangle: no height there
  const Real px = p.x() - ax, pz = p.z() - az;
  const Real u = (px * e2z - e2x * pz) / det, v = (e1x * pz - px * e1z) / det;
  if (u < 0 || v < 0 || u + v > 1) return false;
  const Real y = t.v[0].y() + u * (t.v[1].y() - t.v[0].y()) + v * (t.v[2].y() - t.v[0].y());
  return p.y() < y;
}

void roundContacts(const Vec3& c, Real r, Real margin, std::uint32_t id, HeightFieldScratch& s) {
  auto& cands = s.candidates;
  cands.clear();
  // Is the centre inside the ground (under the surface at its x, z)? Only
  // then may a triangle whose plane the centre is behind push it out along
  // its face normal. In a sharp valley the centre is often behind the plane
  // of the opposite slope's triangle while well above the ground; treating
  // that as deep made a 0.67 m phantom penetration (hills, seed 11,
  // roughness 0.6) that pressed spheres into the valley wall for seconds.
  bool centreUnderground = false;
  for (const HeightFieldTriangle& t : s.triangles)
    if (belowTriangle(c, t)) {
      centreUnderground = true;
      break;
    }
  for (std::uint32_t i = 0; i < s.triangles.size(); ++i) {
    const HeightFieldTriangle& t = s.triangles[i];
    Feature f;
    const Vec3 q = closestOnTriangle(c, t.v[0], t.v[1], t.v[2], f);
    const Vec3 d = c - q;
    const Real along = d.dot(t.normal);
    HeightFieldScratch::Candidate k;
    k.closest = q;
    k.triangle = i;
    k.face = f == Feature::Face;
    if (k.face || (along <= 0 && centreUnderground)) {
      // Face region, or the centre is inside the ground behind this plane
      // (deep): push out along the face normal, never down through the
      // surface.
      k.normal = t.normal;
      k.separation = along - r;
    } else {
      const Real dist = d.norm();
      k.normal = d / dist;
      k.separation = dist - r;
    }
    cands.push_back(k);
  }
  for (const auto& k : cands) {
    if (k.separation > margin) continue;
    if (!k.face) {
      // Keep an edge / vertex contact only at a local minimum of the distance
      // over the surface: no other triangle through q comes closer.
      bool shadowed = false;
      for (const auto& o : cands) {
        if (!(o.separation < k.separation - kCloser_m)) continue;
        const HeightFieldTriangle& t = s.triangles[o.triangle];
        Feature g;
        if ((closestOnTriangle(k.closest, t.v[0], t.v[1], t.v[2], g) - k.closest).squaredNorm() <=
            kOnTriangle_m * kOnTriangle_m) {
          shadowed = true;
          break;
        }
      }
      if (shadowed) continue;
    }
    s.contacts.push_back({k.normal, k.closest + k.normal * (k.separation / 2), k.separation, id});
  }
}

Real minSeparation(const std::vector<SurfaceContact>& contacts) {
  Real m = std::numeric_limits<Real>::max();
  for (const SurfaceContact& c : contacts) m = std::min(m, c.separation_m);
  return m;
}

/// Stable id of a terrain vertex from its position bits (ids of corners and caps are < 16).
std::uint32_t vertexId(const Vec3& v) {
  std::uint32_t h = 2166136261u;
  for (int k = 0; k < 3; k += 2) {
    float f = float(v[k]);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    h = (h ^ bits) * 16777619u;
  }
  return 0x100u | (h << 8);
}

void boxContacts(const Body& b, const HeightField& field, Real margin, HeightFieldScratch& s) {
  const Mat3 R = b.orientation.toRotationMatrix();
  const Vec3& he = b.shape.halfExtents_m;
  for (std::uint32_t i = 0; i < 8; ++i) {
    const Vec3 local((i & 1) ? he.x() : -he.x(), (i & 2) ? he.y() : -he.y(), (i & 4) ? he.z() : -he.z());
    const Vec3 v = b.position_m + R * local;
    Real h;
    Vec3 n;
    if (!field.surfaceAt(v.x(), v.z(), &h, &n)) continue;
    const Real sep = (v.y() - h) * n.y();
    if (sep > margin) continue;
    s.contacts.push_back({n, v - n * (sep / 2), sep, i});
  }
  // Terrain vertices against the lowest face, where they reach deeper than the corners.
  int k = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(R(1, a)) > std::abs(R(1, k))) k = a;
  const Vec3 down = R.col(k) * (R(1, k) > 0 ? Real(-1) : Real(1));  // outward normal of the lowest face
  const int u = (k + 1) % 3, w = (k + 2) % 3;
  // A terrain point inside the box leaves it through the nearest face: the
  // lowest face unless a side face is nearer (a tumbling box whose side is
  // over a ridge). Pushing it out through the lowest face regardless made a
  // 0.43 m phantom penetration along a tilted box's bottom normal (hills
  // seed 5, roughness 0.7).
  auto push = [&](const Vec3& p, Real sep, Vec3* n, Real* depthSep) {
    *n = -down;  // from the surface to the box
    *depthSep = sep;
    if (sep >= 0) return;
    const Vec3 d = p - b.position_m;
    const Real lu = R.col(u).dot(d), lw = R.col(w).dot(d);
    const Real su = std::abs(lu) - he[u], sw = std::abs(lw) - he[w];  // <= 0 inside
    if (su > *depthSep) *depthSep = su, *n = R.col(u) * (lu > 0 ? Real(-1) : Real(1));
    if (sw > *depthSep) *depthSep = sw, *n = R.col(w) * (lw > 0 ? Real(-1) : Real(1));
  };
  const Real deepest = minSeparation(s.contacts) - kPeakTolerance_m;
  const std::size_t corners = s.contacts.size();
  for (const HeightFieldTriangle& t : s.triangles)
    for (const Vec3& v : t.v) {
      const Vec3 d = v - b.position_m;
      const Real sep = down.dot(d) - he[k];
      // Only vertices under or inside the box: one above its top is no contact.
      if (sep > margin || sep >= deepest || sep < -2 * he[k]) continue;
      const Real lu = R.col(u).dot(d), lw = R.col(w).dot(d);
      if (std::abs(lu) > he[u] || std::abs(lw) > he[w]) continue;
      const std::uint32_t id = vertexId(v);
      bool seen = false;
      for (std::size_t j = corners; j < s.contacts.size(); ++j) seen |= s.contacts[j].id == id;
      if (seen) continue;
      Vec3 n;
      Real depthSep;
      push(v, sep, &n, &depthSep);
      s.contacts.push_back({n, v + n * (depthSep / 2), depthSep, id});
    }
  // Terrain edges crossing under the lowest face: a ridge between two
  // terrain vertices outside the face's footprint pokes into the face with
  // no corner and no vertex inside it. Along a straight edge the depth
  // is linear, so its deepest points in the footprint are where it crosses
  // the footprint's border: those are the contacts (face normal, like the
  // vertices), used where they reach 2 mm deeper than every corner and
  // vertex contact (on flat ground they are exactly as deep: rounding must
  // not switch them on). (With the vertices' 1 cm tolerance, an edge contact
  // switched on and off as the box rose and sank by it, and three boxes
  // crept at 0.15 m/s for 30 s.) This closed the 9.6 cm a box sank onto a
  // ridge in hills seed 11, roughness 0.6 (now 4.1 cm, all asleep).
  const Real deepestSoFar = std::min(deepest + kPeakTolerance_m, minSeparation(s.contacts)) - kEdgeTolerance_m;
  const std::size_t beforeEdges = s.contacts.size();
  for (const HeightFieldTriangle& t : s.triangles)
    for (int e = 0; e < 3; ++e) {
      const Vec3& va = t.v[e];
      const Vec3& vb = t.v[(e + 1) % 3];
      const Vec3 da = va - b.position_m, db = vb - b.position_m;
      const Real ua = R.col(u).dot(da), ub = R.col(u).dot(db), wa = R.col(w).dot(da), wb = R.col(w).dot(db);
      const std::uint32_t ia = vertexId(va), ib = vertexId(vb);
      const std::uint32_t edgeId = 0x100u | ((std::min(ia, ib) * 16777619u) ^ std::max(ia, ib));
      for (int side = 0; side < 4; ++side) {
        // side 0/1: the border lu = -/+ he[u]; 2/3: lw = -/+ he[w].
        const bool alongU = side < 2;
        const Real border = (side % 2 ? 1 : -1) * (alongU ? he[u] : he[w]);
        const Real a0 = alongU ? ua : wa, a1 = alongU ? ub : wb;
        if ((a0 - border) * (a1 - border) > 0 || a0 == a1) continue;  // does not cross this border
        const Real f = (border - a0) / (a1 - a0);
        const Real other = alongU ? wa + (wb - wa) * f : ua + (ub - ua) * f;
        if (std::abs(other) > (alongU ? he[w] : he[u])) continue;  // crosses the line outside the face
        const Vec3 p = va + (vb - va) * f;
        const Real sep = down.dot(p - b.position_m) - he[k];
        if (sep > margin || sep >= deepestSoFar || sep < -2 * he[k]) continue;
        const std::uint32_t id = edgeId ^ (std::uint32_t(side) << 4);
        bool seen = false;
        for (std::size_t j = beforeEdges; j < s.contacts.size(); ++j) seen |= s.contacts[j].id == id;
        if (seen) continue;
        Vec3 n;
        Real depthSep;
        push(p, sep, &n, &depthSep);
        s.contacts.push_back({n, p + n * (depthSep / 2), depthSep, id});
      }
    }
}

void hullContacts(const Body& b, const HeightField& field, Real margin, HeightFieldScratch& s) {
  const ConvexHull& hull = *b.shape.hull;
  const Mat3 R = b.orientation.toRotationMatrix();
  for (std::uint32_t i = 0; i < hull.vertices_m.size(); ++i) {
    const Vec3 v = b.position_m + R * hull.vertices_m[i];
    Real h;
    Vec3 n;
    if (!field.surfaceAt(v.x(), v.z(), &h, &n)) continue;
    const Real sep = (v.y() - h) * n.y();
    if (sep > margin) continue;
    s.contacts.push_back({n, v - n * (sep / 2), sep, i});
  }
  std::size_t low = 0;
  for (std::size_t f = 1; f < hull.faces.size(); ++f)
    if ((R * hull.faces[f].normal).y() < (R * hull.faces[low].normal).y()) low = f;
  const HullFace& face = hull.faces[low];
  const Vec3 down = R * face.normal;  // outward normal of the lowest face
  const Real deepest = minSeparation(s.contacts) - kPeakTolerance_m;
  const std::size_t corners = s.contacts.size();
  const Real depth = hull.boundsHi_m.norm() + hull.boundsLo_m.norm();  // no contact deeper than the hull is thick
  for (const HeightFieldTriangle& t : s.triangles)
    for (const Vec3& v : t.v) {
      const Vec3 local = R.transpose() * (v - b.position_m);
      const Real sep = face.normal.dot(local) - face.offset_m;
      if (sep > margin || sep >= deepest || sep < -depth) continue;
      bool inside = true;
      for (std::uint32_t k = 0; k < face.count && inside; ++k) {
        const Vec3& a = hull.vertices_m[hull.faceVertices[face.first + k]];
        const Vec3& c = hull.vertices_m[hull.faceVertices[face.first + (k + 1) % face.count]];
        inside = (c - a).cross(face.normal).dot(local - a) <= 0;
      }
      if (!inside) continue;
      const std::uint32_t id = vertexId(v);
      bool seen = false;
      for (std::size_t j = corners; j < s.contacts.size(); ++j) seen |= s.contacts[j].id == id;
      if (seen) continue;
      const Vec3 n = -down;
      s.contacts.push_back({n, v + n * (sep / 2), sep, id});
    }
}

void capsuleContacts(const Body& b, Real margin, HeightFieldScratch& s) {
  const Vec3 axis = b.orientation * Vec3::UnitY();
  const Real r = b.shape.radius_m;
  const Vec3 p0 = b.position_m - axis * b.shape.halfHeight_m, p1 = b.position_m + axis * b.shape.halfHeight_m;
  roundContacts(p0, r, margin, 0, s);
  roundContacts(p1, r, margin, 1, s);
  const Real deepest = minSeparation(s.contacts) - kPeakTolerance_m;
  const std::size_t caps = s.contacts.size();
  const Vec3 seg = p1 - p0;
  const Real len2 = seg.squaredNorm();
  for (const HeightFieldTriangle& t : s.triangles)
    for (const Vec3& v : t.v) {
      const Real tt = len2 > 0 ? std::clamp<Real>(seg.dot(v - p0) / len2, 0, 1) : 0;
      if (tt <= 0 || tt >= 1) continue;  // the caps cover the ends
      const Vec3 d = p0 + seg * tt - v;
      if (d.dot(t.normal) <= 0) continue;
      const Real dist = d.norm();
      const Real sep = dist - r;
      if (sep > margin || sep >= deepest) continue;
      const std::uint32_t id = vertexId(v);
      bool seen = false;
      for (std::size_t j = caps; j < s.contacts.size(); ++j) seen |= s.contacts[j].id == id;
      if (seen) continue;
      const Vec3 n = d / dist;
      s.contacts.push_back({n, v + n * (sep / 2), sep, id});
    }
}

void cylinderContacts(const Body& b, const HeightField& field, Real margin, HeightFieldScratch& s) {
  const Pose P{b.position_m, b.orientation.toRotationMatrix()};
  const Real r = b.shape.radius_m, hh = b.shape.halfHeight_m;
  Real h0;
  Vec3 n0 = Vec3::UnitY();
  if (!field.surfaceAt(b.position_m.x(), b.position_m.z(), &h0, &n0)) n0 = Vec3::UnitY();
  Vec3 pts[5];
  std::uint32_t ids[5];
  const int k = cylinderSurfacePoints(P, r, hh, n0, pts, ids);
  for (int i = 0; i < k; ++i) {
    Real h;
    Vec3 n;
    if (!field.surfaceAt(pts[i].x(), pts[i].z(), &h, &n)) continue;
    const Real sep = (pts[i].y() - h) * n.y();
    if (sep > margin) continue;
    s.contacts.push_back({n, pts[i] - n * (sep / 2), sep, ids[i]});
  }
  const Real deepest = minSeparation(s.contacts) - kPeakTolerance_m;
  const std::size_t rims = s.contacts.size();
  for (const HeightFieldTriangle& t : s.triangles)
    for (const Vec3& v : t.v) {
      Vec3 closest, out;
      const Real sep = pointCylinderDistance(v, P, r, hh, closest, out);
      if (sep > margin || sep >= deepest) continue;
      const Vec3 n = -out;  // from the surface into the body
      if (n.dot(t.normal) <= 0) continue;
      const std::uint32_t id = vertexId(v);
      bool seen = false;
      for (std::size_t j = rims; j < s.contacts.size(); ++j) seen |= s.contacts[j].id == id;
      if (seen) continue;
      s.contacts.push_back({n, v + n * (sep / 2), sep, id});
    }
}

}  // namespace

int collideHeightField(const Body& body, const HeightField& field, const Vec3& lo, const Vec3& hi, Real margin,
                       HeightFieldScratch& s, Manifold* out) {
  s.triangles.clear();
  s.contacts.clear();
  const Shape& shape = body.shape;
  if (shape.type == ShapeType::Plane) return 0;
  field.forEachTriangle(lo, hi, [&](const HeightFieldTriangle& t) { s.triangles.push_back(t); });
  switch (shape.type) {
    case ShapeType::Sphere: roundContacts(body.position_m, shape.radius_m, margin, 0, s); break;
    case ShapeType::Box: boxContacts(body, field, margin, s); break;
    case ShapeType::Capsule: capsuleContacts(body, margin, s); break;
    case ShapeType::Hull: hullContacts(body, field, margin, s); break;
    case ShapeType::Cylinder: cylinderContacts(body, field, margin, s); break;
    case ShapeType::Plane: break;
    case ShapeType::Compound: break;  // World passes compounds child by child
    case ShapeType::Mesh: break;      // static only: never against the (static) height field
  }
  if (s.contacts.empty()) return 0;
  // Deepest first; ties by id so the order never depends on the triangle order.
  std::sort(s.contacts.begin(), s.contacts.end(), [](const SurfaceContact& a, const SurfaceContact& b) {
    return a.separation_m != b.separation_m ? a.separation_m < b.separation_m : a.id < b.id;
  });
  const bool onePointPerNormal = shape.type == ShapeType::Sphere;
  int count = 0;
  for (const SurfaceContact& c : s.contacts) {
    int k = 0;
    while (k < count && -out[k].normal.dot(c.normal) < kSameNormalCos) ++k;
    if (k == count) {
      if (count == kMaxHeightFieldManifolds) continue;
      Manifold& m = out[count++];
      m = Manifold{};
      m.normal = -c.normal;  // from the body (a) to the surface (b)
    } else if (onePointPerNormal) {
      continue;
    }
    Manifold& m = out[k];
    // Capsules: one point per cap and normal (a cap in a valley has two normals).
    bool dup = false;
    for (int i = 0; i < m.count; ++i) dup |= m.points[i].id == c.id;
    if (dup || m.count >= kMaxManifoldPoints) continue;
    ContactPoint& p = m.points[m.count++];
    p.point_m = c.point_m;
    p.separation_m = c.separation_m;
    p.id = c.id;
  }
  return count;
}

}  // namespace tumble::physics
