// The collision pipeline of a step (World::collide): which pairs may touch,
// their contact manifolds, and the impulses those inherit from last step.
//
//   bucketOldManifolds    last step's manifolds, bucketed for warm starting
//   buildSweptBoxes       every body's box grown by what it can travel this step
//   findCandidatePairs    sweep and prune (broad_phase.h) minus the collision
//                         filter, plus every moving body against each plane
//   collideBodyPair       the narrow phase for one pair (narrow_phase.cpp,
//                         mesh_collision.cpp, swept spheres from ccd.cpp),
//                         then materials, warm start and waking (finishManifold)
//   collideHeightField    every awake dynamic body against the height field
//
// Contacts are speculative: kept up to WorldSettings::speculativeDistance_m
// plus the distance the bodies can close this step, so the solver stops
// fast bodies before they meet (contact_solver.cpp).
//
// Warm starting: a new point takes the impulses of last step's point with
// the same feature id, or of one within kWarmStartMatchDistance_m when the
// ids changed (features flicker when faces are exactly aligned). Manifolds
// of a mesh pair and of the height field (several per pair, one per normal)
// take last step's manifold with the closest normal.
//
// The collision filter (World::disableCollision) lives here too: the sorted
// list of body pairs that never collide.
#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/compound_shape.h"
#include "physics/internal/ccd.h"
#include "physics/internal/convex_collision.h"
#include "physics/internal/mesh_collision.h"
#include "physics/internal/narrow_phase.h"
#include "physics/internal/step_scratch.h"
#include "physics/world.h"

namespace tumble::physics {
namespace {

/// How far (m) a contact point may move between steps and still inherit the
/// old point's impulses when its feature id changed.
constexpr Real kWarmStartMatchDistance_m = Real(0.01);

Aabb shapeBounds(const Body& b) {
  Aabb box;
  b.shape.bounds(b.position_m, b.orientation, &box.lo, &box.hi);
  return box;
}

/// Radius a shape rolls on (0 for shapes that do not roll).
Real rollingRadius(const Shape& s) {
  return s.type == ShapeType::Sphere || s.type == ShapeType::Capsule ? s.radius_m : 0;
}

/// The same for the touching side of shape s at orientation q, normal n: a
/// cylinder rolls on its side (normal across its axis), not on a cap.
Real rollingRadius(const Shape& s, const Quat& q, const Vec3& n) {
  if (s.type != ShapeType::Cylinder) return rollingRadius(s);
  return std::abs((q * Vec3::UnitY()).dot(n)) < kFeatureSin ? s.radius_m : 0;
}

/// Whether a body of shape s at orientation q touches with one point of a
/// cylinder's rim (Manifold::rimA): tilted off both its side and its cap
/// by more than the contact generator's feature angle (convex_collision.cpp,
/// featureOf), where the contact is the cylinder's support point. A
/// compound's cylinder child is not followed (its rim turns about an axis
/// off the body's centre).
bool touchesOnRim(const Shape& s, const Quat& q, const Vec3& n, int count) {
  if (s.type != ShapeType::Cylinder || count != 1) return false;
  const Real an = std::abs((q * Vec3::UnitY()).dot(n));
  return an >= kFeatureSin && an < std::sqrt(1 - kFeatureSin * kFeatureSin);
}

/// Last step's manifold of pair (a, b) between the same children, or null.
const Manifold* findOld(const StepScratch& st, std::uint32_t a, std::uint32_t b, std::uint16_t childA,
                        std::uint16_t childB) {
  for (std::uint32_t k = st.oldStart[b]; k < st.oldStart[b + 1]; ++k) {
    const Manifold& o = st.old[st.oldIndex[k]];
    if (o.a == a && o.b == b && o.childA == childA && o.childB == childB) return &o;
  }
  return nullptr;
}

/// Last step's manifold in `bucket` between a and b (b may be
/// kHeightFieldBody) and m's children whose normal is closest to m's (within
/// acos 0.95) and that no manifold of this pair took yet (st.usedOld), or null.
const Manifold* findOldByNormal(StepScratch& st, std::uint32_t bucket, std::uint32_t b, const Manifold& m,
                                bool matchChildB) {
  const Manifold* best = nullptr;
  std::uint32_t bestIndex = 0;
  Real bestDot = Real(0.95);
  for (std::uint32_t k = st.oldStart[bucket]; k < st.oldStart[bucket + 1]; ++k) {
    const std::uint32_t oi = st.oldIndex[k];
    const Manifold& o = st.old[oi];
    if (o.b != b || o.childA != m.childA || (matchChildB && o.childB != m.childB) ||
        std::find(st.usedOld.begin(), st.usedOld.end(), oi) != st.usedOld.end())
      continue;
    if (const Real d = o.normal.dot(m.normal); d > bestDot) bestDot = d, best = &o, bestIndex = oi;
  }
  if (best) st.usedOld.push_back(bestIndex);
  return best;
}

}  // namespace

void World::inheritImpulses(const Manifold& pm, Manifold& m) const {
  m.touchedBefore = pm.count > 0;
  bool used[kMaxManifoldPoints] = {};
  for (int i = 0; i < m.count; ++i) {
    int match = -1;
    for (int j = 0; j < pm.count; ++j)
      if (!used[j] && pm.points[j].id == m.points[i].id) match = j;
    if (match < 0) {
      Real best = kWarmStartMatchDistance_m * kWarmStartMatchDistance_m;
      for (int j = 0; j < pm.count; ++j) {
        Real d2 = (pm.points[j].point_m - m.points[i].point_m).squaredNorm();
        if (!used[j] && d2 < best) best = d2, match = j;
      }
    }
    if (match < 0) continue;
    used[match] = true;
    m.points[i].normalImpulse = pm.points[match].normalImpulse;
    m.points[i].tangentImpulse[0] = pm.points[match].tangentImpulse[0];
    m.points[i].tangentImpulse[1] = pm.points[match].tangentImpulse[1];
  }
}

void World::collide(Real dt) {
  bucketOldManifolds();
  buildSweptBoxes(dt);
  findCandidatePairs();
  m_events.clear();
  int points = 0;
  for (auto [ia, ib] : m_scratch->pairs) collideBodyPair(ia, ib, dt, points);
  if (m_heightField) collideHeightField(dt, points);
  m_lastContactPoints = points;
  m_error.contactsMax = std::max(m_error.contactsMax, points);
}

void World::bucketOldManifolds() {
  // Keep last step's manifolds, bucketed (counting sort: linear, no
  // hashing, deterministic), for warm starting. A pair's bucket is its
  // higher body b: bucketed by a, the ground (body 0 under a pile) had one
  // manifold per body on it, and every lookup scanned them all (O(n^2):
  // 3% of ragdolls_100's step). Height-field manifolds go by their body a.
  StepScratch& st = *m_scratch;
  const std::size_t n = m_bodies.size();
  std::vector<Manifold>& old = st.old;
  old.swap(m_manifolds);
  m_manifolds.clear();
  auto bucketOf = [](const Manifold& m) { return m.b == kHeightFieldBody ? m.a : m.b; };
  st.oldStart.assign(n + 1, 0);
  for (const Manifold& m : old) ++st.oldStart[bucketOf(m) + 1];
  for (std::size_t i = 0; i < n; ++i) st.oldStart[i + 1] += st.oldStart[i];
  st.cursor.assign(st.oldStart.begin(), st.oldStart.end() - 1);
  st.oldIndex.resize(old.size());
  for (std::uint32_t i = 0; i < old.size(); ++i) st.oldIndex[st.cursor[bucketOf(old[i])]++] = i;
}

void World::buildSweptBoxes(Real dt) {
  // Boxes grown by the distance each body can travel this step
  // (speculative margin), so fast bodies find their contacts in time.
  StepScratch& st = *m_scratch;
  const std::size_t n = m_bodies.size();
  st.boxes.resize(n);
  st.active.assign(n, 0);
  st.planes.clear();
  st.statics.clear();
  const Real spec = m_settings.speculativeDistance_m;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Body& b = m_bodies[i];
    if (!b.alive) continue;
    if (b.shape.type == ShapeType::Plane) {
      st.planes.push_back(i);
      continue;
    }
    Aabb box = shapeBounds(b);
    Vec3 travel = b.moves() ? Vec3(b.linearVelocity_mps * dt) : Vec3::Zero();
    Real spin = b.moves() ? b.angularVelocity_radps.norm() * dt * b.shape.boundingRadius() : 0;
    Vec3 grow = Vec3::Constant(spec + std::min(spin, b.shape.boundingRadius()));
    box.lo += travel.cwiseMin(Vec3::Zero()) - grow;
    box.hi += travel.cwiseMax(Vec3::Zero()) + grow;
    st.boxes[i] = box;
    st.active[i] = 1;
    if (b.type == BodyType::Static) st.statics.push_back(i);
  }
}

void World::findCandidatePairs() {
  StepScratch& st = *m_scratch;
  const std::size_t n = m_bodies.size();
  // The collision filter by body: m_noCollide is sorted by its lower body,
  // so each body's filtered partners are one contiguous run; a pair test
  // scans the run of its lower body (a rag-doll part has 1-3) instead of a
  // binary search over every filtered pair (1000 in ragdolls_100: 1.3% of
  // the step). Same answers as pairFiltered.
  std::vector<std::uint32_t>& filterStart = st.filterStart;
  filterStart.assign(n + 1, 0);
  for (const BodyPair& p : m_noCollide) ++filterStart[p.a + 1];
  for (std::size_t i = 0; i < n; ++i) filterStart[i + 1] += filterStart[i];
  auto filtered = [&](std::uint32_t a, std::uint32_t b) {
    const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
    for (std::uint32_t k = filterStart[lo]; k < filterStart[lo + 1]; ++k) {
      const BodyPair& p = m_noCollide[k];
      if (p.b == hi) return m_bodies[lo].generation == p.genA && m_bodies[hi].generation == p.genB;
    }
    return false;
  };
  auto canCollide = [&](std::uint32_t a, std::uint32_t b) {
    const Body& A = m_bodies[a];
    const Body& B = m_bodies[b];
    if (!(A.moves() || B.moves()) || filtered(a, b)) return 0;
    return A.isDynamic() && B.isDynamic() ? 2 : 1;
  };
  // The cost cap (WorldSettings::maxContactPairsPerBody).
  PairBudget budget;
  if (m_settings.maxContactPairsPerBody > 0)
    budget.fixedLeft = budget.dynamicLeft = std::size_t(m_settings.maxContactPairsPerBody) * std::size_t(m_bodyCount);
  m_broad->findPairs(st.boxes, st.active, canCollide, budget, st.pairs);
  for (std::uint32_t p : st.planes)
    for (std::uint32_t i = 0; i < n; ++i)
      if (st.active[i] && m_bodies[i].moves() && !filtered(p, i) && budget.take(1))
        st.pairs.emplace_back(std::min(p, i), std::max(p, i));
  m_error.contactPairsSkipped += budget.skipped;
  m_lastContactPairsSkipped = budget.skipped;
}

void World::collideBodyPair(std::uint32_t ia, std::uint32_t ib, Real dt, int& points) {
  StepScratch& st = *m_scratch;
  const Body& a = m_bodies[ia];
  const Body& b = m_bodies[ib];
  const Real spec = m_settings.speculativeDistance_m;
  // Margin: the closing speed along any direction this step, bounded.
  Vec3 dv = b.linearVelocity_mps - a.linearVelocity_mps;
  Real margin = spec + dv.norm() * dt;
  // Two spheres closing fast: contact along the normal they will have when
  // they touch (time of impact), none if they pass each other this step.
  // Compounds give one manifold per touching child pair.
  const bool swept = a.shape.type == ShapeType::Sphere && b.shape.type == ShapeType::Sphere && margin > 2 * spec;
  std::vector<Manifold>& found = st.pairManifolds;
  found.clear();
  // A fast sphere against a static box, hull or cylinder: the contact it
  // will have at its time of impact, none if its path misses
  // (sweptSphereContact).
  const bool sphereA = a.shape.type == ShapeType::Sphere, sphereB = b.shape.type == ShapeType::Sphere;
  const Body& other = sphereA ? b : a;
  const bool sweptConvex = margin > 2 * spec && sphereA != sphereB &&
                           (other.shape.type == ShapeType::Box || other.shape.type == ShapeType::Hull ||
                            other.shape.type == ShapeType::Cylinder) &&
                           !other.isDynamic() && other.angularVelocity_radps.squaredNorm() == 0;
  const bool meshPair = a.shape.type == ShapeType::Mesh || b.shape.type == ShapeType::Mesh;
  if (swept) {
    Manifold m;
    if (collideSpheresSwept(a, b, dv * dt, spec, m) > 0) found.push_back(m);
  } else if (sweptConvex) {
    Manifold m;
    if (sweptSphereContact(sphereA ? a : b, other, (sphereA ? Vec3(-dv) : dv) * dt, spec, sphereA, m))
      found.push_back(m);
  } else if (meshPair) {
    collideMeshPair(a, b, margin, found, &m_meshStats, m_settings.meshTree);
  } else {
    collidePair(a, b, margin, found);
  }
  st.usedOld.clear();
  for (Manifold& m : found) {
    m.a = ia;
    m.b = ib;
    // Warm start from matching feature ids (inheritImpulses). A mesh pair
    // has several manifolds per child pair, one per normal: each takes last
    // step's with the closest normal.
    if (const Manifold* prev = meshPair ? findOldByNormal(st, ia, ib, m, true) : findOld(st, ia, ib, m.childA, m.childB))
      inheritImpulses(*prev, m);
    finishPairManifold(m, dt);
    points += m.count;
    m_manifolds.push_back(m);
  }
}

void World::finishPairManifold(Manifold& m, Real dt) {
  const Body& a = m_bodies[m.a];
  const Body& b = m_bodies[m.b];
  // Compounds: the touching child's shape decides. A round child off the
  // centre of mass is still treated as round: the contact solver turns its
  // rolling centre with the body in each substep (RoundOffsetRows).
  const Shape& shapeA = childShape(a.shape, m.childA);
  const Shape& shapeB = childShape(b.shape, m.childB);
  m.friction = std::sqrt(a.friction * b.friction);
  m.restitution = std::max(a.restitution, b.restitution);
  const Quat qA = a.shape.type == ShapeType::Compound ? a.orientation * a.shape.compound->children[m.childA].orientation
                                                      : a.orientation;
  const Quat qB = b.shape.type == ShapeType::Compound ? b.orientation * b.shape.compound->children[m.childB].orientation
                                                      : b.orientation;
  const Real rollA = rollingRadius(shapeA, qA, m.normal), rollB = rollingRadius(shapeB, qB, m.normal);
  m.roundA = rollA > 0;
  m.roundB = rollB > 0;
  m.rimA = touchesOnRim(a.shape, a.orientation, m.normal, m.count);
  m.rimB = touchesOnRim(b.shape, b.orientation, m.normal, m.count);
  m.rollingArm_m = std::max(a.rollingResistance, b.rollingResistance) * std::max(rollA, rollB);
  // A moving body touching a sleeping one wakes it (and its island), and so
  // does one that will close the gap during this step: the speculative
  // contact acts before the bodies touch, and a sleeper still counts as
  // static in the solver, so waking only on overlap would stop the moving
  // body dead against it.
  Real minSeparation = std::numeric_limits<Real>::max();
  for (int i = 0; i < m.count; ++i) {
    minSeparation = std::min(minSeparation, m.points[i].separation_m);
    m_error.penetrationMax_m = std::max(m_error.penetrationMax_m, -m.points[i].separation_m);
  }
  // The manifold exists only within the speculative margin, so any
  // approach at all means the contact may act this step.
  const Real closing_m = -m.normal.dot(b.linearVelocity_mps - a.linearVelocity_mps) * dt;
  const bool touching = minSeparation < m_settings.linearSlop_m || closing_m > 0;
  if (touching) {
    if (a.isDynamic() && !a.awake && b.moves()) wakeIsland(m.a);
    if (b.isDynamic() && !b.awake && a.moves()) wakeIsland(m.b);
  }
}

void World::collideHeightField(Real dt, int& points) {
  // Every awake dynamic body against the height field (see
  // height_field_collision.cpp). Side b of these manifolds is
  // kHeightFieldBody; a body has up to kMaxHeightFieldManifolds of them, one
  // per distinct normal, warm started from last step's manifold of the same
  // body with the closest normal.
  StepScratch& st = *m_scratch;
  Vec3 fieldLo, fieldHi;
  m_heightField->bounds(&fieldLo, &fieldHi);
  const Real spec = m_settings.speculativeDistance_m;
  std::vector<Manifold>& found = st.pairManifolds;
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    const Body& b = m_bodies[i];
    if (!b.alive || !b.isDynamic() || !b.awake || !st.active[i]) continue;
    const Aabb& box = st.boxes[i];
    if ((box.lo.array() > fieldHi.array()).any() || (box.hi.array() < fieldLo.array()).any()) continue;
    const Real margin = spec + b.linearVelocity_mps.norm() * dt;
    found.clear();
    auto collideOne = [&](const Body& part, std::uint16_t child) {
      Manifold m[kMaxHeightFieldManifolds];
      const int k = physics::collideHeightField(part, *m_heightField, box.lo, box.hi, margin, st.heightField, m);
      for (int f = 0; f < k; ++f) {
        m[f].childA = child;
        found.push_back(m[f]);
      }
    };
    if (b.shape.type == ShapeType::Compound) {
      // Child by child, each as a body of its own at its world pose.
      Body part = b;
      const auto& kids = b.shape.compound->children;
      for (std::size_t c = 0; c < kids.size(); ++c) {
        part.shape = kids[c].shape;
        part.position_m = b.position_m + b.orientation * kids[c].position_m;
        part.orientation = b.orientation * kids[c].orientation;
        collideOne(part, std::uint16_t(c));
      }
    } else {
      collideOne(b, 0);
    }
    st.usedOld.clear();
    for (Manifold& m : found) {
      m.a = i;
      m.b = kHeightFieldBody;
      const Vec3& p = m.points[0].point_m;
      const Shape& shape = childShape(b.shape, m.childA);
      m.friction = std::sqrt(b.friction * std::max<Real>(m_heightField->frictionAt(p.x(), p.z()), 0));
      m.restitution = b.restitution;
      const Quat q =
          b.shape.type == ShapeType::Compound ? b.orientation * b.shape.compound->children[m.childA].orientation
                                              : b.orientation;
      const Real roll = rollingRadius(shape, q, m.normal);
      m.roundA = roll > 0;
      m.roundB = false;
      m.rimA = touchesOnRim(b.shape, b.orientation, m.normal, m.count);
      m.rimB = false;
      m.rollingArm_m = b.rollingResistance * roll;
      // Warm start from the old manifold of this body (and child) with the closest normal.
      if (const Manifold* prev = findOldByNormal(st, i, kHeightFieldBody, m, false)) inheritImpulses(*prev, m);
      for (int j = 0; j < m.count; ++j)
        m_error.penetrationMax_m = std::max(m_error.penetrationMax_m, -m.points[j].separation_m);
      points += m.count;
      m_manifolds.push_back(m);
    }
  }
}

// ---- collision filter -------------------------------------------------------------

void World::disableCollision(BodyId a, BodyId b) {
  TUMBLE_ASSERT(isValid(a) && isValid(b), "disableCollision: stale or null BodyId; check World::isValid first");
  if (a.index == b.index) return;
  const BodyPair p = makePair(a, b);
  auto it = std::lower_bound(m_noCollide.begin(), m_noCollide.end(), p);
  if (it != m_noCollide.end() && *it == p) return;
  m_noCollide.insert(it, p);
  // Drop the pair's manifold now, so its old impulses do not act once more.
  m_manifolds.erase(std::remove_if(m_manifolds.begin(), m_manifolds.end(),
                                   [&](const Manifold& m) {
                                     return std::min(m.a, m.b) == p.a && std::max(m.a, m.b) == p.b;
                                   }),
                    m_manifolds.end());
}

void World::enableCollision(BodyId a, BodyId b) {
  const BodyPair p = makePair(a, b);
  auto it = std::lower_bound(m_noCollide.begin(), m_noCollide.end(), p);
  if (it != m_noCollide.end() && *it == p) m_noCollide.erase(it);
}

bool World::collisionDisabled(BodyId a, BodyId b) const {
  if (!isValid(a) || !isValid(b)) return false;
  return pairFiltered(a.index, b.index);
}

bool World::pairFiltered(std::uint32_t a, std::uint32_t b) const {
  if (m_noCollide.empty()) return false;
  const BodyPair p{std::min(a, b), std::max(a, b), 0, 0};
  auto it = std::lower_bound(m_noCollide.begin(), m_noCollide.end(), p);
  // Generations are checked too, though destroyBody drops the pairs of a
  // body: a recycled index must never inherit a filter.
  return it != m_noCollide.end() && *it == p && m_bodies[p.a].generation == it->genA &&
         m_bodies[p.b].generation == it->genB;
}

}  // namespace tumble::physics
