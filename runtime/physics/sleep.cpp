// Sleep and islands: bodies that have been slow for a while stop being
// simulated, and wake together with everything they touch.
//
// An island is a group of dynamic bodies joined by touching contacts or by
// island links (joints, World::setIslandLinks), found by union-find every
// step (World::updateSleep). An island whose bodies have all been slower
// than WorldSettings::sleepLinearSpeed_mps / sleepAngularSpeed_radps for
// timeToSleep_s falls asleep as one: velocities zeroed, the bodies count as
// static in the solver. Each sleeping island keeps an id (m_sleepIsland), so
// waking any body of it (a touch, a setter, World::wake) wakes all of it
// (World::wakeIsland). A kinematic body touching an island keeps it awake.
#include <algorithm>
#include <limits>
#include <numeric>
#include <vector>

#include "physics/internal/height_field_collision.h"
#include "physics/internal/manifold.h"
#include "physics/world.h"

namespace tumble::physics {

void World::wake(BodyId id) {
  if (isValid(id)) wakeIsland(id.index);
}

void World::setIslandLinks(const std::vector<std::pair<BodyId, BodyId>>& links) {
  m_islandLinks.clear();
  for (const auto& [a, b] : links)
    if (isValid(a) && isValid(b) && a.index != b.index) m_islandLinks.push_back(makePair(a, b));
  std::sort(m_islandLinks.begin(), m_islandLinks.end());
  m_islandLinks.erase(std::unique(m_islandLinks.begin(), m_islandLinks.end()), m_islandLinks.end());
  // Linked bodies must share an island: a sleeping group and an awake one
  // just linked to it wake together.
  for (const BodyPair& p : m_islandLinks) {
    const bool awakeA = m_bodies[p.a].awake, awakeB = m_bodies[p.b].awake;
    if (awakeA != awakeB || m_sleepIsland[p.a] != m_sleepIsland[p.b]) {
      wakeIsland(p.a);
      wakeIsland(p.b);
    }
  }
}

void World::wakeIsland(std::uint32_t index) {
  if (index >= m_bodies.size()) return;
  std::uint32_t island = m_sleepIsland[index];
  if (island == 0) {
    m_bodies[index].awake = true;
    m_bodies[index].sleepTime_s = 0;
    return;
  }
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i)
    if (m_sleepIsland[i] == island) {
      m_bodies[i].awake = true;
      m_bodies[i].sleepTime_s = 0;
      m_sleepIsland[i] = 0;
    }
}

void World::updateSleep(Real dt) {
  if (!m_settings.enableSleep) return;
  const std::size_t n = m_bodies.size();
  // Islands: union-find over touching contacts between dynamic bodies.
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const Manifold& m : m_manifolds) {
    if (m.b == kHeightFieldBody) continue;  // the ground joins no island
    if (!m_bodies[m.a].isDynamic() || !m_bodies[m.b].isDynamic()) continue;
    parent[find(m.a)] = find(m.b);
  }
  // Island links (joints) join islands like touching contacts.
  for (const BodyPair& p : m_islandLinks) {
    if (!m_bodies[p.a].isDynamic() || !m_bodies[p.b].isDynamic()) continue;
    parent[find(p.a)] = find(p.b);
  }
  std::vector<Real> islandMin(n, std::numeric_limits<Real>::max());
  const Real lin2 = m_settings.sleepLinearSpeed_mps * m_settings.sleepLinearSpeed_mps;
  const Real ang2 = m_settings.sleepAngularSpeed_radps * m_settings.sleepAngularSpeed_radps;
  for (std::uint32_t i = 0; i < n; ++i) {
    Body& b = m_bodies[i];
    if (!b.alive || !b.isDynamic() || !b.awake) continue;
    bool slow = b.linearVelocity_mps.squaredNorm() < lin2 && b.angularVelocity_radps.squaredNorm() < ang2;
    b.sleepTime_s = (slow && b.allowSleep) ? b.sleepTime_s + dt : 0;
    Real& mn = islandMin[find(i)];
    mn = std::min(mn, b.sleepTime_s);
  }
  // Kinematic bodies touching an island keep it awake.
  for (const Manifold& m : m_manifolds) {
    if (m.b == kHeightFieldBody) continue;
    const Body& a = m_bodies[m.a];
    const Body& b = m_bodies[m.b];
    if (a.type == BodyType::Kinematic && b.isDynamic()) islandMin[find(m.b)] = 0;
    if (b.type == BodyType::Kinematic && a.isDynamic()) islandMin[find(m.a)] = 0;
  }
  std::vector<std::uint32_t> islandId(n, 0);
  for (std::uint32_t i = 0; i < n; ++i) {
    Body& b = m_bodies[i];
    if (!b.alive || !b.isDynamic() || !b.awake) continue;
    std::uint32_t root = find(i);
    if (islandMin[root] < m_settings.timeToSleep_s) continue;
    if (islandId[root] == 0) islandId[root] = m_nextIsland++;
    b.awake = false;
    m_externalImpulse -= b.mass_kg * b.linearVelocity_mps.cast<double>();  // zeroed below
    b.linearVelocity_mps.setZero();
    b.angularVelocity_radps.setZero();
    m_sleepIsland[i] = islandId[root];
  }
}

}  // namespace tumble::physics
