#pragma once
// Static triangle meshes (ShapeType::Mesh): the collision side of a model's
// object tree (the driving paper's tree: each node holds meshes and an
// optional transform, a tight box around its own triangles and a covering
// box around its own and every descendant's).
//
// Index
//   MeshTreeNodeInput, MeshTreeInput   plain data in: a node tree of triangles (no render types)
//   MeshTriangle, MeshNode, MeshShape  the built shape: nodes in depth-first order, boxes, triangles
//   MeshStats                          what the tree saved (nodes skipped, triangles tested)
//   makeMeshShape                      checks and builds; the message names the bad node / vertex
//
// Only static bodies may have a mesh shape (World::createBody refuses
// others): a mesh has no volume and no inside, so it has no mass.
//
// Layout. Nodes are stored depth first; node i's subtree is nodes [i,
// subtreeEnd), so a query that misses node i's covering box jumps to
// subtreeEnd without reading the children (no pointers, no recursion: the
// hot loop walks one array). Each node's triangles are a contiguous range of
// one triangle array, already in the body frame (the node transforms and the
// placement scale are applied when the shape is built; the body pose then
// places it, so one shape serves any position and rotation).
//
// One-sided triangles. A triangle collides only with what is in front of it
// (the side its counter-clockwise winding faces: outside of a closed model,
// as assimp and every model format give it). A body whose centre is behind
// a triangle's plane is not pushed by it, so a body that ends up inside a
// rock (spawned there, or pushed in) is not shot out through the far side by
// back faces, and the thin shell of a model never traps a body between its
// two sides. Rays and continuous collision hit front faces only, for the
// same reason. Rejected: two-sided triangles (a body that crosses the middle
// of a thin wall in one step is pushed on through; the choice for a closed
// model would be arbitrary per triangle). A model drawn with single flat
// quads (a sign) collides from its front only; scale it by -1 on one axis or
// use collision = "box" for such props.
//
// Internal edges. Each triangle edge is "active" only if it is a real
// convex crease (the neighbour across it bends away by more than
// kActiveEdgeAngle_rad), or has no neighbour (an open border), or more than
// one. Edges shared with a coplanar or concave neighbour are inactive: a
// contact whose normal leans over an inactive edge (or a vertex with only
// inactive edges) is not a real contact - the neighbour's face contact
// covers it - and is dropped (mesh_collision.cpp). Neighbours are found by
// bit-identical vertex positions when the shape is built (models duplicate
// vertices per face for normals and uvs, so indices cannot be used).
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "physics/shape.h"

namespace tumble::physics {

/// One node of the input tree: its own triangles in the mesh shape's frame
/// (node transforms already applied) and its parent.
struct MeshTreeNodeInput {
  int parent = -1;  ///< index of the parent node (< this node's index); -1 for the root (node 0)
  std::vector<Vec3> vertices_m;                          ///< m, in the shape's frame
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< counter-clockwise seen from the front (outside)
  std::string name;                                      ///< for error messages ("node 'trunk'")
};

/// A node tree of triangles, parents before children (as render::Model
/// stores its nodes). The app builds it from a model file.
struct MeshTreeInput {
  std::vector<MeshTreeNodeInput> nodes;
};

struct MeshTriangle {
  Vec3 v[3];                    ///< m, body frame, counter-clockwise seen from the front
  Vec3 normal = Vec3::UnitY();  ///< unit front normal
  Vec3 lo_m, hi_m;              ///< the triangle's box (body frame)
  std::uint8_t activeEdges = 7;  ///< bit e: edge v[e] -> v[(e + 1) % 3] is a convex crease or a border
};

struct MeshNode {
  std::uint32_t firstTriangle = 0, triangleCount = 0;  ///< this node's own triangles
  std::uint32_t subtreeEnd = 0;  ///< one past the last node of this subtree (nodes are depth first)
  Vec3 tightLo_m = Vec3::Zero(), tightHi_m = Vec3::Zero();  ///< box of its own triangles (body frame; empty: lo > hi)
  Vec3 coverLo_m = Vec3::Zero(), coverHi_m = Vec3::Zero();  ///< box of its own and every descendant's triangles
};

struct MeshShape {
  std::vector<MeshNode> nodes;  ///< depth first; nodes[0] is the root, its cover box bounds the whole mesh
  std::vector<MeshTriangle> triangles;
  Real boundingRadius_m = 0;  ///< largest |vertex| (about the body origin)
};

/// Work done by mesh queries, summed until World::resetMeshStats. The tree
/// is working when nodesSkipped is large and trianglesTested is small
/// compared with pairs * triangles per mesh.
struct MeshStats {
  std::uint64_t pairs = 0;            ///< shape-against-mesh tests (a compound counts once per child)
  std::uint64_t nodesVisited = 0;     ///< nodes whose covering box was tested
  std::uint64_t subtreesSkipped = 0;  ///< covering box missed: the node and its descendants were not read
  std::uint64_t nodesSkippedTight = 0;  ///< covering box hit but the node's own (tight) box missed
  std::uint64_t trianglesTested = 0;  ///< triangles whose own box was compared with the query
  std::uint64_t exactTests = 0;       ///< triangles whose box was hit: the exact shape-triangle test ran
  std::uint64_t rays = 0;             ///< rays cast against meshes
  void add(const MeshStats& o);
};

/// Angle (rad) between two neighbours' normals beyond which a convex shared
/// edge is active (a real crease); flatter edges are seams.
constexpr Real kActiveEdgeAngle_rad = Real(0.05);
/// Triangles per mesh shape (beyond this, split the model or simplify it).
constexpr std::size_t kMaxMeshTriangles = 1u << 22;

/// A ShapeType::Mesh shape from a node tree; `scale` multiplies every vertex
/// (per axis; a negative product flips the winding, which is corrected).
/// Refuses (the message names the node and vertex, 1-based): no triangles
/// at all, a non-finite vertex, an index out of range, a parent that does
/// not come before its child. Degenerate (zero-area) triangles are dropped.
Result<Shape> makeMeshShape(const MeshTreeInput& tree, const Vec3& scale = Vec3::Ones());

}  // namespace tumble::physics
