// One World step: the order of world.h, run top to bottom in World::step,
// and the bodies' integration between the contact solves.
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
#include <algorithm>
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

/// One implicit-midpoint step of Euler's torque-free equations in the body
/// frame (see the top of this file). Returns the new body-frame w.
Vec3 gyroscopicMidpoint(const Vec3& I, const Vec3& w1, Real h) {
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

}  // namespace

void World::step(Real dt) {
  if (!(dt > 0) || !std::isfinite(dt)) return;
  if (!m_trackingStarted) resetErrorStats();
  freezeNonFinite();  // catches non-finite values set from outside (scripts)
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    m_stepStartPosition[i] = m_bodies[i].position_m;
    m_stepStartOrientation[i] = m_bodies[i].orientation;
  }
  collide(dt);
  const int substeps = std::max(1, m_settings.substeps);
  const SolverSettings ss = solverSettings(m_settings, dt / Real(substeps));
  gatherVelocities();
  ContactSolver& contacts = m_scratch->contacts;
  contacts.prepare(m_manifolds, m_bodies);
  m_inStep = true;
  ConstraintSolver* joints = m_constraintSolver;  // the joint hook (constraint_solver.h), usually null
  if (joints) joints->prepare(*this, dt, substeps);
  for (int s = 0; s < substeps; ++s) substep(ss, joints);
  m_inStep = false;
  scatterVelocities();
  contacts.store(m_manifolds);
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
}

void World::substep(const SolverSettings& ss, ConstraintSolver* joints) {
  StepScratch& st = *m_scratch;
  ContactSolver& contacts = st.contacts;
  const Real tol2 = m_settings.solverTolerance * m_settings.solverTolerance;
  // Separations now, for the solve and for the approach speeds.
  contacts.updateSeparations(st.pose);
  contacts.recordFreeVelocities(st.vel);
  integrateVelocities(ss.h);
  for (auto& [id, hook] : m_substepHooks) hook(*this, ss.h);
  contacts.captureApproachSpeeds(st.vel, ss.h);
  contacts.warmStart(st.vel);
  if (joints) joints->warmStart(st.vel.data(), m_bodies.data());
  // Rolling and split impulses are per substep (not warm started), so
  // each substep can apply its full share again.
  contacts.resetSubstepImpulses();
  // Positions change only in integratePositions, so separations are
  // updated once per phase, not once per iteration.
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

}  // namespace tumble::physics
