// World stepping. The order inside step() is the one documented in world.h.
//
// Integration (semi-implicit Euler, per substep h):
//   v += h (g + F/m);  w += h I^-1 tau;  then the gyroscopic term;
//   contacts change v, w;  x += h v;  q += h/2 (0, w) q;  q normalised.
// The gyroscopic term w x (I w) is integrated in the body frame with the
// implicit midpoint rule: solve
//   f(w2) = I (w2 - w1) + h wm x (I wm) = 0,   wm = (w1 + w2) / 2,
// by Newton's method with J = I + h/2 (skew(wm) I - skew(I wm)).
// Implicit midpoint preserves quadratic invariants exactly, and both the
// kinetic energy w.Iw/2 and |L|^2 = |Iw|^2 are quadratic, so a free body
// keeps both to the Newton tolerance while the Dzhanibekov flip still
// happens. Rejected: explicit (gains energy; a spinning T-handle blows up)
// and Catto's one-step implicit Euler (stable but loses 11% of the energy in
// 20 s of a flipping box at 60 Hz, measured by the RigidBody tests).
#include "physics/world.h"

#include <algorithm>
#include <numeric>

#include "core/hash.h"
#include "physics/compound_shape.h"
#include "physics/constraint_solver.h"
#include "physics/internal/broad_phase.h"
#include "physics/internal/contact_solver.h"
#include "physics/internal/height_field_collision.h"
#include "physics/internal/hull_collision.h"
#include "physics/internal/mesh_collision.h"
#include "physics/internal/narrow_phase.h"

namespace tumble::physics {

/// How far (m) a contact point may move between steps and still inherit the
/// old point's impulses when its feature id changed.
constexpr Real kWarmStartMatchDistance_m = Real(0.01);

/// Arrays reused every step (so stepping does not allocate once warm).
struct StepScratch {
  ContactSolver contacts;
  std::vector<SolverVelocity> vel, pseudo;  ///< real and split-impulse velocities, per body slot
  std::vector<SolverPose> pose;             ///< displacement since the step began, per body slot
  std::vector<Aabb> boxes;
  std::vector<std::uint8_t> active;
  std::vector<std::uint32_t> planes, statics;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  // Last step's manifolds bucketed for warm starting: a pair's manifolds
  // (a < b) by b, a height-field manifold by its body a; the manifolds of
  // bucket k are old[oldIndex[oldStart[k] .. oldStart[k + 1])].
  std::vector<Manifold> old;
  std::vector<std::uint32_t> oldStart, oldIndex, cursor;
  HeightFieldScratch heightField;
  std::vector<Manifold> pairManifolds;  ///< manifolds of one body pair (compounds have several)
  std::vector<std::uint32_t> usedOld;   ///< old height-field manifolds already inherited from
  std::vector<std::uint32_t> filterStart;  ///< per body a: its pairs in m_noCollide start here (sorted by a)
  std::vector<Vec3> linear;  ///< per body slot: linear velocities for BodyIntegration::advance
  bool integrationEngaged = false;  ///< this substep's translation came from integrate.cpp
};

Status validateBodyDef(const BodyDef& d) {
  if (auto s = validateShape(d.shape); !s) return s;
  auto finite3 = [](const Vec3& v) { return v.allFinite(); };
  if (!finite3(d.position_m)) return makeError("body field 'position' must be finite (metres)");
  if (!d.orientation.coeffs().allFinite() || d.orientation.norm() < Real(1e-6))
    return makeError("body field 'orientation' must be a finite, non-zero quaternion");
  if (!finite3(d.linearVelocity_mps)) return makeError("body field 'velocity' must be finite (m/s)");
  if (!finite3(d.angularVelocity_radps)) return makeError("body field 'angular_velocity' must be finite (rad/s)");
  if (!std::isfinite(d.mass_kg) || d.mass_kg < 0)
    return makeError("body field 'mass' must be a finite number >= 0 (kg; 0 = from density), got " +
                     std::to_string(d.mass_kg));
  if (!std::isfinite(d.density_kgpm3) || d.density_kgpm3 <= 0)
    return makeError("body field 'density' must be a finite number > 0 (kg/m^3)");
  if (!std::isfinite(d.friction) || d.friction < 0)
    return makeError("body field 'friction' must be a finite number >= 0, got " + std::to_string(d.friction));
  if (!std::isfinite(d.rollingResistance) || d.rollingResistance < 0)
    return makeError("body field 'rolling_resistance' must be a finite number >= 0");
  if (!std::isfinite(d.restitution) || d.restitution < 0 || d.restitution > 1)
    return makeError("body field 'restitution' must be between 0 and 1, got " + std::to_string(d.restitution));
  if (!std::isfinite(d.linearDamping_per_s) || d.linearDamping_per_s < 0 || !std::isfinite(d.angularDamping_per_s) ||
      d.angularDamping_per_s < 0)
    return makeError("body fields 'linear_damping' and 'angular_damping' must be finite numbers >= 0 (1/s)");
  if (d.shape.type == ShapeType::Plane && d.type != BodyType::Static)
    return makeError("a plane must be a static body (type = \"static\")");
  if (d.shape.type == ShapeType::Mesh && d.type != BodyType::Static)
    return makeError("a triangle mesh shape must be a static body (type = \"static\"): it has no volume, so no mass; "
                     "give moving bodies a hull or compound shape");
  return Ok{};
}

World::World(const WorldSettings& settings)
    : m_settings(settings),
      m_broad(std::make_unique<BroadPhase>()),
      m_integration(std::make_unique<BodyIntegration>()),
      m_scratch(std::make_unique<StepScratch>()) {}

Result<SpringId> World::addSpring(SpringDef def) {
  if (auto s = validateSpringDef(def); !s) return makeError(s.error());
  if (!isValid(def.a)) return makeError("spring field 'a' is a removed body");
  if (!def.b.isNull() && !isValid(def.b)) return makeError("spring field 'b' is a removed body");
  const Vec3 other = def.b.isNull() ? def.anchor_m : body(def.b).position_m;
  if (def.restLength_m < 0) def.restLength_m = (other - body(def.a).position_m).norm();
  wakeIsland(def.a.index);
  if (!def.b.isNull()) wakeIsland(def.b.index);
  return m_integration->addSpring(def);
}

bool World::removeSpring(SpringId id) { return m_integration->removeSpring(id); }
World::~World() = default;

void World::setHeightField(const HeightField* field) {
  m_heightField = field;
  // Bodies resting on the old surface must notice the new one.
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i)
    if (m_bodies[i].alive && m_bodies[i].isDynamic()) wakeIsland(i);
  m_manifolds.erase(std::remove_if(m_manifolds.begin(), m_manifolds.end(),
                                   [](const Manifold& m) { return m.b == kHeightFieldBody; }),
                    m_manifolds.end());
}

BodyId World::idOf(std::uint32_t index) const { return BodyId{index, m_bodies[index].generation}; }

bool World::isValid(BodyId id) const {
  return !id.isNull() && id.index < m_bodies.size() && m_bodies[id.index].alive &&
         m_bodies[id.index].generation == id.generation;
}

const Body& World::body(BodyId id) const {
  TUMBLE_ASSERT(isValid(id), "stale or null BodyId; check World::isValid first");
  return m_bodies[id.index];
}

Body& World::mutableBody(BodyId id) {
  TUMBLE_ASSERT(isValid(id), "stale or null BodyId; check World::isValid first");
  return m_bodies[id.index];
}

Result<BodyId> World::createBody(const BodyDef& def) {
  if (auto s = validateBodyDef(def); !s) return makeError(s.error());
  std::uint32_t index;
  if (!m_freeList.empty()) {
    index = m_freeList.back();
    m_freeList.pop_back();
  } else {
    index = std::uint32_t(m_bodies.size());
    m_bodies.emplace_back();
    m_stepStartPosition.emplace_back(Vec3::Zero());
    m_stepStartOrientation.emplace_back(Quat::Identity());
    m_sleepIsland.push_back(0);
  }
  Body& b = m_bodies[index];
  std::uint32_t generation = b.generation + 1;  // generations start at 1: the zero handle is null
  b = Body{};
  b.generation = generation;
  b.alive = true;
  b.type = def.type;
  b.shape = def.shape;
  b.position_m = def.position_m;
  b.orientation = def.orientation.normalized();
  b.friction = def.friction;
  b.restitution = def.restitution;
  b.rollingResistance = def.rollingResistance;
  b.linearDamping_per_s = def.linearDamping_per_s;
  b.angularDamping_per_s = def.angularDamping_per_s;
  b.allowSleep = def.allowSleep;
  b.userData = def.userData;
  if (def.type != BodyType::Static) {
    b.linearVelocity_mps = def.linearVelocity_mps;
    b.angularVelocity_radps = def.angularVelocity_radps;
  }
  if (def.type == BodyType::Dynamic) {
    b.mass_kg = def.mass_kg > 0 ? def.mass_kg : def.density_kgpm3 * def.shape.volume();
    b.invMass_per_kg = 1 / b.mass_kg;
    b.inertiaLocal_kgm2 = b.mass_kg * def.shape.unitInertia();
    b.invInertiaLocal = b.inertiaLocal_kgm2.cwiseInverse();
  }
  updateInertia(b);
  m_sleepIsland[index] = 0;
  ++m_bodyCount;
  return BodyId{index, generation};
}

bool World::destroyBody(BodyId id) {
  if (!isValid(id)) return false;
  // Wake whatever rested on it.
  for (const Manifold& m : m_manifolds)
    if (m.a == id.index || m.b == id.index) {
      wakeIsland(m.a);
      wakeIsland(m.b);
    }
  Body& b = m_bodies[id.index];
  b.alive = false;
  b.shape = Shape{};  // releases hull / compound data
  ++b.generation;
  m_freeList.push_back(id.index);
  --m_bodyCount;
  m_manifolds.erase(std::remove_if(m_manifolds.begin(), m_manifolds.end(),
                                   [&](const Manifold& m) { return m.a == id.index || m.b == id.index; }),
                    m_manifolds.end());
  auto involves = [&](const BodyPair& p) { return p.a == id.index || p.b == id.index; };
  m_noCollide.erase(std::remove_if(m_noCollide.begin(), m_noCollide.end(), involves), m_noCollide.end());
  m_islandLinks.erase(std::remove_if(m_islandLinks.begin(), m_islandLinks.end(), involves), m_islandLinks.end());
  return true;
}

Status World::setPrincipalInertia(BodyId id, const Vec3& I) {
  if (!isValid(id)) return makeError("setPrincipalInertia: no such body");
  Body& b = mutableBody(id);
  if (!b.isDynamic()) return makeError("setPrincipalInertia: only a dynamic body has inertia");
  if (!I.allFinite() || (I.array() <= 0).any())
    return makeError("setPrincipalInertia: moments must be finite and > 0 kg m^2");
  // A real body's moments satisfy I_a <= I_b + I_c (a little slack for rounding).
  for (int k = 0; k < 3; ++k)
    if (I[k] > Real(1.0001) * (I[(k + 1) % 3] + I[(k + 2) % 3]))
      return makeError("setPrincipalInertia: moments break the triangle inequality (no rigid body has them)");
  b.inertiaLocal_kgm2 = I;
  b.invInertiaLocal = I.cwiseInverse();
  updateInertia(b);
  return Ok{};
}

void World::updateInertia(Body& b) {
  if (!b.isDynamic()) {
    b.invInertiaWorld.setZero();
    return;
  }
  Mat3 R = b.orientation.toRotationMatrix();
  b.invInertiaWorld = R * b.invInertiaLocal.asDiagonal() * R.transpose();
}

void World::setPosition(BodyId id, const Vec3& p, bool wake) {
  Body& b = mutableBody(id);
  b.position_m = p;
  if (wake) wakeIsland(id.index);
}
void World::setOrientation(BodyId id, const Quat& q, bool wake) {
  Body& b = mutableBody(id);
  b.orientation = q.normalized();
  updateInertia(b);
  if (wake) wakeIsland(id.index);
}
void World::setLinearVelocity(BodyId id, const Vec3& v, bool wake) {
  Body& b = mutableBody(id);
  if (b.type == BodyType::Static) return;
  b.linearVelocity_mps = v;
  if (wake) wakeIsland(id.index);
}
void World::setAngularVelocity(BodyId id, const Vec3& w, bool wake) {
  Body& b = mutableBody(id);
  if (b.type == BodyType::Static) return;
  b.angularVelocity_radps = w;
  if (wake) wakeIsland(id.index);
}
void World::setMaterial(BodyId id, Real friction, Real restitution) {
  Body& b = mutableBody(id);
  b.friction = friction;
  b.restitution = restitution;
}
void World::applyForce(BodyId id, const Vec3& f, const Vec3& point, bool wake) {
  Body& b = mutableBody(id);
  if (!b.isDynamic()) return;
  b.force_N += f;
  b.torque_Nm += (point - b.position_m).cross(f);
  if (wake) wakeIsland(id.index);
}
void World::applyTorque(BodyId id, const Vec3& t, bool wake) {
  Body& b = mutableBody(id);
  if (!b.isDynamic()) return;
  b.torque_Nm += t;
  if (wake) wakeIsland(id.index);
}
void World::applyImpulse(BodyId id, const Vec3& J, const Vec3& point) {
  Body& b = mutableBody(id);
  if (!b.isDynamic()) return;
  wakeIsland(id.index);
  double before = 0.5 * b.mass_kg * b.linearVelocity_mps.squaredNorm() +
                  0.5 * b.angularVelocity_radps.dot(b.invInertiaWorld.inverse() * b.angularVelocity_radps);
  b.linearVelocity_mps += b.invMass_per_kg * J;
  b.angularVelocity_radps += b.invInertiaWorld * (point - b.position_m).cross(J);
  double after = 0.5 * b.mass_kg * b.linearVelocity_mps.squaredNorm() +
                 0.5 * b.angularVelocity_radps.dot(b.invInertiaWorld.inverse() * b.angularVelocity_radps);
  m_externalWork += after - before;
  m_externalImpulse += J.cast<double>();
}
static bool rayShape(const Body& b, const Vec3& o, const Vec3& d, Real maxT, Real& tHit, Vec3& nHit,
                     Real inflate = 0, MeshStats* meshStats = nullptr);

int World::addSubstepHook(SubstepHook hook) {
  m_substepHooks.emplace_back(m_nextHookId, std::move(hook));
  return m_nextHookId++;
}

void World::removeSubstepHook(int id) {
  std::erase_if(m_substepHooks, [id](const auto& h) { return h.first == id; });
}

Vec3 World::currentLinearVelocity(BodyId id) const {
  const Body& b = body(id);
  return m_inStep ? narrow(m_scratch->vel[id.index].linear) : b.linearVelocity_mps;
}

Vec3 World::currentAngularVelocity(BodyId id) const {
  const Body& b = body(id);
  return m_inStep ? narrow(m_scratch->vel[id.index].angular) : b.angularVelocity_radps;
}

void World::applyImpulseNow(BodyId id, const Vec3& J, const Vec3& point) {
  if (!m_inStep) {
    if (isValid(id) && body(id).awake) applyImpulse(id, J, point);
    return;
  }
  Body& b = mutableBody(id);
  if (!b.isDynamic() || !b.awake) return;
  SolverVelocity& v = m_scratch->vel[id.index];
  const Vec3 v0 = narrow(v.linear), w0 = narrow(v.angular);
  const Vec3 dv = b.invMass_per_kg * J, dw = b.invInertiaWorld * (point - b.position_m).cross(J);
  v.linear += wide(dv);
  v.angular += wide(dw);
  // Work of the impulse: J . (v0 + v1) / 2 at the point, i.e. the change of
  // kinetic energy it causes.
  const Vec3 r = point - b.position_m;
  const Vec3 vp0 = v0 + w0.cross(r), vp1 = v0 + dv + (w0 + dw).cross(r);
  m_externalWork += 0.5 * double(J.dot(vp0 + vp1));
  m_externalImpulse += J.cast<double>();
}

bool World::rayCastBody(BodyId id, const Vec3& origin, const Vec3& dir, Real maxDistance, RayHit* hit) const {
  if (!isValid(id)) return false;
  const Real len = dir.norm();
  if (!(len > 0) || !origin.allFinite() || !std::isfinite(maxDistance)) return false;
  const Vec3 d = dir / len;
  Real t;
  Vec3 n;
  if (!rayShape(m_bodies[id.index], origin, d, maxDistance, t, n, 0, &m_meshStats)) return false;
  if (hit) *hit = {id, t, origin + d * t, n};
  return true;
}

void World::wake(BodyId id) {
  if (isValid(id)) wakeIsland(id.index);
}

World::BodyPair World::makePair(BodyId x, BodyId y) {
  if (y.index < x.index) std::swap(x, y);
  return BodyPair{x.index, y.index, x.generation, y.generation};
}

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

// ---- stepping ------------------------------------------------------------------

static bool sweptSphereContact(const Body& sphere, const Body& other, const Vec3& motion, Real spec, bool sphereIsA,
                               Manifold& m);

static Aabb shapeBounds(const Body& b) {
  Aabb box;
  b.shape.bounds(b.position_m, b.orientation, &box.lo, &box.hi);
  return box;
}

/// Radius a shape rolls on (0 for shapes that do not roll).
static Real rollingRadius(const Shape& s) {
  return s.type == ShapeType::Sphere || s.type == ShapeType::Capsule ? s.radius_m : 0;
}

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
  StepScratch& st = *m_scratch;
  const std::size_t n = m_bodies.size();
  // Keep last step's manifolds, bucketed (counting sort: linear, no
  // hashing, deterministic), for warm starting. A pair's bucket is its
  // higher body b: bucketed by a, the ground (body 0 under a pile) had one
  // manifold per body on it, and every lookup scanned them all (O(n^2):
  // 3% of ragdolls_100's step). Height-field manifolds go by their body a.
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
  auto findOld = [&](std::uint32_t a, std::uint32_t b, std::uint16_t childA,
                     std::uint16_t childB) -> const Manifold* {
    for (std::uint32_t k = st.oldStart[b]; k < st.oldStart[b + 1]; ++k) {
      const Manifold& o = old[st.oldIndex[k]];
      if (o.a == a && o.b == b && o.childA == childA && o.childB == childB) return &o;
    }
    return nullptr;
  };
  auto findOldByNormal = [&](std::uint32_t a, std::uint32_t b, const Manifold& m) -> const Manifold* {
    const Manifold* best = nullptr;
    std::uint32_t bestIndex = 0;
    Real bestDot = Real(0.95);
    for (std::uint32_t k = st.oldStart[a]; k < st.oldStart[a + 1]; ++k) {
      const std::uint32_t oi = st.oldIndex[k];
      const Manifold& o = old[oi];
      if (o.b != b || o.childA != m.childA || o.childB != m.childB ||
          std::find(st.usedOld.begin(), st.usedOld.end(), oi) != st.usedOld.end())
        continue;
      if (const Real d = o.normal.dot(m.normal); d > bestDot) bestDot = d, best = &o, bestIndex = oi;
    }
    if (best) st.usedOld.push_back(bestIndex);
    return best;
  };

  // Boxes grown by the distance each body can travel this step
  // (speculative margin), so fast bodies find their contacts in time.
  std::vector<Aabb>& boxes = st.boxes;
  std::vector<std::uint8_t>& active = st.active;
  std::vector<std::uint32_t>& planes = st.planes;
  auto& pairs = st.pairs;
  boxes.resize(n);
  active.assign(n, 0);
  planes.clear();
  st.statics.clear();
  const Real spec = m_settings.speculativeDistance_m;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Body& b = m_bodies[i];
    if (!b.alive) continue;
    if (b.shape.type == ShapeType::Plane) {
      planes.push_back(i);
      continue;
    }
    Aabb box = shapeBounds(b);
    Vec3 travel = b.moves() ? Vec3(b.linearVelocity_mps * dt) : Vec3::Zero();
    Real spin = b.moves() ? b.angularVelocity_radps.norm() * dt * b.shape.boundingRadius() : 0;
    Vec3 grow = Vec3::Constant(spec + std::min(spin, b.shape.boundingRadius()));
    box.lo += travel.cwiseMin(Vec3::Zero()) - grow;
    box.hi += travel.cwiseMax(Vec3::Zero()) + grow;
    boxes[i] = box;
    active[i] = 1;
    if (b.type == BodyType::Static) st.statics.push_back(i);
  }
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
    return (A.moves() || B.moves()) && !filtered(a, b);
  };
  m_broad->findPairs(boxes, active, canCollide, pairs);
  for (std::uint32_t p : planes)
    for (std::uint32_t i = 0; i < n; ++i)
      if (active[i] && m_bodies[i].moves() && !filtered(p, i)) pairs.emplace_back(std::min(p, i), std::max(p, i));

  m_events.clear();
  int points = 0;
  for (auto [ia, ib] : pairs) {
    const Body& a = m_bodies[ia];
    const Body& b = m_bodies[ib];
    // Margin: the closing speed along any direction this step, bounded.
    Vec3 dv = b.linearVelocity_mps - a.linearVelocity_mps;
    Real margin = spec + dv.norm() * dt;
    // Two spheres closing fast: contact along the normal they will have when
    // they touch (time of impact), none if they pass each other this step.
    // Compounds give one manifold per touching child pair.
    const bool swept = a.shape.type == ShapeType::Sphere && b.shape.type == ShapeType::Sphere && margin > 2 * spec;
    std::vector<Manifold>& found = st.pairManifolds;
    found.clear();
    // A fast sphere against a static box or hull: the contact it will have
    // at its time of impact, none if its path misses (sweptSphereContact).
    const bool sphereA = a.shape.type == ShapeType::Sphere, sphereB = b.shape.type == ShapeType::Sphere;
    const Body& other = sphereA ? b : a;
    const bool sweptConvex = margin > 2 * spec && sphereA != sphereB &&
                             (other.shape.type == ShapeType::Box || other.shape.type == ShapeType::Hull) &&
                             !other.isDynamic() && other.angularVelocity_radps.squaredNorm() == 0;
    if (swept) {
      Manifold m;
      if (collideSpheresSwept(a, b, dv * dt, spec, m) > 0) found.push_back(m);
    } else if (sweptConvex) {
      Manifold m;
      if (sweptSphereContact(sphereA ? a : b, other, (sphereA ? Vec3(-dv) : dv) * dt, spec, sphereA, m))
        found.push_back(m);
    } else if (a.shape.type == ShapeType::Mesh || b.shape.type == ShapeType::Mesh) {
      collideMeshPair(a, b, margin, found, &m_meshStats, m_settings.meshTree);
    } else {
      collidePair(a, b, margin, found);
    }
    const bool meshPair = a.shape.type == ShapeType::Mesh || b.shape.type == ShapeType::Mesh;
    st.usedOld.clear();
    for (Manifold& m : found) {
      m.a = ia;
      m.b = ib;
      // Compounds: the touching child's shape decides. A round child off the
      // centre of mass is still treated as round (anchor not turned in the
      // substeps); its centre's own swing during one step is picked up by
      // the next step's narrow phase.
      const Shape& shapeA = childShape(a.shape, m.childA);
      const Shape& shapeB = childShape(b.shape, m.childB);
      m.friction = std::sqrt(a.friction * b.friction);
      m.restitution = std::max(a.restitution, b.restitution);
      m.roundA = rollingRadius(shapeA) > 0;
      m.roundB = rollingRadius(shapeB) > 0;
      m.rollingArm_m = std::max(a.rollingResistance, b.rollingResistance) *
                       std::max(rollingRadius(shapeA), rollingRadius(shapeB));
      // Warm start from matching feature ids; a point whose id changed but
      // which sits where an old point was (features flicker when faces are
      // exactly aligned) takes that point's impulses.
      // A mesh pair has several manifolds per child pair, one per normal:
      // each takes last step's with the closest normal.
      if (const Manifold* prev = meshPair ? findOldByNormal(ia, ib, m) : findOld(ia, ib, m.childA, m.childB))
        inheritImpulses(*prev, m);
      // A moving body touching a sleeping one wakes it (and its island), and
      // so does one that will close the gap during this step: the speculative
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
        if (a.isDynamic() && !a.awake && b.moves()) wakeIsland(ia);
        if (b.isDynamic() && !b.awake && a.moves()) wakeIsland(ib);
      }
      points += m.count;
      m_manifolds.push_back(m);
    }
  }
  if (m_heightField) collideHeightField(dt, points);
  m_lastContactPoints = points;
  m_error.contactsMax = std::max(m_error.contactsMax, points);
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
  std::vector<std::uint32_t>& usedOld = st.usedOld;
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
    usedOld.clear();
    for (Manifold& m : found) {
      m.a = i;
      m.b = kHeightFieldBody;
      const Vec3& p = m.points[0].point_m;
      const Shape& shape = childShape(b.shape, m.childA);
      m.friction = std::sqrt(b.friction * std::max<Real>(m_heightField->frictionAt(p.x(), p.z()), 0));
      m.restitution = b.restitution;
      m.roundA = rollingRadius(shape) > 0;
      m.roundB = false;
      m.rollingArm_m = b.rollingResistance * rollingRadius(shape);
      // Warm start from the old manifold of this body (and child) with the closest normal.
      std::int64_t best = -1;
      Real bestDot = Real(0.95);
      for (std::uint32_t q = st.oldStart[i]; q < st.oldStart[i + 1]; ++q) {
        const std::uint32_t oi = st.oldIndex[q];
        if (st.old[oi].b != kHeightFieldBody || st.old[oi].childA != m.childA ||
            std::find(usedOld.begin(), usedOld.end(), oi) != usedOld.end())
          continue;
        const Real d = st.old[oi].normal.dot(m.normal);
        if (d > bestDot) bestDot = d, best = oi;
      }
      if (best >= 0) {
        usedOld.push_back(std::uint32_t(best));
        inheritImpulses(st.old[std::size_t(best)], m);
      }
      for (int j = 0; j < m.count; ++j)
        m_error.penetrationMax_m = std::max(m_error.penetrationMax_m, -m.points[j].separation_m);
      points += m.count;
      m_manifolds.push_back(m);
    }
  }
}

/// One implicit-midpoint step of Euler's torque-free equations in the body
/// frame (see the top of this file). Returns the new body-frame w.
static Vec3 gyroscopicMidpoint(const Vec3& I, const Vec3& w1, Real h) {
  const Vec3 Iw1 = I.cwiseProduct(w1);
  if (w1.cross(Iw1).squaredNorm() == 0) return w1;  // symmetric body or axis spin: nothing to do
  Vec3 w2 = w1;
  for (int it = 0; it < 4; ++it) {
    Vec3 wm = (w1 + w2) / 2;
    Vec3 Iwm = I.cwiseProduct(wm);
    Vec3 f = I.cwiseProduct(w2 - w1) + h * wm.cross(Iwm);
    if (f.squaredNorm() <= Real(1e-14) * Iw1.squaredNorm()) break;
    Mat3 J = Mat3(I.asDiagonal()) + (h / 2) * (skew(wm) * I.asDiagonal() - skew(Iwm));
    w2 -= J.inverse() * f;  // closed-form 3x3 (J is near I: well conditioned); LU cost 2.4% of ragdolls_100
  }
  return w2;
}

void World::integrateVelocities(Real h) {
  const Vec3 g = m_settings.gravity_mps2;
  std::vector<SolverVelocity>& vel = m_scratch->vel;
  double gravityMass = 0;
  // Another integrator or springs: translation comes from integrate.cpp
  // (free motion first, contacts then change the velocity; see there).
  const bool engaged = m_scratch->integrationEngaged = m_integration->engaged(m_settings.integrator);
  if (engaged) {
    std::vector<Vec3>& linear = m_scratch->linear;
    linear.resize(m_bodies.size());
    for (std::uint32_t i = 0; i < m_bodies.size(); ++i) linear[i] = narrow(vel[i].linear);
    m_externalImpulse += m_integration->advance(m_settings.integrator, *this, m_bodies, g, h, linear);
    for (std::uint32_t i = 0; i < m_bodies.size(); ++i) vel[i].linear = wide(linear[i]);
  }
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    Body& b = m_bodies[i];
    if (!b.alive || !b.isDynamic() || !b.awake) continue;
    gravityMass += b.mass_kg;
    Vec3 v = narrow(vel[i].linear), w = narrow(vel[i].angular);
    if (!engaged) v += h * (g + b.invMass_per_kg * b.force_N);
    if (b.force_N != Vec3::Zero() || b.torque_Nm != Vec3::Zero()) {
      w += h * (b.invInertiaWorld * b.torque_Nm);
      m_externalImpulse += double(h) * b.force_N.cast<double>();
      m_externalWork += double(h) * (b.force_N.dot(v) + b.torque_Nm.dot(w));
    }
    // Implicit gyroscopic step in the body frame (see top of file); nothing
    // to do for a body whose principal moments are equal (spheres, cubes).
    const Vec3& I = b.inertiaLocal_kgm2;
    if (m_settings.gyroscopic && !(I.x() == I.y() && I.y() == I.z()))
      w = b.orientation * gyroscopicMidpoint(I, b.orientation.conjugate() * w, h);
    if (b.linearDamping_per_s > 0) {
      Vec3 before = v;
      v *= 1 / (1 + h * b.linearDamping_per_s);
      m_externalImpulse += b.mass_kg * (v - before).cast<double>();
    }
    if (b.angularDamping_per_s > 0) w *= 1 / (1 + h * b.angularDamping_per_s);
    vel[i].linear = wide(v);
    vel[i].angular = wide(w);
  }
  m_externalImpulse += double(h) * gravityMass * g.cast<double>();
}

void World::integratePositions(Real h) {
  StepScratch& st = *m_scratch;
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    Body& b = m_bodies[i];
    if (!b.alive || !b.moves()) continue;
    // Split-impulse pseudo-velocities move the body but are then dropped.
    SolverVelocity& pv = st.pseudo[i];
    const SolverVelocity& v = st.vel[i];
    if (st.integrationEngaged)
      b.position_m += m_integration->displacement(i, narrow(v.linear), h) + h * narrow(pv.linear);
    else
      b.position_m += h * narrow(v.linear + pv.linear);
    const Vec3 w = narrow(v.angular + pv.angular);
    pv = SolverVelocity{};
    Quat dq(0, w.x(), w.y(), w.z());
    dq = dq * b.orientation;
    b.orientation.coeffs() += (h / 2) * dq.coeffs();
    b.orientation.normalize();
    const bool finite =
        b.position_m.allFinite() && b.orientation.coeffs().allFinite() && v.linear.allFinite() && v.angular.allFinite();
    if (!finite) {
      // A fault must not reach the neighbours in the next substep.
      freezeBody(i);
      st.vel[i] = SolverVelocity{};
    }
    st.pose[i].dp = b.position_m - m_stepStartPosition[i];
    st.pose[i].dq = b.orientation * m_stepStartOrientation[i].conjugate();
  }
}

void World::freezeBody(std::uint32_t i) {
  // Put back where the step began and held still, so the fault never
  // spreads through contacts.
  Body& b = m_bodies[i];
  b.frozen = true;
  b.position_m = m_stepStartPosition[i].allFinite() ? m_stepStartPosition[i] : Vec3::Zero();
  b.orientation = m_stepStartOrientation[i].coeffs().allFinite() ? m_stepStartOrientation[i] : Quat::Identity();
  b.linearVelocity_mps.setZero();
  b.angularVelocity_radps.setZero();
  b.invInertiaWorld.setZero();
  ++m_error.nanEvents;
}

void World::freezeNonFinite() {
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    Body& b = m_bodies[i];
    if (!b.alive || b.frozen) continue;
    bool finite = b.position_m.allFinite() && b.orientation.coeffs().allFinite() &&
                  b.linearVelocity_mps.allFinite() && b.angularVelocity_radps.allFinite();
    if (!finite) freezeBody(i);
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

void World::step(Real dt) {
  if (!(dt > 0) || !std::isfinite(dt)) return;
  if (!m_trackingStarted) resetErrorStats();
  freezeNonFinite();  // catches non-finite values set from outside (scripts)
  const std::size_t n = m_bodies.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    m_stepStartPosition[i] = m_bodies[i].position_m;
    m_stepStartOrientation[i] = m_bodies[i].orientation;
  }
  collide(dt);

  const int substeps = std::max(1, m_settings.substeps);
  SolverSettings ss;
  ss.h = dt / Real(substeps);
  ss.contactHertz = m_settings.contactHertz;
  ss.contactDampingRatio = m_settings.contactDampingRatio;
  ss.maxPushout_mps = m_settings.maxPushoutSpeed_mps;
  ss.restitutionThreshold_mps = m_settings.restitutionThreshold_mps;
  ss.linearSlop_m = m_settings.linearSlop_m;
  ss.softContacts = m_settings.softContacts;
  ss.baumgarte = m_settings.baumgarte;
  ss.restitutionIterations = m_settings.restitutionIterations;

  // Gather: the substeps work on compact velocity arrays, not on Body.
  StepScratch& st = *m_scratch;
  // One slot more than there are bodies: the unmoving side of height-field
  // contacts (ContactSolver::prepare maps kHeightFieldBody to it).
  st.vel.resize(n + 1);
  for (std::uint32_t i = 0; i < n; ++i) {
    const Body& b = m_bodies[i];
    st.vel[i] = b.alive ? SolverVelocity{wide(b.linearVelocity_mps), wide(b.angularVelocity_radps)} : SolverVelocity{};
  }
  st.vel[n] = SolverVelocity{};
  st.pseudo.assign(n + 1, SolverVelocity{});
  st.pose.assign(n + 1, SolverPose{});
  ContactSolver& contacts = st.contacts;
  const Real tol2 = m_settings.solverTolerance * m_settings.solverTolerance;
  contacts.prepare(m_manifolds, m_bodies);
  m_inStep = true;
  ConstraintSolver* joints = m_constraintSolver;  // the joint hook (constraint_solver.h), usually null
  if (joints) joints->prepare(*this, dt, substeps);
  for (int s = 0; s < substeps; ++s) {
    integrateVelocities(ss.h);
    for (auto& [id, hook] : m_substepHooks) hook(*this, ss.h);
    contacts.captureApproachSpeeds(st.vel);
    contacts.warmStart(st.vel);
    if (joints) joints->warmStart(st.vel.data(), m_bodies.data());
    // Rolling and split impulses are per substep (not warm started), so
    // each substep can apply its full share again.
    contacts.resetSubstepImpulses();
    // Positions change only in integratePositions, so separations are
    // updated once per phase, not once per iteration.
    if (m_settings.velocityIterations > 0) contacts.updateSeparations(st.pose);
    for (int it = 0; it < m_settings.velocityIterations; ++it) {
      const Real jr = joints ? joints->solve(st.vel.data(), m_bodies.data(), true) : Real(0);
      const Real r = contacts.solve(st.vel, st.pseudo, ss, true);
      if (r <= tol2 * contacts.lastMagnitude() && jr <= tol2) break;  // converged: see WorldSettings::solverTolerance
    }
    if (joints) joints->beforeIntegrate(st.vel.data(), m_bodies.data());
    integratePositions(ss.h);
    if (m_settings.relaxIterations > 0) contacts.updateSeparations(st.pose);
    for (int it = 0; it < m_settings.relaxIterations; ++it) {
      const Real jr = joints ? joints->solve(st.vel.data(), m_bodies.data(), false) : Real(0);
      if (contacts.solve(st.vel, st.pseudo, ss, false) == 0 && jr == 0) break;
    }
    // Impulses from static, kinematic or sleeping bodies are external to the
    // moving set; between two moving bodies they cancel exactly.
    m_externalImpulse += contacts.externalImpulse();
  }
  contacts.applyRestitution(st.vel, ss);
  m_externalImpulse += contacts.externalRestitutionImpulse();
  m_inStep = false;
  // Scatter.
  for (std::uint32_t i = 0; i < n; ++i) {
    Body& b = m_bodies[i];
    if (!b.alive || !b.moves()) continue;
    b.linearVelocity_mps = narrow(st.vel[i].linear);
    b.angularVelocity_radps = narrow(st.vel[i].angular);
  }
  contacts.store(m_manifolds);
  if (joints) joints->finish(*this);
  if (m_settings.continuousStatic) clampToStatic();
  for (Body& b : m_bodies)
    if (b.alive && b.moves()) updateInertia(b);

  // Begin-contact events.
  for (const Manifold& m : m_manifolds) {
    Real total = 0;
    for (int i = 0; i < m.count; ++i) total += m.points[i].normalImpulse;
    if (!m.touchedBefore && total > 0) {
      ContactEvent e;
      e.a = idOf(m.a);
      e.b = m.b == kHeightFieldBody ? BodyId{} : idOf(m.b);
      e.point_m = m.points[0].point_m;
      e.normal = m.normal;
      e.impulse_Ns = total;
      m_events.push_back(e);
    }
  }
  for (Body& b : m_bodies) {
    b.force_N.setZero();
    b.torque_Nm.setZero();
  }
  freezeNonFinite();
  updateSleep(dt);
  trackErrors(dt);
}

void World::clampToStatic() {
  // Continuous collision against static geometry (see WorldSettings::
  // continuousStatic). Speculative contacts stop a body that heads for a
  // wall, but their margins use the velocities at the start of the step: a
  // fast body that another body deflects this step can be sent at a wall it
  // has no contact with and pass through it (measured: 89 of 1000 spheres
  // left highspeed_1000's box). So every body that moved more than half its
  // inner radius r is swept as a sphere of radius r (a ray against each
  // static shape grown by r) from its start to its end position. If it ends
  // more than r/2 inside a grown shape it is put back at the time of impact;
  // its velocity is kept, so the next step's speculative contact bounces it
  // with its restitution (no energy lost). The r/2 depth test keeps bodies
  // that slide along a floor and dip by millimetres from being held back.
  // Rejected: growing the speculative margins by a bound on the velocity
  // change (any body could be hit by any other: margins, pairs and solver
  // work grow for the whole scene to guard a few bodies).
  // The height field: the centre's path as a ray; a hit means the centre
  // ends below the surface, and the body goes back to where a sphere of
  // radius r touches the hit triangle's plane (t - r / cos).
  StepScratch& st = *m_scratch;
  if (st.statics.empty() && st.planes.empty() && !m_heightField) return;
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    Body& b = m_bodies[i];
    if (!b.alive || !b.isDynamic() || !b.awake) continue;
    const Real r = b.shape.innerRadius();
    if (!(r > 0)) continue;  // no sphere about the centre inside the shape (a compound whose centre is in no child)
    const Vec3 p0 = m_stepStartPosition[i];
    const Vec3 d = b.position_m - p0;
    const Real len2 = d.squaredNorm();
    if (!(len2 > Real(0.25) * r * r)) continue;
    const Real len = std::sqrt(len2);
    const Vec3 dir = d / len;
    Aabb swept;
    swept.lo = p0.cwiseMin(b.position_m) - Vec3::Constant(r);
    swept.hi = p0.cwiseMax(b.position_m) + Vec3::Constant(r);
    Real toi = len;
    auto test = [&](std::uint32_t j) {
      Real t;
      Vec3 nrm;
      if (!rayShape(m_bodies[j], p0, dir, toi, t, nrm, r) || !(t > 0)) return;
      const Real depth = (len - t) * -dir.dot(nrm);  // end position below the grown surface
      if (depth > Real(0.5) * r) toi = t;
    };
    for (std::uint32_t j : st.statics)
      if (swept.overlaps(st.boxes[j])) test(j);
    for (std::uint32_t j : st.planes) test(j);
    if (m_heightField) {
      HeightFieldHit hit;
      Real h;
      Vec3 n;
      const bool startAbove = !m_heightField->surfaceAt(p0.x(), p0.z(), &h, &n) || p0.y() >= h;
      if (startAbove && m_heightField->rayCast(p0, dir, len, &hit)) {
        const Real cosine = -dir.dot(hit.normal);
        if (cosine > 0) toi = std::min(toi, std::max<Real>(hit.distance_m - r / cosine, 0));
      }
    }
    if (toi < len) b.position_m = p0 + dir * toi;
  }
}

// ---- error bookkeeping -----------------------------------------------------------

double World::totalEnergy() const {
  double e = 0;
  const Eigen::Vector3d g = m_settings.gravity_mps2.cast<double>();
  for (const Body& b : m_bodies) {
    if (!b.alive || !b.isDynamic()) continue;
    Eigen::Vector3d v = b.linearVelocity_mps.cast<double>();
    Eigen::Vector3d wl = (b.orientation.conjugate() * b.angularVelocity_radps).cast<double>();
    e += 0.5 * b.mass_kg * v.squaredNorm() + 0.5 * wl.dot(b.inertiaLocal_kgm2.cast<double>().cwiseProduct(wl));
    e -= b.mass_kg * g.dot(b.position_m.cast<double>());
  }
  if (m_integration->springCount() > 0) e += m_integration->springEnergy(*this);
  return e;
}

Eigen::Vector3d World::totalMomentum() const {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (const Body& b : m_bodies)
    if (b.alive && b.isDynamic()) p += b.mass_kg * b.linearVelocity_mps.cast<double>();
  return p;
}

void World::resetErrorStats() {
  m_error = ErrorStats{};
  m_energy0 = totalEnergy();
  m_externalWork = 0;
  m_momentum0 = totalMomentum();
  m_externalImpulse.setZero();
  m_trackingStarted = true;
  // Energy scale: the energy that could be converted in the scene, so that a
  // resting scene (E ~ 0) does not divide by zero: sum of |kinetic| plus
  // m g (height above the lowest body) plus 1 J.
  double lowest = 0, ke = 0, mg = 0;
  bool first = true;
  const double g = m_settings.gravity_mps2.cast<double>().norm();
  for (const Body& b : m_bodies)
    if (b.alive && b.isDynamic()) {
      double y = b.position_m.y() - b.shape.boundingRadius();
      lowest = first ? y : std::min(lowest, y);
      first = false;
    }
  double ms = 0;
  for (const Body& b : m_bodies)
    if (b.alive && b.isDynamic()) {
      ke += 0.5 * b.mass_kg * b.linearVelocity_mps.squaredNorm();
      mg += b.mass_kg * g * (b.position_m.y() - lowest);
      ms += b.mass_kg * b.linearVelocity_mps.norm();
    }
  m_energyScale = ke + mg + 1.0;
  m_momentumScale = ms;
}

void World::trackErrors(Real dt) {
  // Energy: contacts (restitution <= 1, friction, soft constraints) and
  // damping can only remove energy, so any gain beyond the work done by
  // scripts is numerical error. energy_rel_drift_max is the largest such gain
  // relative to the scene's energy scale.
  double e = totalEnergy();
  double gain = (e - m_energy0 - m_externalWork) / m_energyScale;
  m_error.energyRelDriftMax = std::max<Real>(m_error.energyRelDriftMax, Real(std::max(gain, 0.0)));
  // Momentum: gravity, forces and impulses from static bodies and scripts are
  // external; what remains must cancel pairwise between dynamic bodies.
  (void)dt;
  double ms = 0;
  for (const Body& b : m_bodies)
    if (b.alive && b.isDynamic() && b.awake) ms += b.mass_kg * b.linearVelocity_mps.norm();
  m_momentumScale = std::max(m_momentumScale, ms);
  Eigen::Vector3d drift = totalMomentum() - m_momentum0 - m_externalImpulse;
  if (m_momentumScale > 0)
    m_error.momentumRelDriftMax = std::max<Real>(m_error.momentumRelDriftMax, Real(drift.norm() / m_momentumScale));
}

std::uint64_t World::stateHash() const {
  Hasher h;
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    const Body& b = m_bodies[i];
    if (!b.alive) continue;
    h.value(i);
    h.bytes(b.position_m.data(), sizeof(Real) * 3);
    h.bytes(b.orientation.coeffs().data(), sizeof(Real) * 4);
    h.bytes(b.linearVelocity_mps.data(), sizeof(Real) * 3);
    h.bytes(b.angularVelocity_radps.data(), sizeof(Real) * 3);
  }
  return h.digest();
}

// ---- queries -----------------------------------------------------------------------

static bool rayShapeAt(const Shape& s, const Vec3& position, const Quat& orientation, const Vec3& o, const Vec3& d,
                       Real maxT, Real& tHit, Vec3& nHit, Real inflate, MeshStats* meshStats = nullptr) {
  // d is unit length here.
  struct {
    const Vec3& position_m;
    const Quat& orientation;
  } b{position, orientation};
  auto raySphere = [&](const Vec3& c, Real r, Real& t, Vec3& n) {
    Vec3 m = o - c;
    Real bq = m.dot(d), cq = m.squaredNorm() - r * r;
    if (cq > 0 && bq > 0) return false;
    Real disc = bq * bq - cq;
    if (disc < 0) return false;
    t = std::max<Real>(-bq - std::sqrt(disc), 0);
    if (t > maxT) return false;
    n = (o + d * t - c).normalized();
    return true;
  };
  switch (s.type) {
    case ShapeType::Sphere: return raySphere(b.position_m, s.radius_m + inflate, tHit, nHit);
    case ShapeType::Plane: {
      Vec3 n = b.orientation * Vec3::UnitY();
      Real denom = n.dot(d);
      Real dist = n.dot(o - b.position_m) - inflate;
      if (dist < 0) return false;  // starts behind the plane
      if (denom >= 0) return false;
      Real t = -dist / denom;
      if (t > maxT) return false;
      tHit = t;
      nHit = n;
      return true;
    }
    case ShapeType::Box: {
      Mat3 R = b.orientation.toRotationMatrix();
      Vec3 lo = R.transpose() * (o - b.position_m), ld = R.transpose() * d;
      const Vec3 he = s.halfExtents_m + Vec3::Constant(inflate);
      Real tmin = 0, tmax = maxT;
      int axis = -1;
      Real sign = 1;
      for (int i = 0; i < 3; ++i) {
        if (std::abs(ld[i]) < Real(1e-12)) {
          if (std::abs(lo[i]) > he[i]) return false;
          continue;
        }
        Real inv = 1 / ld[i];
        Real t1 = (-he[i] - lo[i]) * inv, t2 = (he[i] - lo[i]) * inv;
        Real sg = -1;
        if (t1 > t2) std::swap(t1, t2), sg = 1;
        if (t1 > tmin) tmin = t1, axis = i, sign = sg;
        tmax = std::min(tmax, t2);
        if (tmin > tmax) return false;
      }
      tHit = tmin;
      Vec3 nl = Vec3::Zero();
      if (axis >= 0) nl[axis] = sign;
      else nl = -ld;  // started inside
      nHit = (R * nl).normalized();
      return true;
    }
    case ShapeType::Capsule: {
      Vec3 axis = b.orientation * Vec3::UnitY();
      Vec3 p0 = b.position_m - axis * s.halfHeight_m, p1 = b.position_m + axis * s.halfHeight_m;
      // Infinite cylinder, then the caps.
      Real best = std::numeric_limits<Real>::max();
      Vec3 bestN = Vec3::UnitY();
      Vec3 m = o - p0, dperp = d - axis * d.dot(axis), mperp = m - axis * m.dot(axis);
      const Real rad = s.radius_m + inflate;
      Real a = dperp.squaredNorm(), bq = mperp.dot(dperp), c = mperp.squaredNorm() - rad * rad;
      if (a > Real(1e-12)) {
        Real disc = bq * bq - a * c;
        if (disc >= 0) {
          Real t = (-bq - std::sqrt(disc)) / a;
          if (c < 0) t = 0;
          Real along = (o + d * t - p0).dot(axis);
          if (t >= 0 && t <= maxT && along >= 0 && along <= 2 * s.halfHeight_m) {
            best = t;
            Vec3 q = o + d * t;
            bestN = (q - (p0 + axis * along)).normalized();
          }
        }
      }
      for (const Vec3& c2 : {p0, p1}) {
        Real t;
        Vec3 n;
        if (raySphere(c2, s.radius_m + inflate, t, n) && t < best) best = t, bestN = n;
      }
      if (best > maxT) return false;
      tHit = best;
      nHit = bestN;
      return true;
    }
    case ShapeType::Hull:
      return rayHull(o, d, maxT, Pose{position, orientation.toRotationMatrix()}, *s.hull, inflate, tHit, nHit);
    case ShapeType::Mesh: return rayMesh(o, d, maxT, position, orientation, *s.mesh, inflate, tHit, nHit, meshStats);
    case ShapeType::Compound: {
      bool any = false;
      for (const CompoundChild& c : s.compound->children) {
        Real t;
        Vec3 n;
        if (rayShapeAt(c.shape, position + orientation * c.position_m, orientation * c.orientation, o, d, maxT, t, n,
                       inflate) &&
            (!any || t < tHit))
          any = true, tHit = t, nHit = n;
      }
      return any;
    }
  }
  return false;
}

static bool rayShape(const Body& b, const Vec3& o, const Vec3& d, Real maxT, Real& tHit, Vec3& nHit, Real inflate,
                     MeshStats* meshStats) {
  return rayShapeAt(b.shape, b.position_m, b.orientation, o, d, maxT, tHit, nHit, inflate, meshStats);
}

// Speculative contacts take their normal from the positions at the start of
// the step. A fast sphere that will hit a wall's face squarely can be, at
// the start of the step, closest to the wall's end edge: that contact's
// normal is tilted towards the sphere, and the solver stops the sphere's
// motion along it, deflecting a ball that was about to hit the face (a
// "ghost" contact; bullets.lua with 4 m walls measured 3 of 15 balls turned
// away). So, as collideSpheresSwept does for two spheres, a sphere that can
// move more than 2 * spec this step against a shape that does not move or
// turn gets its contact from the time of impact: its centre's path against
// the shape grown by the radius (rayShape; the grown box has sharp corners,
// so a path grazing a corner counts as a hit: conservative). The normal is
// the face normal there, the separation the distance to that face plane
// along it (so the solver lets it approach exactly until impact), and a path
// that misses gives no contact. A sphere already within spec of the shape
// gets the ordinary contact.
static bool sweptSphereContact(const Body& sphere, const Body& other, const Vec3& motion, Real spec, bool sphereIsA,
                               Manifold& m) {
  m.count = 0;
  if (collideBodies(sphereIsA ? sphere : other, sphereIsA ? other : sphere, spec, m) > 0) return true;
  m.count = 0;
  const Real len = motion.norm();
  if (!(len > 0)) return false;
  const Vec3 dir = motion / len;
  const Real r = sphere.shape.radius_m;
  Real t;
  Vec3 n;
  if (!rayShape(other, sphere.position_m, dir, len + spec, t, n, r)) return false;
  const Real approach = -n.dot(dir);
  if (!(approach > 0)) return false;
  const Real sep = std::max<Real>(t * approach, 0);
  m.normal = sphereIsA ? Vec3(-n) : n;
  ContactPoint& c = m.points[0];
  c.point_m = sphere.position_m - n * (r + sep / 2);
  c.separation_m = sep;
  c.id = 0;
  m.count = 1;
  return true;
}

std::vector<RayHit> World::rayCastAll(const Vec3& origin, const Vec3& dir, Real maxDistance) const {
  std::vector<RayHit> hits;
  Real len = dir.norm();
  if (!(len > 0) || !origin.allFinite() || !std::isfinite(maxDistance)) return hits;
  Vec3 d = dir / len;
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    const Body& b = m_bodies[i];
    if (!b.alive) continue;
    Real t;
    Vec3 n;
    if (rayShape(b, origin, d, maxDistance, t, n, 0, &m_meshStats)) hits.push_back({idOf(i), t, origin + d * t, n});
  }
  HeightFieldHit fh;
  if (m_heightField && m_heightField->rayCast(origin, d, maxDistance, &fh))
    hits.push_back({BodyId{}, fh.distance_m, fh.point_m, fh.normal});
  std::sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) { return a.distance_m < b.distance_m; });
  return hits;
}

bool World::rayCast(const Vec3& origin, const Vec3& dir, Real maxDistance, RayHit* hit) const {
  auto hits = rayCastAll(origin, dir, maxDistance);
  if (hits.empty()) return false;
  if (hit) *hit = hits.front();
  return true;
}

void World::debugDraw(DebugDraw& draw) const {
  for (const Manifold& m : m_manifolds)
    for (int i = 0; i < m.count; ++i) {
      const Vec3& p = m.points[i].point_m;
      draw.line(p, p + m.normal * Real(0.3), Vec3(1, 1, 0));
    }
}

}  // namespace tumble::physics
