#pragma once
// HeightTree: the quad-tree of bounding boxes over the height map, kept in
// ONE array with no pointers.
//
// Layout. Leaves cover leafBlocks x leafBlocks blocks (a power of two; each
// level up groups 2 x 2 nodes). Level 0 is the root, level leafLevel() holds
// the leaves. Level l is a levelWidth(l) x levelHeight(l) grid stored
// row-major starting at levelOffset(l), so a node is (level, x, z) and
//   index    = levelOffset(level) + z * levelWidth(level) + x
//   parent   = (level - 1, x / 2, z / 2)
//   children = (level + 1, 2x + {0,1}, 2z + {0,1}) that exist
// Grids are clipped to the map (a 4097 x 129 map has a 512 x 16 leaf grid,
// not 512 x 512), so non-square maps waste nothing.
//
// A node stores only the min and max sample value below it (2 x uint16);
// its X/Z extent is implicit: node (l, x, z) covers blocks
// [x * s, (x + 1) * s) x [z * s, (z + 1) * s), s = leafBlocks << (leafLevel - l),
// clipped to the map.
//
// Memory. With 8 x 8-block leaves the tree is 4 bytes / 64 blocks * 4/3
// ~= 0.083 bytes per block, so heights + tree stay under 2.1 bytes per
// sample (the terrain's target). Finer leaves are allowed (2 x 2 blocks costs
// 1.33 bytes per block, still under the 8-byte budget) but the budget of 2.1
// bytes/sample then fails; below a leaf, queries walk blocks directly and
// read the 4 samples of each block, which are already in cache.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "terrain/height_map.h"

namespace tumble::terrain {

struct TreeNode {
  std::uint16_t minHeight = 0;  ///< smallest sample value below this node (16-bit units)
  std::uint16_t maxHeight = 0;  ///< largest sample value below this node
};

/// A node's position: level (0 = root), x and z in that level's grid.
struct NodeRef {
  int level = 0;
  int x = 0;
  int z = 0;
};

/// Half-open block range [bi0, bi1) x [bj0, bj1).
struct BlockRange {
  int bi0 = 0, bj0 = 0, bi1 = 0, bj1 = 0;
};

constexpr int kDefaultLeafBlocks = 8;

class HeightTree {
 public:
  static constexpr int kMaxLevels = 16;  // 4096 blocks / 1-block leaves = 13 levels

  HeightTree() = default;
  /// `leafBlocks` must be a power of two in [1, 256].
  void build(const HeightMap& map, int leafBlocks = kDefaultLeafBlocks);
  /// After editing samples [i0, i1] x [j0, j1] (inclusive), refresh the
  /// affected leaves and their ancestors only.
  void refit(const HeightMap& map, int i0, int j0, int i1, int j1);

  bool empty() const { return m_nodes.empty(); }
  int leafBlocks() const { return m_leafBlocks; }
  int levelCount() const { return m_levelCount; }
  int leafLevel() const { return m_levelCount - 1; }
  int levelWidth(int level) const { return m_levelWidth[std::size_t(level)]; }
  int levelHeight(int level) const { return m_levelHeight[std::size_t(level)]; }
  std::uint32_t levelOffset(int level) const { return m_levelOffset[std::size_t(level)]; }
  std::size_t nodeCount() const { return m_nodes.size(); }

  std::uint32_t index(int level, int x, int z) const {
    return levelOffset(level) + std::uint32_t(z) * std::uint32_t(levelWidth(level)) + std::uint32_t(x);
  }
  std::uint32_t index(const NodeRef& r) const { return index(r.level, r.x, r.z); }
  NodeRef ref(std::uint32_t index) const;
  const TreeNode& node(std::uint32_t index) const { return m_nodes[index]; }
  const TreeNode& node(const NodeRef& r) const { return m_nodes[index(r)]; }
  static NodeRef parent(const NodeRef& r) { return {r.level - 1, r.x / 2, r.z / 2}; }
  /// Writes the existing children into `out`, returns how many (0 for a leaf).
  int children(const NodeRef& r, std::array<NodeRef, 4>& out) const;
  /// Blocks covered by a node, clipped to the map.
  BlockRange blocks(const NodeRef& r) const;
  /// Blocks per side of a node at `level` (before clipping).
  int blocksPerSide(int level) const { return m_leafBlocks << (leafLevel() - level); }

  /// Allocated bytes: the node array plus the level tables.
  std::size_t bytes() const;

 private:
  void computeLeaf(const HeightMap& map, int x, int z);
  void computeInner(int level, int x, int z);

  int m_blocksX = 0;
  int m_blocksZ = 0;
  int m_leafBlocks = kDefaultLeafBlocks;
  int m_levelCount = 0;
  std::array<int, kMaxLevels> m_levelWidth{};
  std::array<int, kMaxLevels> m_levelHeight{};
  std::array<std::uint32_t, kMaxLevels + 1> m_levelOffset{};
  std::vector<TreeNode> m_nodes;
};

}  // namespace tumble::terrain
