// One World step: the order of world.h, run top to bottom in World::step,
// and the bodies' integration between the contact solves.
//
// Integration (semi-implicit Euler, per substep h):
//   v += h (g + F/m);  w += h I^-1 tau + the last turn's change of w (below);
//   contacts and joints change v, w;  x += h v;  the orientation turns
//   torque-free for h (below);  q normalised.
//
// ---- Rotation: angular momentum kept, no separate gyroscopic step -----------
// A body whose principal moments differ turns in each substep as a free
// rigid body would: its angular momentum L = R I R^T w (world) is kept, the
// orientation follows the exact torque-free motion for h, and w becomes
// R' I^-1 R'^T L at the new orientation R'. The gyroscopic term w x (I w)
// is thus in the motion itself, and the contacts and joints of the next
// substep see the w a free body has there. That change of w is applied at
// the start of the next substep (integrateVelocities, where the gyroscopic
// step was; after the last substep, at the end of the step): the relax
// sweeps between work with the w the positions just moved with, and the
// Lagrange joint solver counts the change as a known force, as it counted
// the gyroscopic step (lagrange_substeps.cpp, "Time stepping"), and counts
// what the turn did to the positions in its rows' curvature
// (addFreeTurnCurvature there). Applied at
// once instead, the Lagrange relax pulled it back out (its rows and their
// curvature are the substep's start): over 48 piles of rag-dolls (8-12
// dolls, dt 1/60 and 1/30, 4 and 8 substeps, shifted by up to 2 mm) the
// worst anchor error was 0.27 m, against 0.17 m this way.
// The torque-free motion is split as the kinetic energy is (Dullweber, Reich
// and Leimkuhler 1997; for a symmetric body this split is exact):
//   T = |L|^2 / (2 Ia) + sum over the other two axes k of Lk^2/2 (1/Ik - 1/Ia),
// the first a turn about L (|L|^2 commutes with everything), the others
// turns about the body's own axes, in the symmetric order k1 (h/2), k2 (h),
// k1 (h/2). Ia is chosen so that a symmetric body's split has one term
// only. |L| is kept exactly and the energy's error stays bounded; a
// T-handle still flips (Dzhanibekov): base:spin's keeps |L| to 1e-5 and its
// energy to 8e-5 (1e-3 and 2e-3 with the implicit midpoint below). Done in
// double: in float each round trip L -> w -> L through a float quaternion
// scaled |L| by |q|^4, and a flipping body's |L| drifted by 1e-3 in 12 s.
// Why not a gyroscopic step on w before the solve (the implicit midpoint in
// the body frame, before): it turned w by (I3 - I1)/I1 w3 h about the spin
// axis with the orientation held, 0.42 rad a substep for a disc spinning at
// 200 rad/s, and the joints then pulled that rotated w back: a disc top on
// a ball joint (0.25 m from its centre, level, in steady precession) sank
// 18 degrees in 4.5 s and a square box top 28 (the analytic answer stays
// level). Now: 0.06 and 0.18 degrees (0.17 and 0.40 at 50 rad/s), the
// precession within 0.1 % (tools/tumble report accuracy, "top").
// Rejected before that: explicit Euler on w x (I w) (gains energy; a
// spinning T-handle blows up) and Catto's one-step implicit Euler (loses
// 11 % of a flipping box's energy in 20 s at 60 Hz).
// A body with equal moments (sphere, cube) has no gyroscopic term and keeps
// the first-order update q += h/2 (0, w) q. Split-impulse pseudo-velocities
// move the orientation that way too and are then dropped.
// The inverse world inertia of a turning body is refreshed after each
// substep's rotation, so the joint rows of the relax and of the next
// substep and the applied torques use the orientation they act at (the
// contact rows keep the step's start, as they keep their geometry): taken
// once per step, a box top's precession was 2.5 % slow at 200 rad/s and
// 22 % at 50 rad/s, at any number of substeps.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "physics/constraint_solver.h"
#include "physics/internal/step_scratch.h"
#include "physics/world.h"

namespace tumble::physics {
namespace {

/// The contact solver's settings for substeps of length h.
SolverSettings solverSettings(const WorldSettings& ws, Real h) {
  SolverSettings ss;
  ss.h = h;
  ss.contactHertz = ws.contactHertz;
  ss.contactDampingRatio = ws.contactDampingRatio;
  ss.maxPushout_mps = ws.maxPushoutSpeed_mps;
  ss.restitutionThreshold_mps = ws.restitutionThreshold_mps;
  ss.linearSlop_m = ws.linearSlop_m;
  ss.softContacts = ws.softContacts;
  ss.baumgarte = ws.baumgarte;
  ss.restitutionIterations = ws.restitutionIterations;
  return ss;
}

Eigen::Quaterniond axisAngle(const Eigen::Vector3d& axis, double angle) {
  const double half = angle / 2, s = std::sin(half);
  return Eigen::Quaterniond(std::cos(half), s * axis.x(), s * axis.y(), s * axis.z());
}

/// Whether a body's principal moments are all equal (no gyroscopic term).
bool isotropic(const Vec3& I) { return I.x() == I.y() && I.y() == I.z(); }

/// The torque-free motion for time h (see the top of the file): turns q and
/// replaces w (world) by the angular velocity at the new orientation, with
/// the angular momentum kept. I: principal moments (kg m^2). In double
/// (see the top of the file).
Quat turnTorqueFree(const Quat& orientation, const Vec3& principal, Vec3& w, Real h_s) {
  using V = Eigen::Vector3d;
  const double h = h_s;
  const V I = principal.cast<double>();
  Eigen::Quaterniond q = orientation.cast<double>().normalized();
  V Lb = I.cwiseProduct(q.conjugate() * w.cast<double>());  // body frame
  const V L = q * Lb;                                         // world: kept
  // Ia: one of an equal pair where there is one, so the split is exact.
  const int a = I.y() == I.z() ? 1 : 0;
  // A turn about the body's axis k by Lk (1/Ik - 1/Ia) t: the body turns
  // by +angle, so L's body components turn by -angle in the other two.
  auto bodyTurn = [&](int k, double t) {
    const double angle = Lb[k] * (1 / I[k] - 1 / I[a]) * t;
    if (angle == 0) return;
    const double ch = std::cos(angle / 2), sh = std::sin(angle / 2);
    Eigen::Quaterniond r(ch, 0, 0, 0);
    r.vec()[k] = sh;
    q = q * r;
    const double c = ch * ch - sh * sh, s = 2 * sh * ch;
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double li = Lb[i], lj = Lb[j];
    Lb[i] = c * li + s * lj;
    Lb[j] = c * lj - s * li;
  };
  const int k1 = (a + 1) % 3, k2 = (a + 2) % 3;
  bodyTurn(k1, h / 2);
  bodyTurn(k2, h);
  bodyTurn(k1, h / 2);
  // The turn about L itself (world) leaves L's body components as they are.
  const double Ln = L.norm();
  if (Ln > 0) q = axisAngle(L / Ln, Ln / I[a] * h) * q;
  q.normalize();
  w = (q * Lb.cwiseQuotient(I)).cast<Real>();
  return q.cast<Real>();
}

}  // namespace

namespace {

/// Adds the time from its construction to its destruction to *sum_ms, when
/// sum_ms is not null (World::setPhaseTiming).
class PhaseClock {
 public:
  explicit PhaseClock(double* sum_ms) : m_sum(sum_ms) {
    if (m_sum) m_t0 = std::chrono::steady_clock::now();
  }
  ~PhaseClock() {
    if (m_sum) *m_sum += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - m_t0).count();
  }
  PhaseClock(const PhaseClock&) = delete;
  PhaseClock& operator=(const PhaseClock&) = delete;

 private:
  double* m_sum;
  std::chrono::steady_clock::time_point m_t0;
};

}  // namespace

void World::step(Real dt) {
  if (!(dt > 0) || !std::isfinite(dt)) return;
  m_phaseTimes = PhaseTimes{};
  double* const solverClock = m_phaseTiming ? &m_phaseTimes.contactSolver_ms : nullptr;
  if (!m_trackingStarted) resetErrorStats();
  freezeNonFinite();  // catches non-finite values set from outside (scripts)
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    m_stepStartPosition[i] = m_bodies[i].position_m;
    m_stepStartOrientation[i] = m_bodies[i].orientation;
  }
  {
    PhaseClock clock(m_phaseTiming ? &m_phaseTimes.collide_ms : nullptr);
    collide(dt);
  }
  const int substeps = std::max(1, m_settings.substeps);
  const SolverSettings ss = solverSettings(m_settings, dt / Real(substeps));
  gatherVelocities();
  ContactSolver& contacts = m_scratch->contacts;
  std::unique_ptr<WorkerPool>& pool = m_scratch->pool;
  const int threads = std::clamp(m_settings.threads, 1, 64);
  if (threads == 1) pool.reset();
  else if (!pool || pool->threads() != threads) pool = std::make_unique<WorkerPool>(threads);
  contacts.setPool(pool.get());
  {
    PhaseClock clock(solverClock);
    contacts.prepare(m_manifolds, m_bodies);
  }
  if (contacts.threadedLevels() > 0) ++m_stepsOnThreads;
  m_inStep = true;
  ConstraintSolver* joints = m_constraintSolver;  // the joint hook (constraint_solver.h), usually null
  if (joints) joints->prepare(*this, dt, substeps);
  for (int s = 0; s < substeps; ++s) substep(ss, joints);
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) m_scratch->vel[i].angular += wide(m_scratch->turn[i]);
  m_inStep = false;
  scatterVelocities();
  {
    PhaseClock clock(solverClock);
    contacts.store(m_manifolds);
  }
  if (joints) joints->finish(*this);
  if (m_settings.continuousStatic) clampToStatic();
  for (Body& b : m_bodies)
    if (b.alive && b.moves()) updateInertia(b);
  collectContactEvents();
  for (Body& b : m_bodies) {
    b.force_N.setZero();
    b.torque_Nm.setZero();
  }
  freezeNonFinite();
  updateSleep(dt);
  trackErrors(dt);
}

void World::gatherVelocities() {
  // The substeps work on compact velocity arrays, not on Body.
  StepScratch& st = *m_scratch;
  const std::size_t n = m_bodies.size();
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
  st.turn.assign(n + 1, Vec3::Zero());
}

void World::substep(const SolverSettings& ss, ConstraintSolver* joints) {
  StepScratch& st = *m_scratch;
  ContactSolver& contacts = st.contacts;
  const Real tol2 = m_settings.solverTolerance * m_settings.solverTolerance;
  double* const solverClock = m_phaseTiming ? &m_phaseTimes.contactSolver_ms : nullptr;
  // Separations now, for the solve and for the approach speeds.
  {
    PhaseClock clock(solverClock);
    contacts.updateSeparations(st.pose);
    contacts.recordFreeVelocities(st.vel);
  }
  integrateVelocities(ss.h);
  for (auto& [id, hook] : m_substepHooks) hook(*this, ss.h);
  {
    PhaseClock clock(solverClock);
    contacts.captureApproachSpeeds(st.vel, ss.h);
    contacts.warmStart(st.vel);
  }
  if (joints) joints->warmStart(st.vel.data(), m_bodies.data());
  {
    // Rolling and split impulses are per substep (not warm started), so
    // each substep can apply its full share again.
    PhaseClock clock(solverClock);
    contacts.resetSubstepImpulses();
  }
  // Positions change only in integratePositions, so separations are
  // updated once per phase, not once per iteration.
  for (int it = 0; it < m_settings.velocityIterations; ++it) {
    const Real jr = joints ? joints->solve(st.vel.data(), m_bodies.data(), true) : Real(0);
    Real r = 0;
    {
      PhaseClock clock(solverClock);
      r = contacts.solve(st.vel, st.pseudo, ss, true);
    }
    if (joints) joints->solvePushout(st.pseudo.data());
    if (r <= tol2 * contacts.lastMagnitude() && jr <= tol2) break;  // converged: see WorldSettings::solverTolerance
  }
  if (joints) {
    joints->beforeIntegrate(st.vel.data(), m_bodies.data());
    joints->projectPushout(st.pseudo.data(), m_bodies.data());
  }
  integratePositions(ss.h);
  if (m_settings.relaxIterations > 0) {
    PhaseClock clock(solverClock);
    contacts.updateSeparations(st.pose);
  }
  for (int it = 0; it < m_settings.relaxIterations; ++it) {
    const Real jr = joints ? joints->solve(st.vel.data(), m_bodies.data(), false) : Real(0);
    PhaseClock clock(solverClock);
    if (contacts.solve(st.vel, st.pseudo, ss, false) == 0 && jr == 0) break;
  }
  PhaseClock clock(solverClock);
  // Impulses from static, kinematic or sleeping bodies are external to the
  // moving set; between two moving bodies they cancel exactly.
  m_externalImpulse += contacts.externalImpulse();
  // Newton's law for the points that first pushed in this substep, so each
  // impact bounces in its own substep (two impacts in one step stay two).
  m_externalImpulse += contacts.applyRestitution(st.vel, ss);
}

void World::scatterVelocities() {
  const StepScratch& st = *m_scratch;
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    Body& b = m_bodies[i];
    if (!b.alive || !b.moves()) continue;
    b.linearVelocity_mps = narrow(st.vel[i].linear);
    b.angularVelocity_radps = narrow(st.vel[i].angular);
  }
}

void World::collectContactEvents() {
  // Begin-contact events: a manifold that had no points last step and
  // pushed this step.
  for (const Manifold& m : m_manifolds) {
    Real total = 0;
    for (int i = 0; i < m.count; ++i) total += m.points[i].impactImpulse;
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
    w += m_scratch->turn[i];
    m_scratch->turn[i].setZero();
    if (b.force_N != Vec3::Zero() || b.torque_Nm != Vec3::Zero()) {
      w += h * (b.invInertiaWorld * b.torque_Nm);
      m_externalImpulse += double(h) * b.force_N.cast<double>();
      m_externalWork += double(h) * (b.force_N.dot(v) + b.torque_Nm.dot(w));
    }
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
    // The rotation (see the top of the file): torque-free with the angular
    // momentum kept, or first order for equal moments; then the
    // pseudo-velocity's turn, which is dropped.
    const bool turns = m_settings.gyroscopic && b.isDynamic() && !isotropic(b.inertiaLocal_kgm2);
    Vec3 w = narrow(v.angular);
    if (turns) {
      b.orientation = turnTorqueFree(b.orientation, b.inertiaLocal_kgm2, w, h);
      st.turn[i] = w - narrow(v.angular);
      w = narrow(pv.angular);
    } else {
      w += narrow(pv.angular);
    }
    pv = SolverVelocity{};
    if (w != Vec3::Zero()) {
      Quat dq(0, w.x(), w.y(), w.z());
      dq = dq * b.orientation;
      b.orientation.coeffs() += (h / 2) * dq.coeffs();
      b.orientation.normalize();
    }
    const bool finite =
        b.position_m.allFinite() && b.orientation.coeffs().allFinite() && v.linear.allFinite() && v.angular.allFinite();
    if (!finite) {
      // A fault must not reach the neighbours in the next substep.
      freezeBody(i);
      st.vel[i] = SolverVelocity{};
      st.turn[i].setZero();
    } else if (turns) {
      updateInertia(b);
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

}  // namespace tumble::physics
