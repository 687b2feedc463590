#pragma once
// Sweep and prune (Baraff; Eberly, Game Physics 5.4): bodies sorted by the
// lower end of their box on one axis; each step the order is repaired by
// insertion sort, which is O(n) when bodies moved little (temporal coherence),
// then one sweep reports boxes that overlap on all three axes.
//
// Rejected: a full three-axis endpoint structure with incremental overlap
// counters. It reports pair changes rather than pairs, which we do not need
// because the narrow phase re-runs every step anyway; one sorted axis plus a
// check of the other two is simpler and as fast for scenes that are spread
// out in x. The sweep axis is the axis of largest spread, re-chosen when the
// spread changes a lot.
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace tumble::physics {

struct Aabb {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  bool overlaps(const Aabb& o) const {
    return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() && o.lo.y() <= hi.y() &&
           lo.z() <= o.hi.z() && o.lo.z() <= hi.z();
  }
};

/// The step's cost cap on pairs (WorldSettings::maxContactPairsPerBody):
/// pairs with a body that contacts cannot move (static, kinematic, a plane)
/// and pairs of two dynamic bodies each get their own allowance, so bodies
/// piled into each other never cost the ground its contacts.
struct PairBudget {
  std::size_t fixedLeft = SIZE_MAX, dynamicLeft = SIZE_MAX;
  long skipped = 0;  ///< overlapping pairs left out this step
  /// kind: 1 = a pair with a fixed body, 2 = two dynamic bodies.
  bool take(int kind) {
    std::size_t& left = kind == 1 ? fixedLeft : dynamicLeft;
    if (left == 0) return ++skipped, false;
    --left;
    return true;
  }
};

class BroadPhase {
 public:
  /// boxes[i] for every body slot; active[i] false for dead slots and planes.
  /// canCollide(i, j) filters (static-static, sleeping pairs): 0 = no, else
  /// the pair's kind for the budget (PairBudget::take).
  template <typename Filter>
  void findPairs(const std::vector<Aabb>& boxes, const std::vector<std::uint8_t>& active, Filter&& canCollide,
                 PairBudget& budget, std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs);

  /// Insertion-sort swaps in the last update (a measure of coherence).
  std::size_t lastSwaps() const { return m_swaps; }
  /// The sort order and axis kept between steps (they decide the order of
  /// the pairs), for World::saveState / restoreState.
  const std::vector<std::uint32_t>& order() const { return m_order; }
  int axis() const { return m_axis; }
  void restore(std::vector<std::uint32_t> order, int axis, std::size_t swaps) {
    m_order = std::move(order);
    m_axis = axis;
    m_swaps = swaps;
  }

 private:
  void chooseAxis(const std::vector<Aabb>& boxes);
  std::vector<std::uint32_t> m_order;  ///< body indices sorted by lo[axis]
  std::vector<std::uint8_t> m_seen;    ///< scratch, kept to avoid allocating per step
  int m_axis = 0;
  std::size_t m_swaps = 0;
};

template <typename Filter>
void BroadPhase::findPairs(const std::vector<Aabb>& boxes, const std::vector<std::uint8_t>& active,
                           Filter&& canCollide, PairBudget& budget,
                           std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
  pairs.clear();
  // Keep m_order in sync with the set of active slots.
  std::size_t w = 0;
  std::vector<std::uint8_t>& seen = m_seen;
  seen.assign(boxes.size(), 0);
  for (std::uint32_t idx : m_order)
    if (idx < active.size() && active[idx] && !seen[idx]) {
      seen[idx] = 1;
      m_order[w++] = idx;
    }
  m_order.resize(w);
  for (std::uint32_t i = 0; i < active.size(); ++i)
    if (active[i] && !seen[i]) m_order.push_back(i);
  if (m_order.size() > 64 && (m_swaps > 4 * m_order.size() || m_order.size() != boxes.size())) chooseAxis(boxes);
  // Insertion sort on lo[axis].
  m_swaps = 0;
  const int ax = m_axis;
  for (std::size_t i = 1; i < m_order.size(); ++i) {
    std::uint32_t key = m_order[i];
    Real v = boxes[key].lo[ax];
    std::size_t j = i;
    while (j > 0 && boxes[m_order[j - 1]].lo[ax] > v) {
      m_order[j] = m_order[j - 1];
      --j;
      ++m_swaps;
    }
    m_order[j] = key;
  }
  // Sweep.
  for (std::size_t i = 0; i < m_order.size(); ++i) {
    const std::uint32_t a = m_order[i];
    const Aabb& ba = boxes[a];
    for (std::size_t j = i + 1; j < m_order.size(); ++j) {
      const std::uint32_t b = m_order[j];
      const Aabb& bb = boxes[b];
      if (bb.lo[ax] > ba.hi[ax]) break;
      if (!ba.overlaps(bb)) continue;
      const int kind = canCollide(a, b);
      if (kind == 0 || !budget.take(kind)) continue;
      pairs.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
}

}  // namespace tumble::physics
