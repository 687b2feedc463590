// Contact solver: sequential impulses at velocity level with soft
// constraints and substepping ("soft step", Catto, Box2D v3, 2024).
//
// For each contact point with normal n and offsets rA, rB from the centres of
// mass, the relative normal velocity is
//     vn = n . (vB + wB x rB - vA - wA x rA)
// and an impulse P = lambda n changes it by lambda / m_eff, with
//     1/m_eff = 1/mA + 1/mB + n . ((IA^-1 (rA x n)) x rA + (IB^-1 (rB x n)) x rB).
// Accumulated impulses are clamped (lambda >= 0: contacts push, never pull),
// which with Gauss-Seidel iteration converges to the complementarity
// solution; warm starting with last step's impulses makes stacks converge.
//
// Overlap is removed by a soft constraint: a spring-damper of stiffness
// `contactHertz` and damping ratio `contactDampingRatio` expressed as
// (biasRate, massScale, impulseScale) so that it is unconditionally stable for
// any step. Each substep solves with that bias, integrates positions, then
// "relaxes" without bias so the push-out velocity does not turn into bounce
// (this is what split impulses achieve, without a second velocity set).
// Two push-out models are implemented (WorldSettings::softContacts):
//  - split impulses (default): the velocity solve never pushes overlapping
//    bodies apart; a separate pass computes pseudo-velocities that remove
//    beta * depth / h of the overlap (at most maxPushout), positions move by
//    them, and they are then discarded (Catto 2006; Bullet's split impulse).
//    Correction cannot add kinetic energy, so a clump of deeply overlapping
//    bodies separates without being launched;
//  - soft: Box2D v3's mass-normalised spring-damper in the solve pass, with a
//    bias-free relax pass after the position update. Its steady-state overlap
//    is F / (m_eff w^2): a light body under a heavy one sinks deeply.
// Measured on 2026-11-22 (10 s of a 20-box stack, 5 s of a 1 kg box under a
// 1000 kg box, 6 s of 50 boxes spawned overlapping; dt = 1/60):
//   model  substeps x iters   stack drift   stack sink   1:1000 sink   overlap max speed
//   soft        4 x 1            6 mm         208 mm      collapses
//   soft        8 x 8            5 mm         208 mm      558 mm
//   rigid Baumgarte bias in the velocity solve (+relax), 8 x 4:
//                                3 mm           2 mm        9 mm        20 m/s (launched)
//   split impulses, 8 x 4:       3 mm           2 mm       12 mm         6.3 m/s (the fall)
//   split impulses, 4 x 4:      24 mm           8 mm       24 mm
//   split impulses, 8 x 8:       7 mm           1 mm        7 mm
// so the default is split impulses with 8 substeps of 4 iterations.
// Speculative contacts: a point with positive separation s allows the bodies
// to approach by at most s in this substep (bias = s/h), so a fast body stops
// at the surface instead of tunnelling through it.
//
// Restitution follows Newton's law: after the substeps, a point that was
// approaching faster than the threshold gets vn' = -e vn (one pass), so a
// ball dropped from h0 rebounds to e^2 h0.
//
// Friction: Coulomb with two tangents; the tangential impulse vector is
// clamped to the disc of radius mu * lambda_n (the friction cone, not a box).
//
// Rolling resistance: an angular constraint on the relative angular velocity
// in the tangent plane, its angular impulse clamped to the disc of radius
// arm * sum(lambda_n) with arm = C_rr * rolling radius, so a rolling ball
// feels at most the torque C_rr r N and comes to rest. Spin about the normal
// (drilling) is resisted with the same arm: without it a ball spinning on the
// spot spins for ever and drags whatever rests on it round in circles.
#include "physics/internal/contact_solver.h"

#include <algorithm>

namespace tumble::physics {
namespace {

struct BodyView {
  Real invMass;
  const Mat3* invI;
};
const Mat3 kZero3 = Mat3::Zero();

BodyView view(const Body& b) {
  if (!b.isDynamic() || !b.awake) return {0, &kZero3};
  return {b.invMass_per_kg, &b.invInertiaWorld};
}

Real effectiveMass(const BodyView& A, const BodyView& B, const Vec3& rA, const Vec3& rB, const Vec3& dir) {
  Vec3 ra = rA.cross(dir), rb = rB.cross(dir);
  Real k = A.invMass + B.invMass + ra.dot(*A.invI * ra) + rb.dot(*B.invI * rb);
  return k > 0 ? 1 / k : 0;
}

Vec3 relativeVelocity(const Body& a, const Body& b, const Vec3& rA, const Vec3& rB) {
  return b.linearVelocity_mps + b.angularVelocity_radps.cross(rB) - a.linearVelocity_mps -
         a.angularVelocity_radps.cross(rA);
}

void applyImpulse(Manifold& m, Body& a, Body& b, const BodyView& A, const BodyView& B, const Vec3& rA,
                  const Vec3& rB, const Vec3& P) {
  // Record what a non-moving side gives the moving side (momentum check).
  if (A.invMass == 0) m.externalImpulse_Ns += P.cast<double>();
  if (B.invMass == 0) m.externalImpulse_Ns -= P.cast<double>();
  a.linearVelocity_mps -= A.invMass * P;
  a.angularVelocity_radps -= *A.invI * rA.cross(P);
  b.linearVelocity_mps += B.invMass * P;
  b.angularVelocity_radps += *B.invI * rB.cross(P);
}

// Split-impulse position correction for one manifold: pseudo-velocities that
// remove beta * (depth - slop) / h of the overlap, accumulated per substep.
void solvePseudo(Manifold& m, const BodyView& A, const BodyView& B, const StepStart& start, const SolverSettings& s) {
  Vec3& lA = (*start.pseudoLinear)[m.a];
  Vec3& aA = (*start.pseudoAngular)[m.a];
  Vec3& lB = (*start.pseudoLinear)[m.b];
  Vec3& aB = (*start.pseudoAngular)[m.b];
  const Real invH = 1 / s.h;
  for (int i = 0; i < m.count; ++i) {
    ContactPoint& c = m.points[i];
    Real depth = -(c.currentSeparation_m + s.linearSlop_m);
    if (depth <= 0 && c.pseudoImpulse == 0) continue;
    Real target = std::min(s.baumgarte * invH * std::max<Real>(depth, 0), s.maxPushout_mps);
    Real pvn = m.normal.dot(lB + aB.cross(c.rB) - lA - aA.cross(c.rA));
    Real newImpulse = std::max<Real>(c.pseudoImpulse + c.normalMass * (target - pvn), 0);
    Real dl = newImpulse - c.pseudoImpulse;
    c.pseudoImpulse = newImpulse;
    Vec3 P = dl * m.normal;
    lA -= A.invMass * P;
    aA -= *A.invI * c.rA.cross(P);
    lB += B.invMass * P;
    aB += *B.invI * c.rB.cross(P);
  }
}

}  // namespace

void prepareContacts(std::vector<Manifold>& manifolds, const std::vector<Body>& bodies, const SolverSettings&) {
  for (Manifold& m : manifolds) {
    const Body& a = bodies[m.a];
    const Body& b = bodies[m.b];
    BodyView A = view(a), B = view(b);
    (void)A;
    (void)B;
    m.externalImpulse_Ns.setZero();
    // Tangent basis perpendicular to the normal.
    const Vec3& n = m.normal;
    Vec3 t0 = std::abs(n.x()) < Real(0.57) ? Vec3(Vec3::UnitX().cross(n)) : Vec3(Vec3::UnitY().cross(n));
    t0.normalize();
    m.tangent[0] = t0;
    m.tangent[1] = n.cross(t0);
    for (int i = 0; i < m.count; ++i) {
      ContactPoint& c = m.points[i];
      c.rA = c.point_m - a.position_m;
      c.rB = c.point_m - b.position_m;
      c.baseSeparation_m = c.separation_m - n.dot(c.rB - c.rA);
      c.normalMass = effectiveMass(A, B, c.rA, c.rB, n);
      c.tangentMass[0] = effectiveMass(A, B, c.rA, c.rB, m.tangent[0]);
      c.tangentMass[1] = effectiveMass(A, B, c.rA, c.rB, m.tangent[1]);
      c.relativeVelocity_mps = n.dot(relativeVelocity(a, b, c.rA, c.rB));
      c.maxNormalImpulse = 0;
    }
    m.rollingImpulse[0] = m.rollingImpulse[1] = m.rollingImpulse[2] = 0;
    if (m.rollingArm_m > 0)
      for (int k = 0; k < 3; ++k) {
        const Vec3& axis = k < 2 ? m.tangent[k] : m.normal;
        Real kr = axis.dot((*A.invI + *B.invI) * axis);
        m.rollingMass[k] = kr > 0 ? 1 / kr : 0;
      }
  }
}

void warmStartContacts(std::vector<Manifold>& manifolds, std::vector<Body>& bodies) {
  for (Manifold& m : manifolds) {
    Body& a = bodies[m.a];
    Body& b = bodies[m.b];
    BodyView A = view(a), B = view(b);
    for (int i = 0; i < m.count; ++i) {
      const ContactPoint& c = m.points[i];
      Vec3 P = c.normalImpulse * m.normal + c.tangentImpulse[0] * m.tangent[0] + c.tangentImpulse[1] * m.tangent[1];
      applyImpulse(m, a, b, A, B, c.rA, c.rB, P);
    }
  }
}

void solveContacts(std::vector<Manifold>& manifolds, std::vector<Body>& bodies, const StepStart& start,
                   const SolverSettings& s, bool useBias) {
  // Soft constraint coefficients (Box2D v3 b2MakeSoft).
  const Real hertz = std::min(s.contactHertz, Real(0.25) / s.h);
  const Real omega = 2 * kPi * hertz, zeta = s.contactDampingRatio;
  const Real a1 = 2 * zeta + s.h * omega, a2 = s.h * omega * a1, a3 = 1 / (1 + a2);
  const Real biasRate = omega / a1, softMassScale = a2 * a3, softImpulseScale = a3;
  const Real invH = 1 / s.h;

  for (Manifold& m : manifolds) {
    Body& a = bodies[m.a];
    Body& b = bodies[m.b];
    BodyView A = view(a), B = view(b);
    if (A.invMass == 0 && B.invMass == 0) continue;
    const Vec3& n = m.normal;
    // Displacements since the start of the step, to update separations
    // without re-running the narrow phase each substep.
    Vec3 dpA = a.position_m - (*start.position)[m.a];
    Vec3 dpB = b.position_m - (*start.position)[m.b];
    Quat dqA = a.orientation * (*start.orientation)[m.a].conjugate();
    Quat dqB = b.orientation * (*start.orientation)[m.b].conjugate();
    for (int i = 0; i < m.count; ++i) {
      ContactPoint& c = m.points[i];
      Vec3 d = dpB - dpA + (m.roundB ? c.rB : Vec3(dqB * c.rB)) - (m.roundA ? c.rA : Vec3(dqA * c.rA));
      Real sep = n.dot(d) + c.baseSeparation_m;
      Real bias = 0, massScale = 1, impulseScale = 0;
      if (sep > 0) {
        bias = sep * invH;  // speculative
      } else if (useBias && s.softContacts) {
        bias = std::max(biasRate * std::min<Real>(sep + s.linearSlop_m, 0), -s.maxPushout_mps);
        massScale = softMassScale;
        impulseScale = softImpulseScale;
      }
      c.currentSeparation_m = sep;
      Real vn = n.dot(relativeVelocity(a, b, c.rA, c.rB));
      // Newton's law needs the approach speed at impact: remember the normal
      // velocity of the substep in which this point first pushes.
      if (useBias && c.maxNormalImpulse == 0) c.relativeVelocity_mps = vn;
      Real impulse = -c.normalMass * massScale * (vn + bias) - impulseScale * c.normalImpulse;
      Real newImpulse = std::max<Real>(c.normalImpulse + impulse, 0);
      impulse = newImpulse - c.normalImpulse;
      c.normalImpulse = newImpulse;
      c.maxNormalImpulse = std::max(c.maxNormalImpulse, impulse);
      applyImpulse(m, a, b, A, B, c.rA, c.rB, impulse * n);
    }
    // Friction, clamped to the cone.
    for (int i = 0; i < m.count; ++i) {
      ContactPoint& c = m.points[i];
      Vec3 dv = relativeVelocity(a, b, c.rA, c.rB);
      Real old0 = c.tangentImpulse[0], old1 = c.tangentImpulse[1];
      Real t0 = old0 - c.tangentMass[0] * dv.dot(m.tangent[0]);
      Real t1 = old1 - c.tangentMass[1] * dv.dot(m.tangent[1]);
      Real maxF = m.friction * c.normalImpulse;
      Real len2 = t0 * t0 + t1 * t1;
      if (len2 > maxF * maxF) {
        Real scale = maxF / std::sqrt(len2);
        t0 *= scale;
        t1 *= scale;
      }
      c.tangentImpulse[0] = t0;
      c.tangentImpulse[1] = t1;
      Vec3 P = (t0 - old0) * m.tangent[0] + (t1 - old1) * m.tangent[1];
      applyImpulse(m, a, b, A, B, c.rA, c.rB, P);
    }
    if (m.rollingArm_m > 0) {
      Real total = 0;
      for (int i = 0; i < m.count; ++i) total += m.points[i].normalImpulse;
      Vec3 dw = b.angularVelocity_radps - a.angularVelocity_radps;
      Real old0 = m.rollingImpulse[0], old1 = m.rollingImpulse[1];
      Real r0 = old0 - m.rollingMass[0] * dw.dot(m.tangent[0]);
      Real r1 = old1 - m.rollingMass[1] * dw.dot(m.tangent[1]);
      Real maxR = m.rollingArm_m * total, len2 = r0 * r0 + r1 * r1;
      if (len2 > maxR * maxR) {
        Real scale = maxR / std::sqrt(len2);
        r0 *= scale;
        r1 *= scale;
      }
      m.rollingImpulse[0] = r0;
      m.rollingImpulse[1] = r1;
      Real old2 = m.rollingImpulse[2];
      Real r2 = std::clamp(old2 - m.rollingMass[2] * dw.dot(m.normal), -maxR, maxR);
      m.rollingImpulse[2] = r2;
      Vec3 L = (r0 - old0) * m.tangent[0] + (r1 - old1) * m.tangent[1] + (r2 - old2) * m.normal;
      a.angularVelocity_radps -= *A.invI * L;
      b.angularVelocity_radps += *B.invI * L;
    }
    if (useBias && !s.softContacts) solvePseudo(m, A, B, start, s);
  }
}

void applyRestitution(std::vector<Manifold>& manifolds, std::vector<Body>& bodies, const SolverSettings& s) {
  for (Manifold& m : manifolds) {
    if (m.restitution == 0) continue;
    Body& a = bodies[m.a];
    Body& b = bodies[m.b];
    BodyView A = view(a), B = view(b);
    for (int i = 0; i < m.count; ++i) {
      ContactPoint& c = m.points[i];
      if (c.relativeVelocity_mps > -s.restitutionThreshold_mps || c.maxNormalImpulse == 0) continue;
      Real vn = m.normal.dot(relativeVelocity(a, b, c.rA, c.rB));
      Real impulse = -c.normalMass * (vn + m.restitution * c.relativeVelocity_mps);
      Real newImpulse = std::max<Real>(c.normalImpulse + impulse, 0);
      impulse = newImpulse - c.normalImpulse;
      c.normalImpulse = newImpulse;
      applyImpulse(m, a, b, A, B, c.rA, c.rB, impulse * m.normal);
    }
  }
}

}  // namespace tumble::physics
