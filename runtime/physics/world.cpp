// The World's body store: creating, validating, removing and changing
// bodies, applied forces and impulses (counted as external work and
// momentum for the error figures), springs, the height field and the
// per-substep hooks. What a step does is in world_step.cpp; the other
// parts of the World each have a file of their own (see README.md).
#include "physics/world.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/byte_stream.h"
#include "physics/internal/broad_phase.h"
#include "physics/internal/height_field_collision.h"
#include "physics/internal/step_scratch.h"

namespace tumble::physics {

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

Status validateWorldSettings(const WorldSettings& s) {
  auto bad = [](const char* field, const char* expected) {
    return makeError(std::string("world settings field ") + field + ": expected " + expected);
  };
  if (!validBools(s.softContacts, s.continuousStatic, s.meshTree, s.enableSleep, s.gyroscopic))
    return bad("(a switch)", "true or false");
  if (s.substeps < 1 || s.substeps > 1000) return bad("substeps", "1..1000");
  if (s.threads < 1 || s.threads > 64) return bad("threads", "1..64");
  if (s.velocityIterations < 1 || s.velocityIterations > 1000) return bad("velocityIterations", "1..1000");
  if (s.relaxIterations < 0 || s.relaxIterations > 1000) return bad("relaxIterations", "0..1000");
  if (s.restitutionIterations < 0 || s.restitutionIterations > 1000) return bad("restitutionIterations", "0..1000");
  if (s.maxContactPairsPerBody < 0) return bad("maxContactPairsPerBody", ">= 0 (0: no cap)");
  if (int(s.integrator) < int(BodyIntegrator::SymplecticEuler) || int(s.integrator) > int(BodyIntegrator::Sdirk2))
    return bad("integrator", "one of the body integrators");
  if (!s.gravity_mps2.allFinite()) return bad("gravity_mps2", "finite m/s^2");
  for (auto [field, v] : {std::pair<const char*, Real>{"solverTolerance", s.solverTolerance},
                          {"restitutionThreshold_mps", s.restitutionThreshold_mps},
                          {"baumgarte", s.baumgarte},
                          {"contactHertz", s.contactHertz},
                          {"contactDampingRatio", s.contactDampingRatio},
                          {"maxPushoutSpeed_mps", s.maxPushoutSpeed_mps},
                          {"speculativeDistance_m", s.speculativeDistance_m},
                          {"linearSlop_m", s.linearSlop_m},
                          {"sleepLinearSpeed_mps", s.sleepLinearSpeed_mps},
                          {"sleepAngularSpeed_radps", s.sleepAngularSpeed_radps},
                          {"timeToSleep_s", s.timeToSleep_s}})
    if (!std::isfinite(v) || v < 0) return bad(field, "a finite number >= 0");
  return Ok{};
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
void World::setSoundMaterial(BodyId id, std::uint8_t material) { mutableBody(id).soundMaterial = material; }
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

World::BodyPair World::makePair(BodyId x, BodyId y) {
  if (y.index < x.index) std::swap(x, y);
  return BodyPair{x.index, y.index, x.generation, y.generation};
}

}  // namespace tumble::physics
