#pragma once
// Terrain: a height map placed in the world, its quad-tree, optional
// material maps and static objects, and the queries physics and rendering
// use. Sections: creation, world mapping, point queries, ray cast, box
// overlap, frustum culling, materials, static objects, memory.
//
// World mapping (terrain_desc.h): sample (i, j) sits at
//   (originX_m + i * spacing_m, baseHeight_m + value * heightScale_m, originZ_m + j * spacing_m).
//
// Triangle split. Block (bi, bj) has corners p00 = sample (bi, bj),
// p10 = (bi+1, bj), p01 = (bi, bj+1), p11 = (bi+1, bj+1); with local
// u = (x - x(p00)) / spacing and v = (z - z(p00)) / spacing in [0, 1] it is
// cut along the diagonal p00-p11:
//   half 0 (u >= v): triangle (p00, p11, p10)
//   half 1 (u <  v): triangle (p00, p01, p11)
// Both wind counter-clockwise seen from +Y. heightAt and normalAt use exactly
// these planes, so they agree with the triangles, the ray cast and the box
// query (points on the diagonal belong to half 0).
//
// Outside the grid, heightAt/normalAt/frictionAt/softnessAt clamp to the nearest edge
// block; use contains() to tell.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "terrain/height_map.h"
#include "terrain/height_tree.h"
#include "terrain/material_map.h"
#include "terrain/static_objects.h"
#include "terrain/terrain_desc.h"
#include "terrain/terrain_types.h"

namespace tumble::terrain {

class Terrain {
 public:
  // --- creation -----------------------------------------------------------
  /// Checks the size and the desc, builds the tree. `leafBlocks` as in HeightTree.
  static Result<Terrain> create(HeightMap heights, const TerrainDesc& desc, int leafBlocks = kDefaultLeafBlocks);
  /// Loads "path" and its sidecar "path.json" if present (else `defaults`).
  static Result<Terrain> loadPng(const std::string& path, const TerrainDesc& defaults = {},
                                 int leafBlocks = kDefaultLeafBlocks);

  const HeightMap& heights() const { return m_heights; }
  const TerrainDesc& desc() const { return m_desc; }
  const HeightTree& tree() const { return m_tree; }
  int blocksX() const { return m_heights.blocksX(); }
  int blocksZ() const { return m_heights.blocksZ(); }

  /// Edit samples, then refit the tree over what changed. `edit` gets the
  /// HeightMap; [i0, i1] x [j0, j1] (inclusive) must cover every changed sample.
  template <typename Fn>
  void editHeights(int i0, int j0, int i1, int j1, Fn&& edit) {
    edit(m_heights);
    m_tree.refit(m_heights, i0, j0, i1, j1);
  }

  // --- world mapping ------------------------------------------------------
  Vec3 samplePosition(int i, int j) const;
  /// True if (x, z) lies over the grid (edges included).
  bool contains(Real x_m, Real z_m) const;
  /// World-space Y of a 16-bit value.
  double toHeight_m(double value) const { return m_desc.baseHeight_m + value * m_desc.heightScale_m; }
  /// Axis-aligned bounds of the whole terrain.
  Aabb bounds() const { return nodeBounds(0); }

  // --- point queries --------------------------------------------------------
  Real heightAt(Real x_m, Real z_m) const;
  /// Unit face normal of the triangle under (x, z).
  Vec3 normalAt(Real x_m, Real z_m) const;
  /// Block under (x, z), clamped to the grid.
  void blockAt(Real x_m, Real z_m, int& bi, int& bj) const;
  TerrainTriangle triangle(std::uint32_t block, int half) const;

  // --- ray cast -------------------------------------------------------------
  /// Closest hit along origin + t * normalize(direction), 0 <= t <= maxDistance_m.
  /// Triangles are hit from either side; the normal is always the upward face.
  std::optional<RayHit> rayCast(const Vec3& origin, const Vec3& direction, Real maxDistance_m) const;

  // --- box overlap (allocation-free) ------------------------------------------
  /// Calls fn(const TerrainTriangle&) for each triangle whose bounding box
  /// overlaps `box`. No allocation; physics calls this every step.
  template <typename Fn>
  void forEachTriangleInBox(const Aabb& box, Fn&& fn) const {
    visitTrianglesInBox(box, [](void* ctx, const TerrainTriangle& t) { (*static_cast<Fn*>(ctx))(t); }, &fn);
  }
  /// Same, collected: clears `out` and fills it (reuse `out` across calls to
  /// avoid allocating). Static objects overlapping the box go to `objects` if given.
  void overlapBox(const Aabb& box, std::vector<TerrainTriangle>& out,
                  std::vector<std::uint32_t>* objects = nullptr) const;

  // --- frustum culling ------------------------------------------------------
  /// Clears `out` and fills it with the indices of the tree nodes at `level`
  /// (clamped to the leaf level) whose boxes are at least partly inside the
  /// frustum: the renderer's chunk list.
  void frustumCull(const Frustum& frustum, int level, std::vector<std::uint32_t>& out) const;
  /// World AABB of a tree node (X/Z from its blocks, Y from its min/max).
  Aabb nodeBounds(std::uint32_t nodeIndex) const;

  // --- materials ------------------------------------------------------------
  /// Nullptr until created: a scene without material maps pays nothing.
  const MaterialMaps* materials() const { return m_materials.has_value() ? &*m_materials : nullptr; }
  MaterialMaps* materials() { return m_materials.has_value() ? &*m_materials : nullptr; }
  MaterialMaps& createMaterials(const MaterialDefaults& defaults = {});
  /// Coulomb friction coefficient of the block under (x, z): from the
  /// friction layer, or the default (0.6) without material maps.
  Real frictionAt(Real x_m, Real z_m) const;
  /// Softness of the block under (x, z) (unitless, material_map.h): from
  /// the softness layer, or the default (0.4) without material maps.
  Real softnessAt(Real x_m, Real z_m) const;

  // --- static objects -------------------------------------------------------
  Status addStaticObject(std::uint32_t id, const Aabb& box) { return m_objects.add(m_tree, m_desc, id, box); }
  bool removeStaticObject(std::uint32_t id) { return m_objects.remove(m_tree, id); }
  const StaticObjects& staticObjects() const { return m_objects; }
  /// Appends the ids of static objects whose AABB overlaps `box`.
  void staticObjectsInBox(const Aabb& box, std::vector<std::uint32_t>& out) const {
    m_objects.query(m_tree, m_desc, box, out);
  }

  // --- memory ---------------------------------------------------------------
  TerrainMemory memory() const;

 private:
  using TriangleVisitor = void (*)(void* ctx, const TerrainTriangle& triangle);
  void visitTrianglesInBox(const Aabb& box, TriangleVisitor visit, void* ctx) const;

  HeightMap m_heights;
  TerrainDesc m_desc;
  HeightTree m_tree;
  std::optional<MaterialMaps> m_materials;
  StaticObjects m_objects;
};

}  // namespace tumble::terrain
