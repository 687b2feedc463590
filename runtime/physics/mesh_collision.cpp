// Convex shapes against static triangle meshes.
//
// Where. All work is in the mesh body's frame: the moving piece's pose is
// brought into it (one rotation), its box is taken there and grown by the
// speculative margin, so the triangles (stored in that frame) are never
// transformed. The node tree is walked in depth-first order: a node whose
// covering box misses the query box is skipped with its whole subtree (one
// jump to subtreeEnd), a node whose own tight box misses has its triangles
// skipped, and only then each triangle's box and the exact test run. The
// counters in MeshStats say how much each level saved.
//
// What. Each triangle is a flat two-faced polytope (front and back face, three
// edges), so the existing convex routines do the exact test: the sphere and
// capsule closest points (collideSphereHull, collideCapsuleHull) and the
// separating-axis test with face clipping (collidePolytopes) for boxes and
// hulls. Triangles are one-sided (mesh_shape.h): a piece whose centre is
// behind a triangle's plane, and a contact whose normal points to the
// back, are ignored.
//
// Seams. Flat floors of many triangles must not bump: a box sliding across
// a seam is 1 cm from the next triangle, whose nearest feature is the shared
// edge; the box's side face against that triangle's vertices gives a
// speculative contact with a horizontal normal that stops the box (the
// internal-edge "ghost" contact; height_field_collision.cpp has the same
// problem for round shapes). Here the mesh knows its neighbours (active-edge
// flags made once when the shape is built), so the rule is exact and needs
// no search over nearby triangles: a contact whose normal is not the
// triangle's face normal lies on the edges its normal leans over (nc . o_e > 0
// for the edge's outward in-plane direction o_e; one edge, or two at a
// vertex); if none of those is active (a real convex crease or a border),
// the contact is a seam artefact and is dropped - the neighbour across the
// edge, coplanar or folding up, gives the true face contact. This is the
// "active edges" idea of Jolt and of Bullet's internal edge utility, with
// dropping instead of bending the normal (a bent normal at a concave seam
// pushes along the floor). Rejected: the height field's "is another triangle
// closer at q" search (it handles round shapes only; boxes and hulls give
// polygon contacts whose points are not closest points).
//
// Grouping. Contacts from all triangles go into at most kMaxMeshManifolds
// manifolds by normal (within kSameNormalCos), deepest first; a group with
// more than four points keeps the deepest, the farthest from it and the two
// spanning the largest area on either side (the support polygon), as
// boxBox does. Feature ids: points that are vertices of the moving piece
// (a box corner on the triangle's face, a capsule end) keep the piece's own
// id, so a box sliding from triangle to triangle keeps warm starting; points
// made by clipping against a triangle's edges take the triangle's index into
// their id (and are matched by position, World::inheritImpulses, when it
// changes).
#include "physics/internal/mesh_collision.h"

#include <algorithm>
#include <limits>

#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/internal/convex_collision.h"
#include "physics/internal/hull_collision.h"

namespace tumble::physics {
namespace {

constexpr Real kSameNormalCos = Real(0.999);   ///< normals within ~2.6 degrees share a manifold
constexpr Real kFaceNormalCos = Real(0.9999);  ///< a contact normal this close to the face normal is a face contact
constexpr Real kLean = Real(1e-4);             ///< a normal leans over an edge when nc . o_e exceeds this
constexpr Real kBackTolerance = Real(1e-3);    ///< contact normals this far behind the face plane are back contacts

struct MeshContact {
  Vec3 normal;  ///< from the mesh to the piece (local frame)
  Vec3 point;   ///< midway between the surfaces (local frame)
  Real separation;
  std::uint32_t id;
};

struct Scratch {
  ConvexHull tri;
  std::vector<MeshContact> contacts;
  std::vector<MeshContact> group;
  std::vector<std::uint8_t> taken;
  Scratch() {
    tri.vertices_m.assign(3, Vec3::Zero());
    tri.faces.resize(2);
    tri.faces[0].first = 0;
    tri.faces[0].count = 3;
    tri.faces[1].first = 3;
    tri.faces[1].count = 3;
    tri.faceVertices = {0, 1, 2, 0, 2, 1};  // the back face runs the other way round
    tri.edges = {{0, 1, 0, 1}, {1, 2, 0, 1}, {2, 0, 0, 1}};
  }
  void set(const MeshTriangle& t) {
    for (int c = 0; c < 3; ++c) tri.vertices_m[std::size_t(c)] = t.v[c];
    tri.faces[0].normal = t.normal;
    tri.faces[0].offset_m = t.normal.dot(t.v[0]);
    tri.faces[1].normal = -t.normal;
    tri.faces[1].offset_m = -tri.faces[0].offset_m;
  }
};

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

bool boxesOverlap(const Vec3& lo, const Vec3& hi, const Vec3& lo2, const Vec3& hi2) {
  return (lo.array() <= hi2.array()).all() && (hi.array() >= lo2.array()).all();
}

/// True when contact normal nc (from the triangle to the piece) is a real
/// contact of triangle t: the face normal, or leaning over an active edge.
bool onActiveFeature(const MeshTriangle& t, const Vec3& nc) {
  if (nc.dot(t.normal) >= kFaceNormalCos) return true;
  bool leans = false;
  for (int e = 0; e < 3; ++e) {
    const Vec3 outward = (t.v[(e + 1) % 3] - t.v[e]).cross(t.normal);
    if (nc.dot(outward) <= kLean * outward.norm()) continue;
    leans = true;
    if (t.activeEdges & (1u << e)) return true;
  }
  return !leans;  // no edge leaned over (round-off near the face normal): a face contact
}

/// Id of a contact point: the piece's own vertex ids stay, anything made
/// from the triangle's features takes the triangle's index in.
std::uint32_t pointId(std::uint32_t id, bool polytope, std::uint32_t triangle) {
  if (!polytope) return id;  // sphere, capsule: the piece's own feature (cap 0, 1, middle 2)
  const bool pieceVertex = (id & 0x80000000u) && !(id & 0x40000000u) && !(id & 0x200u);  // triangle is reference face
  return pieceVertex ? id : (id ^ (triangle * 2654435761u)) | 0x1000u;
}

/// One convex piece (local pose pL, RL in the mesh frame) against the mesh.
void pieceContacts(const Shape& shape, const Vec3& pL, const Mat3& RL, const Quat& qL, const MeshShape& mesh,
                   Real margin, bool useTree, MeshStats& stats, Scratch& s) {
  Vec3 lo, hi;
  shape.bounds(pL, qL, &lo, &hi);
  lo.array() -= margin;
  hi.array() += margin;
  ++stats.pairs;
  // Cylinders come back from collideConvex with the polytopes' id layout.
  const bool polytope =
      shape.type == ShapeType::Box || shape.type == ShapeType::Hull || shape.type == ShapeType::Cylinder;
  auto testTriangle = [&](std::uint32_t ti) {
    const MeshTriangle& t = mesh.triangles[ti];
    ++stats.trianglesTested;
    if (!boxesOverlap(lo, hi, t.lo_m, t.hi_m)) return;
    const Real centre = t.normal.dot(pL - t.v[0]);
    if (centre < 0) return;  // centre behind the front: one-sided
    // The piece's extent towards the plane: farther than the margin in front, no contact.
    Real reach = 0;
    switch (shape.type) {
      case ShapeType::Sphere: reach = shape.radius_m; break;
      case ShapeType::Capsule: reach = shape.radius_m + std::abs(RL.col(1).dot(t.normal)) * shape.halfHeight_m; break;
      case ShapeType::Box: reach = (RL.transpose() * t.normal).cwiseAbs().dot(shape.halfExtents_m); break;
      case ShapeType::Cylinder: {
        const Real along = std::abs(RL.col(1).dot(t.normal));
        reach = shape.halfHeight_m * along + shape.radius_m * std::sqrt(std::max<Real>(1 - along * along, 0));
        break;
      }
      default: reach = shape.boundingRadius(); break;
    }
    if (centre - reach > margin) return;
    ++stats.exactTests;
    s.set(t);
    Manifold m;
    const Pose triPose;
    switch (shape.type) {
      case ShapeType::Sphere: collideSphereHull(pL, shape.radius_m, triPose, s.tri, margin, m, 0); break;
      case ShapeType::Capsule: {
        const Vec3 axis = RL.col(1) * shape.halfHeight_m;
        collideCapsuleHull(pL - axis, pL + axis, shape.radius_m, triPose, s.tri, margin, m);
        break;
      }
      case ShapeType::Box:
        collidePolytopes(Pose{pL, RL}, unitCubeHull(), shape.halfExtents_m, triPose, s.tri, Vec3::Ones(), margin, m);
        break;
      case ShapeType::Hull:
        collidePolytopes(Pose{pL, RL}, *shape.hull, Vec3::Ones(), triPose, s.tri, Vec3::Ones(), margin, m);
        break;
      case ShapeType::Cylinder: {
        ConvexPiece piece, tri;
        convexPiece(shape, Pose{pL, RL}, &piece);
        tri.kind = ConvexPiece::Kind::Hull;
        tri.hull = &s.tri;
        collideConvex(piece, tri, margin, m);
        break;
      }
      default: return;
    }
    if (m.count == 0) return;
    const Vec3 nc = -m.normal;  // from the triangle to the piece
    if (nc.dot(t.normal) < -kBackTolerance) return;
    if (!onActiveFeature(t, nc)) return;
    for (int i = 0; i < m.count; ++i)
      s.contacts.push_back({nc, m.points[i].point_m, m.points[i].separation_m, pointId(m.points[i].id, polytope, ti)});
  };
  const std::uint32_t nodeCount = std::uint32_t(mesh.nodes.size());
  if (!useTree) {
    for (std::uint32_t ti = 0; ti < mesh.triangles.size(); ++ti) testTriangle(ti);
    return;
  }
  for (std::uint32_t i = 0; i < nodeCount;) {
    const MeshNode& node = mesh.nodes[i];
    ++stats.nodesVisited;
    if (!boxesOverlap(lo, hi, node.coverLo_m, node.coverHi_m)) {
      ++stats.subtreesSkipped;
      i = node.subtreeEnd;
      continue;
    }
    if (node.triangleCount > 0) {
      if (boxesOverlap(lo, hi, node.tightLo_m, node.tightHi_m)) {
        for (std::uint32_t ti = node.firstTriangle; ti < node.firstTriangle + node.triangleCount; ++ti) testTriangle(ti);
      } else {
        ++stats.nodesSkippedTight;
      }
    }
    ++i;
  }
}

/// Keeps at most four contacts of a group (see the top of the file).
void reduceGroup(std::vector<MeshContact>& c, const Vec3& normal) {
  if (c.size() <= 4) return;
  std::size_t i0 = 0;  // deepest (the group is sorted deepest first)
  std::size_t i1 = 1;
  Real best = -1;
  for (std::size_t i = 1; i < c.size(); ++i)
    if (Real d2 = (c[i].point - c[i0].point).squaredNorm(); d2 > best) best = d2, i1 = i;
  std::ptrdiff_t i2 = -1, i3 = -1;
  Real maxPos = 0, maxNeg = 0;
  const Vec3 e = c[i1].point - c[i0].point;
  for (std::size_t i = 1; i < c.size(); ++i) {
    if (i == i1) continue;
    const Real area = normal.dot(e.cross(c[i].point - c[i0].point));
    if (area > maxPos) maxPos = area, i2 = std::ptrdiff_t(i);
    if (area < maxNeg) maxNeg = area, i3 = std::ptrdiff_t(i);
  }
  MeshContact kept[4];
  int k = 0;
  for (std::ptrdiff_t idx : {std::ptrdiff_t(i0), std::ptrdiff_t(i1), i2, i3})
    if (idx >= 0) kept[k++] = c[std::size_t(idx)];
  c.assign(kept, kept + k);
}

/// Groups s.contacts into manifolds (normals from the piece to the mesh, world frame).
int groupContacts(Scratch& s, const Vec3& pm, const Mat3& Rm, bool onePointPerNormal, Manifold* out) {
  auto& cs = s.contacts;
  if (cs.empty()) return 0;
  std::sort(cs.begin(), cs.end(), [](const MeshContact& a, const MeshContact& b) {
    return a.separation != b.separation ? a.separation < b.separation : a.id < b.id;
  });
  std::vector<std::uint8_t>& taken = s.taken;
  taken.assign(cs.size(), 0);
  int count = 0;
  for (std::size_t i = 0; i < cs.size() && count < kMaxMeshManifolds; ++i) {
    if (taken[i]) continue;
    const Vec3 n = cs[i].normal;
    s.group.clear();
    for (std::size_t j = i; j < cs.size(); ++j) {
      if (taken[j] || cs[j].normal.dot(n) < kSameNormalCos) continue;
      taken[j] = 1;
      if (onePointPerNormal && !s.group.empty()) continue;
      s.group.push_back(cs[j]);
    }
    // Reduce first (linear), then drop repeated ids among the kept four: a
    // box corner on a seam is found by both triangles, at the same place.
    reduceGroup(s.group, n);
    for (std::size_t g = 1; g < s.group.size();) {
      bool dup = false;
      for (std::size_t h = 0; h < g; ++h) dup |= s.group[h].id == s.group[g].id;
      if (dup) s.group.erase(s.group.begin() + std::ptrdiff_t(g));
      else ++g;
    }
    Manifold& m = out[count++];
    m = Manifold{};
    m.normal = Rm * -n;
    for (const MeshContact& g : s.group) {
      ContactPoint& p = m.points[m.count++];
      p.point_m = pm + Rm * g.point;
      p.separation_m = g.separation;
      p.id = g.id;
    }
  }
  return count;
}

}  // namespace

int collideMeshPair(const Body& a, const Body& b, Real margin, std::vector<Manifold>& out, MeshStats* stats,
                    bool useTree) {
  const bool meshA = a.shape.type == ShapeType::Mesh;
  const Body& meshBody = meshA ? a : b;
  const Body& other = meshA ? b : a;
  if (other.shape.type == ShapeType::Mesh || other.shape.type == ShapeType::Plane || !meshBody.shape.mesh) return 0;
  MeshStats local;
  MeshStats& st = stats ? *stats : local;
  Scratch& s = scratch();
  const MeshShape& mesh = *meshBody.shape.mesh;
  const Mat3 Rm = meshBody.orientation.toRotationMatrix();
  const Quat qmInv = meshBody.orientation.conjugate();
  const std::size_t before = out.size();
  auto onePiece = [&](const Shape& shape, const Vec3& p, const Quat& q, std::uint16_t child) {
    if (shape.type == ShapeType::Plane || shape.type == ShapeType::Mesh || shape.type == ShapeType::Compound) return;
    const Vec3 pL = Rm.transpose() * (p - meshBody.position_m);
    const Quat qL = qmInv * q;
    s.contacts.clear();
    pieceContacts(shape, pL, qL.toRotationMatrix(), qL, mesh, margin, useTree, st, s);
    Manifold m[kMaxMeshManifolds];
    const int k = groupContacts(s, meshBody.position_m, Rm, shape.type == ShapeType::Sphere, m);
    for (int i = 0; i < k; ++i) {
      if (meshA) {  // computed piece -> mesh; the pair's a is the mesh
        m[i].normal = -m[i].normal;
        m[i].childB = child;
      } else {
        m[i].childA = child;
      }
      out.push_back(m[i]);
    }
  };
  if (other.shape.type == ShapeType::Compound) {
    const auto& kids = other.shape.compound->children;
    for (std::size_t c = 0; c < kids.size(); ++c)
      onePiece(kids[c].shape, other.position_m + other.orientation * kids[c].position_m,
               other.orientation * kids[c].orientation, std::uint16_t(c));
  } else {
    onePiece(other.shape, other.position_m, other.orientation, 0);
  }
  return int(out.size() - before);
}

bool sphereMeshContact(const Vec3& centre, Real radius, const Vec3& position, const Quat& orientation,
                       const MeshShape& mesh, Vec3* normal, Real* depth) {
  const Mat3 R = orientation.toRotationMatrix();
  const Vec3 c = R.transpose() * (centre - position);
  const Vec3 lo = c - Vec3::Constant(radius), hi = c + Vec3::Constant(radius);
  Scratch& s = scratch();
  Real deepest = 0;
  for (std::uint32_t i = 0; i < mesh.nodes.size();) {
    const MeshNode& node = mesh.nodes[i];
    if (!boxesOverlap(lo, hi, node.coverLo_m, node.coverHi_m)) {
      i = node.subtreeEnd;
      continue;
    }
    for (std::uint32_t ti = node.firstTriangle; ti < node.firstTriangle + node.triangleCount; ++ti) {
      const MeshTriangle& t = mesh.triangles[ti];
      if (!boxesOverlap(lo, hi, t.lo_m, t.hi_m) || t.normal.dot(c - t.v[0]) < 0) continue;
      s.set(t);
      Vec3 closest, n;
      const Real d = radius - pointHullDistance(c, Pose{}, s.tri, closest, n);
      if (d <= deepest || n.dot(t.normal) < -kBackTolerance || !onActiveFeature(t, n)) continue;
      deepest = d;
      *normal = R * n;
      *depth = d;
    }
    ++i;
  }
  return deepest > 0;
}

bool rayMesh(const Vec3& origin, const Vec3& dir, Real maxT, const Vec3& position, const Quat& orientation,
             const MeshShape& mesh, Real inflate, Real& tHit, Vec3& nHit, MeshStats* stats) {
  const Mat3 R = orientation.toRotationMatrix();
  const Vec3 o = R.transpose() * (origin - position), d = R.transpose() * dir;
  MeshStats local;
  MeshStats& st = stats ? *stats : local;
  ++st.rays;
  const Vec3 inv(1 / d.x(), 1 / d.y(), 1 / d.z());  // +-inf on an axis the ray does not move along
  Real best = maxT;
  bool hit = false;
  // Slab test of the ray segment [0, best] against a box grown by the inflation.
  auto rayBox = [&](const Vec3& lo, const Vec3& hi) {
    Real t0 = 0, t1 = best;
    for (int k = 0; k < 3; ++k) {
      if (d[k] == 0) {
        if (o[k] < lo[k] - inflate || o[k] > hi[k] + inflate) return false;
        continue;
      }
      Real a = (lo[k] - inflate - o[k]) * inv[k], b = (hi[k] + inflate - o[k]) * inv[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
      if (t0 > t1) return false;
    }
    return true;
  };
  for (std::uint32_t i = 0; i < mesh.nodes.size();) {
    const MeshNode& node = mesh.nodes[i];
    ++st.nodesVisited;
    if (!rayBox(node.coverLo_m, node.coverHi_m)) {
      ++st.subtreesSkipped;
      i = node.subtreeEnd;
      continue;
    }
    if (node.triangleCount > 0 && rayBox(node.tightLo_m, node.tightHi_m)) {
      for (std::uint32_t ti = node.firstTriangle; ti < node.firstTriangle + node.triangleCount; ++ti) {
        const MeshTriangle& t = mesh.triangles[ti];
        ++st.trianglesTested;
        const Real denom = t.normal.dot(d);
        if (!(denom < 0)) continue;  // one-sided: only rays coming at the front
        ++st.exactTests;
        // Moller-Trumbore on the triangle pushed out by the inflation.
        const Vec3 shift = t.normal * inflate;
        const Vec3 v0 = t.v[0] + shift, e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0];
        const Vec3 pv = d.cross(e2);
        const Real det = e1.dot(pv);
        if (std::abs(det) < Real(1e-12)) continue;
        const Real invDet = 1 / det;
        const Vec3 tv = o - v0;
        const Real u = tv.dot(pv) * invDet;
        if (u < 0 || u > 1) continue;
        const Vec3 qv = tv.cross(e1);
        const Real v = d.dot(qv) * invDet;
        if (v < 0 || u + v > 1) continue;
        const Real t_ = e2.dot(qv) * invDet;
        if (t_ < 0 || t_ > best) continue;
        best = t_;
        nHit = R * t.normal;
        hit = true;
      }
    }
    ++i;
  }
  if (hit) tHit = best;
  return hit;
}

}  // namespace tumble::physics
