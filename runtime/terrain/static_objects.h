#pragma once
// Registry of static objects (rocks, trees, buildings) placed on the terrain.
// Each object is an id and a world AABB, registered at the tightest tree node
// whose X/Z extent covers the object's X/Z projection. Objects whose
// projection is not entirely over the terrain go to the root, so they are
// still found by every query that could touch them.
//
// Queries walk only the nodes that have objects in their subtree (a count per
// such node, in a hash map, so a terrain with no objects pays nothing).
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/result.h"
#include "terrain/height_tree.h"
#include "terrain/terrain_desc.h"
#include "terrain/terrain_types.h"

namespace tumble::terrain {

class StaticObjects {
 public:
  /// Duplicate ids and non-finite or inverted boxes are errors (mod data).
  Status add(const HeightTree& tree, const TerrainDesc& desc, std::uint32_t id, const Aabb& box);
  bool remove(const HeightTree& tree, std::uint32_t id);
  bool contains(std::uint32_t id) const { return m_objects.count(id) != 0; }
  std::size_t size() const { return m_objects.size(); }
  /// Index of the node the object is registered at (see HeightTree::index).
  std::uint32_t nodeOf(std::uint32_t id) const;
  const Aabb& boxOf(std::uint32_t id) const;

  /// Appends the ids of objects whose AABB overlaps `box` to `out`.
  void query(const HeightTree& tree, const TerrainDesc& desc, const Aabb& box, std::vector<std::uint32_t>& out) const;

  std::size_t approximateBytes() const;

 private:
  struct Object {
    Aabb box;
    std::uint32_t node = 0;
  };
  std::unordered_map<std::uint32_t, Object> m_objects;                        // id -> object
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> m_atNode;     // node -> ids registered there
  std::unordered_map<std::uint32_t, std::uint32_t> m_inSubtree;              // node -> objects at or below it
};

}  // namespace tumble::terrain
