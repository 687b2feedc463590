// Building mesh shapes: the node tree in depth-first order, the boxes, and
// the active-edge flags (mesh_shape.h explains the layout and the choices).
#include "physics/mesh_shape.h"

#include <algorithm>
#include <limits>

namespace tumble::physics {

void MeshStats::add(const MeshStats& o) {
  pairs += o.pairs;
  nodesVisited += o.nodesVisited;
  subtreesSkipped += o.subtreesSkipped;
  nodesSkippedTight += o.nodesSkippedTight;
  trianglesTested += o.trianglesTested;
  exactTests += o.exactTests;
  rays += o.rays;
}

namespace {

std::string nodeLabel(const MeshTreeInput& tree, std::size_t i) {
  const std::string& name = tree.nodes[i].name;
  return "mesh node " + std::to_string(i + 1) + (name.empty() ? std::string() : " ('" + name + "')");
}

/// Marks each edge active unless exactly one neighbour shares it (same
/// vertex positions, opposite direction) and that neighbour is coplanar or
/// folds towards the front (concave).
void findActiveEdges(std::vector<MeshTriangle>& tris) {
  struct EdgeRecord {
    std::array<Real, 6> key;  // the edge's two end points, smaller first
    std::uint32_t tri;
    std::uint8_t edge;
  };
  std::vector<EdgeRecord> edges;
  edges.reserve(tris.size() * 3);
  auto less = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    for (std::uint8_t e = 0; e < 3; ++e) {
      Vec3 a = tris[t].v[e], b = tris[t].v[(e + 1) % 3];
      if (less(b, a)) std::swap(a, b);
      edges.push_back({{a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}, t, e});
    }
  std::sort(edges.begin(), edges.end(), [](const EdgeRecord& x, const EdgeRecord& y) {
    return x.key != y.key ? x.key < y.key : (x.tri != y.tri ? x.tri < y.tri : x.edge < y.edge);
  });
  const Real cosActive = std::cos(kActiveEdgeAngle_rad);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    if (j - i == 2) {
      MeshTriangle& t1 = tris[edges[i].tri];
      MeshTriangle& t2 = tris[edges[i + 1].tri];
      const int e1 = edges[i].edge, e2 = edges[i + 1].edge;
      const bool opposite = t1.v[e1] == t2.v[(e2 + 1) % 3];  // consistent winding walks a shared edge both ways
      const Vec3& w2 = t2.v[(e2 + 2) % 3];                     // t2's vertex off the edge
      const Real fold = t1.normal.dot(w2 - t1.v[e1]);         // < 0: t2 bends away behind t1's front (convex)
      const bool crease = fold < 0 && t1.normal.dot(t2.normal) < cosActive;
      if (opposite && !crease) {
        t1.activeEdges &= std::uint8_t(~(1u << e1));
        t2.activeEdges &= std::uint8_t(~(1u << e2));
      }
    }
    i = j;
  }
}

}  // namespace

Result<Shape> makeMeshShape(const MeshTreeInput& tree, const Vec3& scale) {
  if (tree.nodes.empty()) return makeError("a mesh shape needs at least one node with triangles");
  if (!scale.allFinite() || (scale.array() == 0).any())
    return makeError("mesh scale must be finite and non-zero on every axis");
  const std::size_t n = tree.nodes.size();
  std::vector<std::vector<std::uint32_t>> children(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int p = tree.nodes[i].parent;
    if (i == 0 ? p != -1 : (p < 0 || std::size_t(p) >= i))
      return makeError(nodeLabel(tree, i) + ": parent must be an earlier node (the root, node 1, has none)");
    if (i > 0) children[std::size_t(p)].push_back(std::uint32_t(i));
  }
  auto mesh = std::make_shared<MeshShape>();
  // Depth-first order with an explicit stack (children in their given order).
  std::vector<std::uint32_t> order, stack{0};
  order.reserve(n);
  while (!stack.empty()) {
    const std::uint32_t i = stack.back();
    stack.pop_back();
    order.push_back(i);
    for (auto it = children[i].rbegin(); it != children[i].rend(); ++it) stack.push_back(*it);
  }
  const bool flip = scale.prod() < 0;
  mesh->nodes.resize(n);
  std::vector<std::uint32_t> position(n);  // input index -> depth-first index
  for (std::uint32_t k = 0; k < n; ++k) position[order[k]] = k;
  for (std::uint32_t k = 0; k < n; ++k) {
    const MeshTreeNodeInput& in = tree.nodes[order[k]];
    MeshNode& node = mesh->nodes[k];
    node.firstTriangle = std::uint32_t(mesh->triangles.size());
    for (std::size_t v = 0; v < in.vertices_m.size(); ++v)
      if (!in.vertices_m[v].allFinite())
        return makeError(nodeLabel(tree, order[k]) + ": vertex " + std::to_string(v + 1) +
                         " is not finite (every coordinate must be a number, in metres)");
    for (std::size_t t = 0; t < in.triangles.size(); ++t) {
      const auto& idx = in.triangles[t];
      if (idx[0] >= in.vertices_m.size() || idx[1] >= in.vertices_m.size() || idx[2] >= in.vertices_m.size())
        return makeError(nodeLabel(tree, order[k]) + ": triangle " + std::to_string(t + 1) +
                         " names a vertex that does not exist (" + std::to_string(in.vertices_m.size()) + " vertices)");
      MeshTriangle tri;
      for (int c = 0; c < 3; ++c) tri.v[c] = in.vertices_m[idx[c]].cwiseProduct(scale);
      if (flip) std::swap(tri.v[1], tri.v[2]);
      const Vec3 cross = (tri.v[1] - tri.v[0]).cross(tri.v[2] - tri.v[0]);
      const Real len = cross.norm();
      if (!(len > Real(1e-12))) continue;  // zero area: no normal, no contact
      tri.normal = cross / len;
      tri.lo_m = tri.v[0].cwiseMin(tri.v[1]).cwiseMin(tri.v[2]);
      tri.hi_m = tri.v[0].cwiseMax(tri.v[1]).cwiseMax(tri.v[2]);
      mesh->triangles.push_back(tri);
    }
    node.triangleCount = std::uint32_t(mesh->triangles.size()) - node.firstTriangle;
    if (mesh->triangles.size() > kMaxMeshTriangles)
      return makeError("mesh has more than " + std::to_string(kMaxMeshTriangles) + " triangles; simplify the model");
  }
  if (mesh->triangles.empty()) return makeError("mesh has no triangles with area (nothing to collide with)");
  // Boxes: tight from the node's own triangles; covering from the last node
  // back (children come after their parent in depth-first order).
  constexpr Real inf = std::numeric_limits<Real>::infinity();
  for (MeshNode& node : mesh->nodes) {
    node.tightLo_m = Vec3::Constant(inf);
    node.tightHi_m = Vec3::Constant(-inf);
    for (std::uint32_t t = node.firstTriangle; t < node.firstTriangle + node.triangleCount; ++t) {
      node.tightLo_m = node.tightLo_m.cwiseMin(mesh->triangles[t].lo_m);
      node.tightHi_m = node.tightHi_m.cwiseMax(mesh->triangles[t].hi_m);
    }
    node.coverLo_m = node.tightLo_m;
    node.coverHi_m = node.tightHi_m;
  }
  for (std::uint32_t k = std::uint32_t(n); k-- > 0;) {
    MeshNode& node = mesh->nodes[k];
    node.subtreeEnd = k + 1;
    for (std::uint32_t c : children[order[k]]) {
      const MeshNode& child = mesh->nodes[position[c]];
      node.coverLo_m = node.coverLo_m.cwiseMin(child.coverLo_m);
      node.coverHi_m = node.coverHi_m.cwiseMax(child.coverHi_m);
      node.subtreeEnd = std::max(node.subtreeEnd, child.subtreeEnd);
    }
  }
  findActiveEdges(mesh->triangles);
  for (const MeshTriangle& t : mesh->triangles)
    for (const Vec3& v : t.v) mesh->boundingRadius_m = std::max(mesh->boundingRadius_m, v.norm());
  Shape s;
  s.type = ShapeType::Mesh;
  s.mesh = std::move(mesh);
  return s;
}

}  // namespace tumble::physics
