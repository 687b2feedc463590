#include "physics/convex_hull.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "physics/mass_properties.h"

namespace tumble::physics {
namespace {

using V3 = Eigen::Vector3d;

struct Tri {
  int v[3];
  V3 n;
  double d;
  bool alive;
};

Tri makeTri(const std::vector<V3>& p, int a, int b, int c) {
  Tri t{{a, b, c}, (p[b] - p[a]).cross(p[c] - p[a]), 0, true};
  const double len = t.n.norm();
  t.n = len > 0 ? V3(t.n / len) : V3::UnitY();
  t.d = t.n.dot(p[a]);
  return t;
}

std::string describe(const Vec3& v) {
  std::string s = "(";  // appended piece by piece: GCC 12 misreads "(" + temporary (-Wrestrict)
  s += std::to_string(v.x());
  s += ", ";
  s += std::to_string(v.y());
  s += ", ";
  s += std::to_string(v.z());
  s += ")";
  return s;
}

}  // namespace

const Vec3& ConvexHull::support(const Vec3& dir) const {
  std::size_t best = 0;
  Real bestDot = -std::numeric_limits<Real>::max();
  for (std::size_t i = 0; i < vertices_m.size(); ++i) {
    const Real d = vertices_m[i].dot(dir);
    if (d > bestDot) bestDot = d, best = i;
  }
  return vertices_m[best];
}

Result<ConvexHull> computeConvexHull(std::span<const Vec3> points) {
  if (points.size() < 4)
    return makeError("a convex hull needs at least 4 points that span a volume, got " + std::to_string(points.size()));
  if (points.size() > std::size_t(kMaxHullPoints))
    return makeError("a convex hull takes at most " + std::to_string(kMaxHullPoints) + " points, got " +
                     std::to_string(points.size()) + " (simplify the cloud; collision hulls need tens of points)");
  std::vector<V3> p(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      return makeError("convex hull point " + std::to_string(i + 1) + " is not finite: " + describe(points[i]));
    p[i] = points[i].cast<double>();
  }
  V3 lo = p[0], hi = p[0];
  for (const V3& q : p) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const double size = (hi - lo).norm();
  const double eps = 1e-7 * size;   // "on the hull" tolerance
  const double flat = 1e-4 * size;  // the initial tetrahedron must be at least this thick
  // Initial tetrahedron from extreme points.
  int i0 = 0;
  for (int i = 1; i < int(p.size()); ++i)
    if (p[i].x() < p[i0].x()) i0 = i;
  auto farthest = [&](auto dist) {
    int best = -1;
    double bestD = -1;
    for (int i = 0; i < int(p.size()); ++i)
      if (double d = dist(p[i]); d > bestD) bestD = d, best = i;
    return std::pair{best, bestD};
  };
  auto [i1, d1] = farthest([&](const V3& q) { return (q - p[i0]).norm(); });
  if (d1 <= flat) return makeError("convex hull points all coincide; they must span a volume");
  const V3 axis = (p[i1] - p[i0]).normalized();
  auto [i2, d2] = farthest([&](const V3& q) { return (q - p[i0]).cross(axis).norm(); });
  if (d2 <= flat) return makeError("convex hull points are all on one line; they must span a volume");
  const V3 normal = (p[i1] - p[i0]).cross(p[i2] - p[i0]).normalized();
  auto [i3, d3] = farthest([&](const V3& q) { return std::abs((q - p[i0]).dot(normal)); });
  if (d3 <= flat)
    return makeError("convex hull points are all on one plane (coplanar); they must span a volume");

  std::vector<Tri> tris;
  const V3 inside = (p[i0] + p[i1] + p[i2] + p[i3]) / 4;
  auto addOutward = [&](int a, int b, int c) {
    Tri t = makeTri(p, a, b, c);
    if (t.n.dot(inside) > t.d) t = makeTri(p, a, c, b);
    tris.push_back(t);
  };
  addOutward(i0, i1, i2);
  addOutward(i0, i1, i3);
  addOutward(i0, i2, i3);
  addOutward(i1, i2, i3);

  std::vector<std::pair<int, int>> visibleEdges, horizon;
  for (int i = 0; i < int(p.size()); ++i) {
    if (i == i0 || i == i1 || i == i2 || i == i3) continue;
    visibleEdges.clear();
    for (Tri& t : tris) {
      if (!t.alive || t.n.dot(p[i]) - t.d <= eps) continue;
      t.alive = false;
      for (int k = 0; k < 3; ++k) visibleEdges.emplace_back(t.v[k], t.v[(k + 1) % 3]);
    }
    if (visibleEdges.empty()) continue;  // inside
    // Horizon: edges of the visible region whose twin is not visible.
    horizon.clear();
    for (const auto& [a, b] : visibleEdges)
      if (std::find(visibleEdges.begin(), visibleEdges.end(), std::pair{b, a}) == visibleEdges.end())
        horizon.emplace_back(a, b);
    for (const auto& [a, b] : horizon) tris.push_back(makeTri(p, a, b, i));
    if (tris.size() > 4 * p.size() + 64)  // drop dead triangles now and then
      tris.erase(std::remove_if(tris.begin(), tris.end(), [](const Tri& t) { return !t.alive; }), tris.end());
  }
  tris.erase(std::remove_if(tris.begin(), tris.end(), [](const Tri& t) { return !t.alive; }), tris.end());

  // Merge coplanar triangles into faces.
  struct Group {
    V3 n;
    double d;
    std::vector<int> verts;
  };
  std::vector<Group> groups;
  for (const Tri& t : tris) {
    Group* g = nullptr;
    for (Group& o : groups)
      if (o.n.dot(t.n) > 1 - 1e-6 && std::abs(o.d - t.d) <= 10 * eps) g = &o;
    if (!g) {
      groups.push_back({t.n, t.d, {}});
      g = &groups.back();
    }
    for (int v : t.v)
      if (std::find(g->verts.begin(), g->verts.end(), v) == g->verts.end()) g->verts.push_back(v);
  }
  ConvexHull hull;
  std::vector<int> remap(p.size(), -1);
  for (Group& g : groups) {
    // The face polygon: the 2-D convex hull of the group's points in the
    // face plane (Andrew's monotone chain), counter-clockwise about the
    // normal. Points inside the face or on its edges (added while the hull
    // was smaller, now coplanar) drop out, so faces share exactly their corners.
    V3 c = V3::Zero();
    for (int v : g.verts) c += p[v];
    c /= double(g.verts.size());
    const V3 u = (p[g.verts[0]] - c).normalized();
    const V3 w = g.n.cross(u);
    auto uv = [&](int v) { return Eigen::Vector2d((p[v] - c).dot(u), (p[v] - c).dot(w)); };
    std::sort(g.verts.begin(), g.verts.end(), [&](int a, int b) {
      const Eigen::Vector2d pa = uv(a), pb = uv(b);
      return pa.x() != pb.x() ? pa.x() < pb.x() : pa.y() < pb.y();
    });
    auto cross2 = [&](int o, int a, int b) {
      const Eigen::Vector2d po = uv(o), pa = uv(a) - po, pb = uv(b) - po;
      return pa.x() * pb.y() - pa.y() * pb.x();
    };
    const double area2Tol = eps * size;  // collinear within the hull tolerance
    std::vector<int> ring;
    for (int pass = 0; pass < 2; ++pass) {
      const std::size_t start = ring.size();
      for (std::size_t k = 0; k < g.verts.size(); ++k) {
        const int v = pass == 0 ? g.verts[k] : g.verts[g.verts.size() - 1 - k];
        while (ring.size() >= start + 2 && cross2(ring[ring.size() - 2], ring.back(), v) <= area2Tol) ring.pop_back();
        ring.push_back(v);
      }
      ring.pop_back();  // the last point starts the other chain
    }
    g.verts = ring;
    HullFace f;
    f.normal = g.n.cast<Real>();
    f.first = std::uint32_t(hull.faceVertices.size());
    f.count = std::uint32_t(g.verts.size());
    double offset = -std::numeric_limits<double>::max();
    for (int v : g.verts) {
      if (remap[v] < 0) {
        remap[v] = int(hull.vertices_m.size());
        hull.vertices_m.push_back(points[v]);
      }
      hull.faceVertices.push_back(std::uint32_t(remap[v]));
      offset = std::max(offset, g.n.dot(p[v]));
    }
    f.offset_m = Real(offset);
    hull.faces.push_back(f);
  }
  // Edges (each once) with the two faces that share them.
  for (std::uint32_t fi = 0; fi < hull.faces.size(); ++fi) {
    const HullFace& f = hull.faces[fi];
    for (std::uint32_t k = 0; k < f.count; ++k) {
      const std::uint32_t a = hull.faceVertices[f.first + k], b = hull.faceVertices[f.first + (k + 1) % f.count];
      auto it = std::find_if(hull.edges.begin(), hull.edges.end(),
                             [&](const HullEdge& e) { return e.v0 == b && e.v1 == a; });
      if (it != hull.edges.end())
        it->face1 = fi;
      else
        hull.edges.push_back({a, b, fi, fi});
    }
    for (std::uint32_t k = 1; k + 1 < f.count; ++k)
      hull.triangles.push_back({hull.faceVertices[f.first], hull.faceVertices[f.first + k],
                                hull.faceVertices[f.first + k + 1]});
  }
  // A closed convex polytope: every edge between two faces, V - E + F = 2.
  // Round-off in a nearly degenerate cloud could break that; refuse it
  // rather than hand the narrow phase a broken mesh.
  const bool closed = std::all_of(hull.edges.begin(), hull.edges.end(),
                                  [](const HullEdge& e) { return e.face0 != e.face1; }) &&
                      hull.vertices_m.size() + hull.faces.size() == hull.edges.size() + 2;
  if (!closed)
    return makeError("convex hull points are too close to degenerate (nearly flat or with near-duplicates) to "
                     "build a closed hull; spread them out");
  const MassProperties mp = massPropertiesOfMesh(hull.vertices_m, hull.triangles, 1);
  hull.volume_m3 = mp.volume_m3;
  hull.centroid_m = mp.centreOfMass_m;
  hull.unitInertia_m2 = mp.volume_m3 > 0 ? Mat3(mp.inertia_kgm2 / mp.volume_m3) : Mat3::Zero();
  hull.boundsLo_m = lo.cast<Real>();
  hull.boundsHi_m = hi.cast<Real>();
  for (const Vec3& v : hull.vertices_m) hull.boundingRadius_m = std::max(hull.boundingRadius_m, v.norm());
  hull.innerRadius_m = std::numeric_limits<Real>::max();
  for (const HullFace& f : hull.faces) hull.innerRadius_m = std::min(hull.innerRadius_m, f.offset_m);
  return hull;
}

ConvexHull toPrincipalFrame(ConvexHull hull, ShapeFrame* frame) {
  const PrincipalFrame pf = principalFrame(hull.unitInertia_m2);
  const Vec3 c = hull.centroid_m;
  const Mat3 Rt = pf.rotation.toRotationMatrix().transpose();
  hull.boundsLo_m = Vec3::Constant(std::numeric_limits<Real>::max());
  hull.boundsHi_m = -hull.boundsLo_m;
  hull.boundingRadius_m = 0;
  for (Vec3& v : hull.vertices_m) {
    v = Rt * (v - c);
    hull.boundsLo_m = hull.boundsLo_m.cwiseMin(v);
    hull.boundsHi_m = hull.boundsHi_m.cwiseMax(v);
    hull.boundingRadius_m = std::max(hull.boundingRadius_m, v.norm());
  }
  hull.innerRadius_m = std::numeric_limits<Real>::max();
  for (HullFace& f : hull.faces) {
    f.normal = (Rt * f.normal).normalized();
    f.offset_m = -std::numeric_limits<Real>::max();
    for (std::uint32_t k = 0; k < f.count; ++k)
      f.offset_m = std::max(f.offset_m, f.normal.dot(hull.vertices_m[hull.faceVertices[f.first + k]]));
    hull.innerRadius_m = std::min(hull.innerRadius_m, f.offset_m);
  }
  hull.centroid_m = Vec3::Zero();
  hull.unitInertia_m2 = pf.moments_kgm2.asDiagonal();
  if (frame) *frame = {c, pf.rotation};
  return hull;
}

Result<Shape> makeHullShape(std::span<const Vec3> points, ShapeFrame* frame) {
  auto hull = computeConvexHull(points);
  if (!hull) return makeError(hull.error());
  Shape s;
  s.type = ShapeType::Hull;
  s.hull = std::make_shared<const ConvexHull>(toPrincipalFrame(std::move(hull.value()), frame));
  return s;
}

}  // namespace tumble::physics
