// JointSystem: the joints' bookkeeping and the facade over the two joint
// solvers. Which file holds what:
//   joint.cpp                  definitions, validation, the table of joint types
//   ball_joint.cpp, hinge_joint.cpp, cone_twist_joint.cpp, fixed_joint.cpp
//                              each type's rows for both solvers
//   lagrange_solver.cpp        the Lagrange multipliers' sparse system (LDL^T)
//   lagrange_substeps.cpp      ... and its driver inside World::step
//   impulse_solver.cpp         the sequential-impulse solver inside World::step
//   elimination_order.cpp      the joints' order (both solvers)
//   free_integration.cpp       integrateFree, the joint-only integrator
//   ragdoll.cpp                the rag-doll builder
// Here: creating and removing joints, the results of the last step (forces,
// breaks, the anchor error), sleepers and dead bodies, the joint order and
// the World's island links, and switching the solver.
#include "physics/joints/joint_system.h"

#include <algorithm>
#include <cmath>

#include "physics/internal/impulse_joints.h"
#include "physics/internal/joint_types.h"
#include "physics/internal/lagrange_solver.h"

namespace tumble::physics {

using namespace lagrange;

const char* jointSolverName(JointSolverKind kind) {
  return kind == JointSolverKind::Impulse ? "impulse" : "lagrange";
}

bool parseJointSolver(const std::string& text, JointSolverKind* out) {
  if (text == "lagrange") *out = JointSolverKind::Lagrange;
  else if (text == "impulse") *out = JointSolverKind::Impulse;
  else return false;
  return true;
}

const char* jointIntegratorName(JointIntegrator m) {
  switch (m) {
    case JointIntegrator::ExplicitEuler: return "explicit_euler";
    case JointIntegrator::Trapezoid: return "trapezoid";
    case JointIntegrator::SemiImplicitEuler: return "semi_implicit_euler";
    case JointIntegrator::Rk4: return "rk4";
  }
  return "?";
}

JointSystem::JointSystem(World& world, const JointSettings& settings)
    : m_world(world), m_settings(settings), m_impl(std::make_unique<Impl>()) {
  const JointSolverKind kind = m_settings.solver;
  m_settings.solver = JointSolverKind::Lagrange;
  setSolver(kind);
}

JointSystem::~JointSystem() {
  if (m_impulse && m_world.constraintSolver() == m_impulse.get()) m_world.setConstraintSolver(nullptr);
  if (m_lagrange && m_world.constraintSolver() == m_lagrange.get()) m_world.setConstraintSolver(nullptr);
}

void JointSystem::setSolver(JointSolverKind kind) {
  m_settings.solver = kind;
  // Asked for Lagrange: the cost cap is checked again before the next step.
  m_orderDirty = m_orderDirty || kind == JointSolverKind::Lagrange;
  runSolver(kind);
}

void JointSystem::runSolver(JointSolverKind kind) {
  if (kind == JointSolverKind::Impulse && !m_impulse) {
    if (m_lagrange && m_world.constraintSolver() == m_lagrange.get()) m_world.setConstraintSolver(nullptr);
    m_lagrange.reset();
    m_impl->inStep = false;
    m_impl->resultsPending = false;
    m_impl->pendingBreaks.clear();
    m_impulse = std::make_unique<ImpulseJoints>(*this, m_settings.impulseHertz, m_settings.impulseDampingRatio);
    m_world.setConstraintSolver(m_impulse.get());
  } else if (kind == JointSolverKind::Lagrange && !m_lagrange) {
    if (m_impulse && m_world.constraintSolver() == m_impulse.get()) m_world.setConstraintSolver(nullptr);
    m_impulse.reset();
    m_lagrange = std::make_unique<LagrangeSubsteps>(*this);
    m_world.setConstraintSolver(m_lagrange.get());
  }
}

// ---- joint bookkeeping -------------------------------------------------------------

Result<JointId> JointSystem::createJoint(const JointDef& def) {
  if (auto s = validateJointDef(m_world, def); !s) return makeError(s.error());
  std::uint32_t index;
  if (!m_freeList.empty()) {
    index = m_freeList.back();
    m_freeList.pop_back();
  } else {
    index = std::uint32_t(m_slots.size());
    m_slots.emplace_back();
  }
  Slot& s = m_slots[index];
  const std::uint32_t generation = s.generation + 1;  // odd while alive; the zero handle is null
  s = Slot{};
  s.def = def;
  s.def.localFrameA.normalize();
  s.def.localFrameB.normalize();
  s.generation = generation;
  s.alive = true;
  ++m_jointCount;
  m_orderDirty = true;
  return JointId{index, generation};
}

bool JointSystem::isValid(JointId id) const {
  return !id.isNull() && id.index < m_slots.size() && m_slots[id.index].alive &&
         m_slots[id.index].generation == id.generation;
}

bool JointSystem::destroyJoint(JointId id) {
  if (!isValid(id)) return false;
  Slot& s = m_slots[id.index];
  s.alive = false;
  ++s.generation;
  m_freeList.push_back(id.index);
  --m_jointCount;
  m_orderDirty = true;
  return true;
}

const JointDef& JointSystem::jointDef(JointId id) const {
  TUMBLE_ASSERT(isValid(id), "stale or null JointId; check JointSystem::isValid first");
  return m_slots[id.index].def;
}
bool JointSystem::setMotor(JointId id, Real speed_radps, Real maxTorque_Nm) {
  if (!isValid(id) || !std::isfinite(speed_radps) || !std::isfinite(maxTorque_Nm) || maxTorque_Nm < 0) return false;
  JointDef& d = m_slots[id.index].def;
  d.enableMotor = maxTorque_Nm > 0;
  d.motorSpeed_radps = speed_radps;
  d.maxMotorTorque_Nm = maxTorque_Nm;
  if (m_world.isValid(d.bodyA)) m_world.wake(d.bodyA);
  return true;
}

bool JointSystem::setWorldAnchor(JointId id, const Vec3& anchor_m) {
  if (!isValid(id) || !anchor_m.allFinite()) return false;
  JointDef& d = m_slots[id.index].def;
  if (!d.bodyB.isNull()) return false;
  d.localAnchorB_m = anchor_m;
  if (m_world.isValid(d.bodyA)) m_world.wake(d.bodyA);
  return true;
}

Vec3 JointSystem::lastForce_N(JointId id) const {
  TUMBLE_ASSERT(isValid(id), "stale or null JointId; check JointSystem::isValid first");
  return m_slots[id.index].force_N;
}
Vec3 JointSystem::lastTorque_Nm(JointId id) const {
  TUMBLE_ASSERT(isValid(id), "stale or null JointId; check JointSystem::isValid first");
  return m_slots[id.index].torque_Nm;
}

std::vector<std::pair<BodyId, BodyId>> JointSystem::connectedPairs() const {
  std::vector<std::pair<BodyId, BodyId>> pairs;
  for (const Slot& s : m_slots)
    if (s.alive && !s.def.bodyB.isNull()) pairs.emplace_back(s.def.bodyA, s.def.bodyB);
  return pairs;
}

// ---- queries -------------------------------------------------------------------------

double JointSystem::jointAngle_rad(JointId id) const {
  const JointDef& d = jointDef(id);
  const JointTypeRows& type = jointTypeRows(d.type);
  if (!type.angle) return 0;
  BodyState a = stateFromWorld(m_world, d.bodyA);
  a.R = a.q.toRotationMatrix();
  BodyState b;
  if (!d.bodyB.isNull()) {
    b = stateFromWorld(m_world, d.bodyB);
    b.R = b.q.toRotationMatrix();
  }
  const JointPose pa = poseOf(d.localAnchorA_m, d.localFrameA, &a);
  const JointPose pb = poseOf(d.localAnchorB_m, d.localFrameB, d.bodyB.isNull() ? nullptr : &b);
  return type.angle(pa.F, pb.F);
}

double JointSystem::swingAngle_rad(JointId id) const {
  const JointDef& d = jointDef(id);
  const Quat qa = m_world.body(d.bodyA).orientation * d.localFrameA;
  const Quat qb = d.bodyB.isNull() ? d.localFrameB : m_world.body(d.bodyB).orientation * d.localFrameB;
  const double c = std::clamp<double>((qa * Vec3::UnitX()).cast<double>().dot((qb * Vec3::UnitX()).cast<double>()), -1, 1);
  return std::acos(c);
}

double JointSystem::anchorError_m(bool includeSprings) const {
  double worst = 0;
  for (const Slot& s : m_slots) {
    if (!s.alive || !m_world.isValid(s.def.bodyA) || (!includeSprings && s.def.linearStiffness_Npm > 0)) continue;
    const Body& a = m_world.body(s.def.bodyA);
    V3 pa = wide3(a.position_m) + (a.orientation * s.def.localAnchorA_m).cast<double>();
    V3 pb = wide3(s.def.localAnchorB_m);
    if (!s.def.bodyB.isNull()) {
      if (!m_world.isValid(s.def.bodyB)) continue;
      const Body& b = m_world.body(s.def.bodyB);
      pb = wide3(b.position_m) + (b.orientation * s.def.localAnchorB_m).cast<double>();
    }
    worst = std::max(worst, (pa - pb).norm());
  }
  return worst;
}

// Springs (grabs among them) stretch by design: not an error.
void JointSystem::measureError() { m_maxAnchorError_m = std::max(m_maxAnchorError_m, anchorError_m(false)); }

// ---- joint order, results, sleepers ---------------------------------------------------

void JointSystem::refreshLinks() {
  if (!m_orderDirty) return;
  Impl& im = *m_impl;
  std::vector<JointDef> defs;
  std::vector<std::uint32_t> ids;
  for (std::uint32_t i = 0; i < m_slots.size(); ++i)
    if (m_slots[i].alive) defs.push_back(m_slots[i].def), ids.push_back(i);
  im.order = eliminationOrder(m_world, defs, ids);
  // Jointed bodies sleep and wake as one island (World::setIslandLinks).
  m_world.setIslandLinks(connectedPairs());
  m_orderDirty = false;
}

void JointSystem::solveOrder(std::vector<std::uint32_t>& out) const {
  out.clear();
  if (!m_orderDirty) {
    for (std::uint32_t i : m_impl->order)
      if (m_slots[i].alive) out.push_back(i);
    return;
  }
  for (std::uint32_t i = 0; i < m_slots.size(); ++i)
    if (m_slots[i].alive) out.push_back(i);
}

void JointSystem::recordForces() {
  const Impl& im = *m_impl;
  for (std::size_t k = 0; k < im.ev.slots.size() && k < im.jointForce.size(); ++k) {
    Slot& s = m_slots[im.ev.slots[k]];
    if (!s.alive || s.generation != im.ev.generations[k]) continue;  // destroyed since
    s.force_N = im.jointForce[k].cast<Real>();
    s.torque_Nm = im.jointTorque[k].cast<Real>();
  }
}

void JointSystem::finishBreaks(std::vector<JointBreakEvent>& events) {
  for (JointBreakEvent& e : events) {
    if (e.id.index >= m_slots.size() || !m_slots[e.id.index].alive) continue;  // reported already
    if (e.id.generation != 0 && e.id.generation != m_slots[e.id.index].generation) continue;  // slot reused since
    e.id.generation = m_slots[e.id.index].generation;
    destroyJoint(e.id);
    m_broken.push_back(e);
  }
}

bool JointSystem::dropJointsOfDeadBodies() {
  for (std::uint32_t i = 0; i < m_slots.size(); ++i) {
    Slot& s = m_slots[i];
    if (!s.alive) continue;
    if (!m_world.isValid(s.def.bodyA) || (!s.def.bodyB.isNull() && !m_world.isValid(s.def.bodyB))) {
      JointBreakEvent e{JointId{i, s.generation}, s.def.bodyA, s.def.bodyB, 0, 0, s.def.userData};
      destroyJoint(e.id);
      m_broken.push_back(e);
    }
  }
  return m_jointCount > 0;
}

void JointSystem::wakeJointedSleepers() {
  // Sleeping bodies: a sleeping body jointed to a body that moves faster
  // than the sleep thresholds is woken (the World's islands know only
  // contacts); otherwise it is held as fixed for this step and gets no force.
  const WorldSettings& ws = m_world.settings();
  auto fast = [&](const Body& b) {
    return b.isDynamic() && b.awake &&
           (b.linearVelocity_mps.norm() > ws.sleepLinearSpeed_mps ||
            b.angularVelocity_radps.norm() > ws.sleepAngularSpeed_radps);
  };
  for (const Slot& s : m_slots) {
    if (!s.alive || s.def.bodyB.isNull()) continue;
    const Body& a = m_world.body(s.def.bodyA);
    const Body& b = m_world.body(s.def.bodyB);
    if (!a.awake && a.isDynamic() && fast(b)) m_world.wake(s.def.bodyA);
    if (!b.awake && b.isDynamic() && fast(a)) m_world.wake(s.def.bodyB);
  }
}

void JointSystem::step(Real dt_s) {
  // The projection runs at the start of the step rather than at the end of
  // the previous one: for free chains that is the same cycle, but with
  // contacts the World's contact solver then has the last word on the
  // velocities (projecting after it pushed resting parts back into the
  // ground: a rag-doll never fell asleep, measured 0.3 m/s forever).
  beforeWorldStep();
  m_world.step(dt_s);
  if (m_impulse) collectImpulseResults();
  else collectLagrangeResults();
  measureError();
}

void JointSystem::beforeWorldStep() {
  // Both solvers solve inside World::step (ImpulseJoints,
  // LagrangeSubsteps); here: the results of the last step, dead bodies,
  // sleepers, the joint order.
  m_broken.clear();
  if (m_impulse) collectImpulseResults();
  else collectLagrangeResults();
  if (dropJointsOfDeadBodies()) wakeJointedSleepers();
  const bool changed = m_orderDirty;
  const bool fresh = changed || !allJointedBodiesKnown();
  refreshLinks();
  if (m_settings.solver == JointSolverKind::Lagrange) {
    // The cost cap (JointSettings::lagrangeMaxFactorWorkPerRow): checked whenever
    // the joint set changes, and found in a step when active limit rows
    // grew the system past it; the impulse solver stands in meanwhile.
    if (m_lagrange && m_impl->overCostCap) {
      m_overCostCapWorkPerRow = m_stats.factorWork / std::max(1, m_stats.rows);
      runSolver(JointSolverKind::Impulse);
    } else if (changed) {
      runSolver(lagrangeFitsCostCap() ? JointSolverKind::Lagrange : JointSolverKind::Impulse);
    }
    m_impl->overCostCap = false;
    if (m_impulse) ++m_stepsOverCostCap;
  }
  if (!m_impulse && m_settings.postStabilize && fresh) postStabilize();
  measureError();
}

bool JointSystem::allJointedBodiesKnown() const {
  // Known: solved in the last World step (a valid memo, see substepSolve).
  const Impl& im = *m_impl;
  auto known = [&](BodyId id) {
    if (id.isNull() || !m_world.isValid(id)) return true;
    const Body& b = m_world.body(id);
    if (!b.isDynamic() || !b.awake) return true;
    if (id.index >= im.memo.size()) return false;
    const Impl::Memo& memo = im.memo[id.index];
    return memo.generation == id.generation && memo.serial >= im.serial;
  };
  for (const Slot& s : m_slots)
    if (s.alive && (!known(s.def.bodyA) || !known(s.def.bodyB))) return false;
  return true;
}

void JointSystem::collectLagrangeResults() {
  Impl& im = *m_impl;
  if (!im.resultsPending) return;
  im.resultsPending = false;
  recordForces();
  finishBreaks(im.pendingBreaks);
  im.pendingBreaks.clear();
}

void JointSystem::collectImpulseResults() {
  const std::vector<ImpulseJoints::Output>& out = m_impulse->outputs();
  std::vector<JointBreakEvent> events;
  for (std::uint32_t i = 0; i < m_slots.size() && i < out.size(); ++i) {
    Slot& s = m_slots[i];
    if (!s.alive || out[i].generation != s.generation) continue;
    // Stored as the force on A, like the Lagrange solver's lastForce_N.
    s.force_N = -out[i].force_N;
    s.torque_Nm = -out[i].torque_Nm;
    if (out[i].broken) {
      JointBreakEvent e{JointId{i, s.generation}, s.def.bodyA, s.def.bodyB, double(out[i].force_N.norm()),
                        double(out[i].torque_Nm.norm()), s.def.userData};
      events.push_back(e);
    }
  }
  m_impulse->clearBroken();
  finishBreaks(events);
}

}  // namespace tumble::physics
