#include "terrain/height_tree.h"

#include <algorithm>

namespace tumble::terrain {

void HeightTree::build(const HeightMap& map, int leafBlocks) {
  TUMBLE_ASSERT(leafBlocks >= 1 && leafBlocks <= 256 && (leafBlocks & (leafBlocks - 1)) == 0,
                "HeightTree::build: leafBlocks must be a power of two in [1, 256]");
  TUMBLE_ASSERT(map.width() >= 2 && map.height() >= 2, "HeightTree::build: the map needs at least 2 x 2 samples");
  m_blocksX = map.blocksX();
  m_blocksZ = map.blocksZ();
  m_leafBlocks = leafBlocks;
  const int leavesX = (m_blocksX + leafBlocks - 1) / leafBlocks;
  const int leavesZ = (m_blocksZ + leafBlocks - 1) / leafBlocks;
  int depth = 0;
  while ((1 << depth) < std::max(leavesX, leavesZ)) ++depth;
  TUMBLE_ASSERT(depth + 1 <= kMaxLevels, "HeightTree::build: map too large for kMaxLevels");
  m_levelCount = depth + 1;
  std::uint32_t offset = 0;
  for (int l = 0; l < m_levelCount; ++l) {
    const int shift = depth - l;
    m_levelWidth[std::size_t(l)] = (leavesX + (1 << shift) - 1) >> shift;
    m_levelHeight[std::size_t(l)] = (leavesZ + (1 << shift) - 1) >> shift;
    m_levelOffset[std::size_t(l)] = offset;
    offset += std::uint32_t(m_levelWidth[std::size_t(l)]) * std::uint32_t(m_levelHeight[std::size_t(l)]);
  }
  m_levelOffset[std::size_t(m_levelCount)] = offset;
  m_nodes.assign(offset, TreeNode{});
  m_nodes.shrink_to_fit();
  const int leaf = leafLevel();
  for (int z = 0; z < levelHeight(leaf); ++z)
    for (int x = 0; x < levelWidth(leaf); ++x) computeLeaf(map, x, z);
  for (int l = leaf - 1; l >= 0; --l)
    for (int z = 0; z < levelHeight(l); ++z)
      for (int x = 0; x < levelWidth(l); ++x) computeInner(l, x, z);
}

void HeightTree::computeLeaf(const HeightMap& map, int x, int z) {
  const BlockRange b = blocks({leafLevel(), x, z});
  std::uint16_t lo = 0xffff, hi = 0;
  const std::uint16_t* s = map.samples().data();
  const std::size_t w = std::size_t(map.width());
  // Blocks [bi0, bi1) touch samples [bi0, bi1] inclusive.
  for (int j = b.bj0; j <= b.bj1; ++j) {
    const std::uint16_t* row = s + std::size_t(j) * w;
    for (int i = b.bi0; i <= b.bi1; ++i) {
      lo = std::min(lo, row[i]);
      hi = std::max(hi, row[i]);
    }
  }
  m_nodes[index(leafLevel(), x, z)] = {lo, hi};
}

void HeightTree::computeInner(int level, int x, int z) {
  std::array<NodeRef, 4> kids;
  const int n = children({level, x, z}, kids);
  TreeNode box{0xffff, 0};
  for (int k = 0; k < n; ++k) {
    const TreeNode& c = node(kids[std::size_t(k)]);
    box.minHeight = std::min(box.minHeight, c.minHeight);
    box.maxHeight = std::max(box.maxHeight, c.maxHeight);
  }
  m_nodes[index(level, x, z)] = box;
}

void HeightTree::refit(const HeightMap& map, int i0, int j0, int i1, int j1) {
  if (empty()) return;
  // Sample i belongs to blocks i-1 and i.
  const int bi0 = std::clamp(i0 - 1, 0, m_blocksX - 1), bi1 = std::clamp(i1, 0, m_blocksX - 1);
  const int bj0 = std::clamp(j0 - 1, 0, m_blocksZ - 1), bj1 = std::clamp(j1, 0, m_blocksZ - 1);
  int x0 = bi0 / m_leafBlocks, x1 = bi1 / m_leafBlocks, z0 = bj0 / m_leafBlocks, z1 = bj1 / m_leafBlocks;
  for (int z = z0; z <= z1; ++z)
    for (int x = x0; x <= x1; ++x) computeLeaf(map, x, z);
  for (int l = leafLevel() - 1; l >= 0; --l) {
    x0 /= 2, x1 /= 2, z0 /= 2, z1 /= 2;
    for (int z = z0; z <= z1; ++z)
      for (int x = x0; x <= x1; ++x) computeInner(l, x, z);
  }
}

NodeRef HeightTree::ref(std::uint32_t idx) const {
  TUMBLE_ASSERT(idx < m_nodes.size(), "HeightTree::ref: node index out of range");
  int level = 0;
  while (idx >= m_levelOffset[std::size_t(level) + 1]) ++level;
  const std::uint32_t local = idx - m_levelOffset[std::size_t(level)];
  const std::uint32_t w = std::uint32_t(m_levelWidth[std::size_t(level)]);
  return {level, int(local % w), int(local / w)};
}

int HeightTree::children(const NodeRef& r, std::array<NodeRef, 4>& out) const {
  if (r.level >= leafLevel()) return 0;
  const int l = r.level + 1;
  int n = 0;
  for (int dz = 0; dz < 2; ++dz)
    for (int dx = 0; dx < 2; ++dx) {
      const int x = 2 * r.x + dx, z = 2 * r.z + dz;
      if (x < levelWidth(l) && z < levelHeight(l)) out[std::size_t(n++)] = {l, x, z};
    }
  return n;
}

BlockRange HeightTree::blocks(const NodeRef& r) const {
  const int s = blocksPerSide(r.level);
  return {r.x * s, r.z * s, std::min((r.x + 1) * s, m_blocksX), std::min((r.z + 1) * s, m_blocksZ)};
}

std::size_t HeightTree::bytes() const {
  return m_nodes.capacity() * sizeof(TreeNode) + sizeof(m_levelWidth) + sizeof(m_levelHeight) + sizeof(m_levelOffset);
}

}  // namespace tumble::terrain
