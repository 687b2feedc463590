#include "terrain/static_objects.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace tumble::terrain {

namespace {

// X/Z world rectangle of a node, from its implicit block range.
struct RectXZ {
  double x0, z0, x1, z1;
};

RectXZ nodeRect(const HeightTree& tree, const TerrainDesc& d, const NodeRef& r) {
  const BlockRange b = tree.blocks(r);
  return {d.originX_m + b.bi0 * d.spacing_m, d.originZ_m + b.bj0 * d.spacing_m, d.originX_m + b.bi1 * d.spacing_m,
          d.originZ_m + b.bj1 * d.spacing_m};
}

bool insideXZ(const RectXZ& r, const Aabb& box) {
  return box.min.x() >= r.x0 && box.max.x() <= r.x1 && box.min.z() >= r.z0 && box.max.z() <= r.z1;
}

bool overlapsXZ(const RectXZ& r, const Aabb& box) {
  return box.min.x() <= r.x1 && box.max.x() >= r.x0 && box.min.z() <= r.z1 && box.max.z() >= r.z0;
}

}  // namespace

Status StaticObjects::add(const HeightTree& tree, const TerrainDesc& desc, std::uint32_t id, const Aabb& box) {
  if (m_objects.count(id)) return makeError("static object " + std::to_string(id) + " is already registered");
  if (!box.min.allFinite() || !box.max.allFinite() || (box.min.array() > box.max.array()).any())
    return makeError("static object " + std::to_string(id) + ": box must be finite with min <= max");
  TUMBLE_ASSERT(!tree.empty(), "StaticObjects::add: build the tree first");
  // Descend while exactly one child covers the whole X/Z projection.
  NodeRef at{0, 0, 0};
  if (insideXZ(nodeRect(tree, desc, at), box)) {
    std::array<NodeRef, 4> kids;
    for (;;) {
      const int n = tree.children(at, kids);
      int covering = -1;
      for (int k = 0; k < n; ++k)
        if (insideXZ(nodeRect(tree, desc, kids[std::size_t(k)]), box)) {
          covering = k;
          break;
        }
      if (covering < 0) break;
      at = kids[std::size_t(covering)];
    }
  }
  const std::uint32_t node = tree.index(at);
  m_objects[id] = {box, node};
  m_atNode[node].push_back(id);
  for (NodeRef r = at;; r = HeightTree::parent(r)) {
    ++m_inSubtree[tree.index(r)];
    if (r.level == 0) break;
  }
  return Ok{};
}

bool StaticObjects::remove(const HeightTree& tree, std::uint32_t id) {
  auto it = m_objects.find(id);
  if (it == m_objects.end()) return false;
  const std::uint32_t node = it->second.node;
  auto& ids = m_atNode[node];
  ids.erase(std::find(ids.begin(), ids.end(), id));
  if (ids.empty()) m_atNode.erase(node);
  for (NodeRef r = tree.ref(node);; r = HeightTree::parent(r)) {
    auto c = m_inSubtree.find(tree.index(r));
    if (--c->second == 0) m_inSubtree.erase(c);
    if (r.level == 0) break;
  }
  m_objects.erase(it);
  return true;
}

std::uint32_t StaticObjects::nodeOf(std::uint32_t id) const {
  auto it = m_objects.find(id);
  TUMBLE_ASSERT(it != m_objects.end(), "StaticObjects::nodeOf: unknown id; check contains() first");
  return it->second.node;
}

const Aabb& StaticObjects::boxOf(std::uint32_t id) const {
  auto it = m_objects.find(id);
  TUMBLE_ASSERT(it != m_objects.end(), "StaticObjects::boxOf: unknown id; check contains() first");
  return it->second.box;
}

void StaticObjects::query(const HeightTree& tree, const TerrainDesc& desc, const Aabb& box,
                          std::vector<std::uint32_t>& out) const {
  if (m_objects.empty()) return;
  // Depth-first over nodes with objects below them; the root is always
  // visited because objects not over the terrain live there.
  std::array<NodeRef, 4 * HeightTree::kMaxLevels> stack;
  int top = 0;
  stack[std::size_t(top++)] = {0, 0, 0};
  std::array<NodeRef, 4> kids;
  while (top > 0) {
    const NodeRef r = stack[std::size_t(--top)];
    const std::uint32_t idx = tree.index(r);
    if (!m_inSubtree.count(idx)) continue;
    if (r.level > 0 && !overlapsXZ(nodeRect(tree, desc, r), box)) continue;
    if (auto at = m_atNode.find(idx); at != m_atNode.end())
      for (std::uint32_t id : at->second)
        if (m_objects.at(id).box.overlaps(box)) out.push_back(id);
    const int n = tree.children(r, kids);
    for (int k = 0; k < n; ++k) stack[std::size_t(top++)] = kids[std::size_t(k)];
  }
}

std::size_t StaticObjects::approximateBytes() const {
  // Hash nodes are roughly key + value + two pointers each.
  return m_objects.size() * (sizeof(std::uint32_t) + sizeof(Object) + 16) +
         m_atNode.size() * (sizeof(std::uint32_t) + sizeof(std::vector<std::uint32_t>) + 16) + m_objects.size() * 4 +
         m_inSubtree.size() * (8 + 16);
}

}  // namespace tumble::terrain
