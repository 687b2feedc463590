// Joints by sequential impulses inside the contact solver (issue 4,
// formulation B; after Catto's "soft step" in Box2D v3 and Jolt's
// constraint parts).
//
// ---- What runs when ---------------------------------------------------------
// World::step calls this through the ConstraintSolver hook (constraint_solver.h):
// prepare once per step (bodies, masses, inverse world inertia at the start
// of the step, as the contact rows take them), then in every substep of
// length h: warm start (apply last substep's accumulated impulses), one
// sweep before each of the contacts' solve sweeps (with position feedback),
// positions integrated, one sweep before each relax sweep (no feedback).
// Joints and contacts thus see each other's impulses within a substep: a
// limb pressed into the ground by its neighbours is held by the contact, not
// by a stretched joint (what formulation A cannot do, its forces being fixed
// before the contacts are solved).
//
// ---- Rows ---------------------------------------------------------------------
// Anchors and frames are taken from the bodies' current poses in every sweep
// (rA = qA localAnchorA, ...), so the rows follow the bodies through the substeps.
// Impulses act on B, their negative on A. With vA, wA, vB, wB the velocities:
//   point (3 rows, one 3x3 block):  C = pB - pA,
//     Cdot = vB + wB x rB - vA - wA x rA,
//     K = (mA + mB) 1 - [rA] IA^-1 [rA] - [rB] IB^-1 [rB]   ([r] = cross matrix).
//   hinge alignment (2 rows, one 2x2 block), a1 = A's hinge axis, b2, b3 =
//     B's frame axes normal to its hinge axis: C_k = a1.b_k, v_k = b_k x a1,
//     Cdot_k = (wB - wA).v_k, K_ij = v_i.(IA^-1 + IB^-1) v_j.
//   fixed orientation (3 rows, 3x3 block): C = 2 vec(qB qA^-1) (frames;
//     the small-angle rotation vector), Cdot = wB - wA, K = IA^-1 + IB^-1.
//   angle limits, one row each, lambda >= 0 (hinge angle about a1; twist about
//     the bisector of the twist axes; swing about n = a1 x b1 / |a1 x b1|,
//     C = swingLimit - acos(a1.b1)): C >= 0, Cdot = +-(wB - wA).n.
//   hinge motor (1 row): Cdot = (wB - wA).a1 - motorSpeed, |lambda| <= maxTorque h.
//
// ---- Soft constraints ----------------------------------------------------------
// Hard rows correct position error softly (Box2D v3's b2MakeSoft): with
// omega = 2 pi f, zeta, substep h:  a1 = 2 zeta + h omega, a2 = h omega a1,
// a3 = 1 / (1 + a2); bias = (omega / a1) C, massScale = a2 a3,
// impulseScale = a3, and
//   dlambda = -massScale K^-1 (Cdot + bias) - impulseScale lambda_acc.
// This is a damped spring on the error that stays stable at any mass ratio
// (the implicit-Euler step of the spring), unlike Baumgarte's C / h. The
// relax sweeps use bias 0, massScale 1, impulseScale 0: the position error's
// correction velocity is removed again, so it does not turn into motion.
// Default 120 Hz, zeta 2 at the 480 Hz substeps (Box2D v3 uses 60 Hz; its
// steady sag under load, (impulseScale / massScale) K lambda / biasRate,
// left a hanging 10-link chain's top joint 1.3 mm open; at 120 Hz 0.3 mm),
// at most a quarter of the substep rate. Limits ahead of their stop use the
// speculative bias C / h (they may close the gap in this substep, not more).
// Springs (JointDef stiffness k and damping c) are the same soft row with
// physical gains (Catto, "Soft constraints", GDC 2011):
//   gamma = 1 / (h (c + h k)),  beta = h k / (c + h k),
//   dlambda = -(K + gamma)^-1 (Cdot + beta / h C + gamma lambda_acc),
// applied in every sweep (the spring is a real force, not an error correction).
//
// ---- Warm starting, breaking ---------------------------------------------------
// Accumulated impulses are per substep and are kept between substeps and
// steps (per joint slot; a new joint in a reused slot starts from zero).
// The constraint force is the accumulated impulse of the last substep / h:
// that is what breakForce_N and breakTorque_Nm are compared with, once per
// step (finish); the JointSystem removes a broken joint before the next step.
#include "physics/internal/impulse_joints.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/internal/contact_solver.h"
#include "physics/joints/joint_system.h"
#include "physics/world.h"

namespace tumble::physics {

namespace {

using Side = ImpulseJoints::Side;

Side sideOf(const Body* b, const Vec3& localAnchor, const Quat& localFrame) {
  Side s;
  if (!b) {
    s.p = localAnchor;
    s.q = localFrame;
  } else {
    s.r = b->orientation * localAnchor;
    s.p = b->position_m + s.r;
    s.q = b->orientation * localFrame;
  }
  s.F = s.q.toRotationMatrix();
  return s;
}

Real hingeAngle(const Mat3& FA, const Mat3& FB) {
  return std::atan2(FB.col(1).dot(FA.col(2)), FB.col(1).dot(FA.col(1)));
}
Real twistAngle(const Quat& qa, const Quat& qb) {
  const Quat rel = qa.conjugate() * qb;  // B's frame in A's frame
  Real t = 2 * std::atan2(rel.x(), rel.w());
  if (t > kPi) t -= 2 * kPi;
  if (t < -kPi) t += 2 * kPi;
  return t;
}

/// Velocities of the two sides (the world's are zero), written back by store().
struct Vel {
  Vec3 vA = Vec3::Zero(), wA = Vec3::Zero(), vB = Vec3::Zero(), wB = Vec3::Zero();
};

}  // namespace

ImpulseJoints::ImpulseJoints(const JointSystem& joints, double hertz, double dampingRatio)
    : m_system(joints), m_hertz(hertz), m_zeta(dampingRatio) {}

void ImpulseJoints::clearBroken() {
  for (Output& o : m_out) o.broken = false;
}

void ImpulseJoints::prepare(const World& world, Real dt_s, int substeps) {
  m_h = dt_s / Real(std::max(1, substeps));
  m_invH = 1 / m_h;
  // At most a quarter of the substep rate (120 Hz at 8 substeps of 1/60
  // s), so that h omega stays below pi/2 when fewer substeps are asked for.
  const double omega = 2 * M_PI * std::min(m_hertz, 0.25 / double(m_h)), a1 = 2 * m_zeta + m_h * omega, a2 = m_h * omega * a1,
               a3 = 1 / (1 + a2);
  m_biasRate = Real(omega / a1);
  m_massScale = Real(a2 * a3);
  m_impulseScale = Real(a3);
  m_joints.clear();
  m_system.solveOrder(m_order);
  for (std::uint32_t slot : m_order) {
    const JointId id{slot, m_system.generationOf(slot)};
    const JointDef& d = m_system.jointDef(id);
    if (id.index >= m_accum.size()) m_accum.resize(id.index + 1), m_out.resize(id.index + 1);
    Accum& acc = m_accum[id.index];
    if (acc.generation != id.generation) acc = Accum{}, acc.generation = id.generation;
    if (!world.isValid(d.bodyA) || (!d.bodyB.isNull() && !world.isValid(d.bodyB))) continue;
    Joint j;
    j.def = &d;
    j.slot = id.index;
    j.a = d.bodyA.index;
    const Body& A = world.body(d.bodyA);
    j.movesA = A.isDynamic() && A.awake;
    if (j.movesA) j.mA = A.invMass_per_kg, j.iA = A.invInertiaWorld;
    j.world = d.bodyB.isNull();
    if (!j.world) {
      j.b = d.bodyB.index;
      const Body& B = world.body(d.bodyB);
      j.movesB = B.isDynamic() && B.awake;
      if (j.movesB) j.mB = B.invMass_per_kg, j.iB = B.invInertiaWorld;
    }
    if (!j.movesA && !j.movesB) {
      acc.linear.setZero(), acc.angular.setZero();  // asleep: nothing to warm start
      acc.lower = acc.upper = acc.swing = acc.motor = 0;
      continue;
    }
    j.soft = d.linearStiffness_Npm > 0;
    if (j.soft) {
      const Real h = m_h;
      auto gains = [h](Real k, Real c, Real& gamma, Real& beta) {
        const Real s = c + h * k;
        gamma = s > 0 ? 1 / (h * s) : 0;
        beta = s > 0 ? h * k / s : 0;
      };
      gains(d.linearStiffness_Npm, d.linearDamping_Nspm, j.gammaLin, j.betaLin);
      gains(d.angularStiffness_Nmprad, d.angularDamping_Nmsprad, j.gammaAng, j.betaAng);
      j.angularFree = !(d.angularStiffness_Nmprad > 0 || d.angularDamping_Nmsprad > 0);
    }
    m_joints.push_back(j);
  }
}

namespace {

struct Ctx {
  const ImpulseJoints::Joint& j;
  Vel& v;
  Real& change;  ///< sum of squared impulse changes
  Real& total;   ///< sum of squared accumulated impulses
  // Inlined by hand (always_inline): three calls per joint and sweep, in
  // the hot loop; as calls they cost 8% of ragdolls_100 (perf).
  [[gnu::always_inline]] void linear(const Side& sa, const Side& sb, const Vec3& P) {
    v.vA -= j.mA * P;
    v.wA -= j.iA * sa.r.cross(P);
    v.vB += j.mB * P;
    v.wB += j.iB * sb.r.cross(P);
  }
  [[gnu::always_inline]] void angular(const Vec3& L) {
    v.wA -= j.iA * L;
    v.wB += j.iB * L;
  }
  /// One inequality row about axis n (impulse +n lambda on B), lambda >= 0.
  [[gnu::always_inline]] void limit(const Vec3& n, Real k, Real C, Real cdot, Real& acc, bool useBias, Real invH,
                                    Real biasRate, Real massScale, Real impulseScale) {
    if (!(k > 0)) return;
    // Ahead of its stop and not closing the gap within this substep: no
    // impulse (the speculative row would compute zero), none to take back.
    if (C > 0 && acc == 0 && cdot * (1 / invH) + C >= 0) return;
    Real bias = 0, ms = 1, is = 0;
    if (C > 0) bias = C * invH;  // speculative: may close the gap in this substep
    else if (useBias) bias = biasRate * C, ms = massScale, is = impulseScale;
    Real d = -ms * (cdot + bias) / k - is * acc;
    const Real next = std::max(acc + d, Real(0));
    d = next - acc;
    acc = next;
    angular(n * d);
    change += d * d;
    total += acc * acc;
  }
};

}  // namespace

void ImpulseJoints::refreshGeometry(const Body* bodies) {
  for (Joint& j : m_joints) {
    const JointDef& d = *j.def;
    j.sa = sideOf(&bodies[j.a], d.localAnchorA_m, d.localFrameA);
    j.sb = sideOf(j.world ? nullptr : &bodies[j.b], d.localAnchorB_m, d.localFrameB);
    const Mat3 SA = skew(j.sa.r), SB = skew(j.sb.r);
    Mat3 K = (j.mA + j.mB) * Mat3::Identity() - SA * j.iA * SA - SB * j.iB * SB;
    if (j.soft) K.diagonal().array() += j.gammaLin;
    j.pointKinv = K.inverse();
    j.pointOk = j.pointKinv.allFinite();
    // Limit rows: angles, axes and effective masses of this phase.
    const Mat3 iAB = j.iA + j.iB;
    const Vec3 a1 = j.sa.F.col(0), b1 = j.sb.F.col(0);
    if (d.type == JointType::Hinge) {
      j.limitAxis = a1;
      j.angle = hingeAngle(j.sa.F, j.sb.F);
    } else if (d.type == JointType::ConeTwist) {
      const Vec3 axb = a1.cross(b1);
      const Real sn = axb.norm();
      j.swingAngle = std::atan2(sn, a1.dot(b1));
      j.swingActive = sn > Real(1e-6) && j.swingAngle > Real(0.5) * d.swingLimit_rad;
      if (j.swingActive) j.swingAxis = axb / sn, j.swingK = j.swingAxis.dot(iAB * j.swingAxis);
      Vec3 n = a1 + b1;
      j.limitAxis = n.squaredNorm() > Real(1e-12) ? Vec3(n.normalized()) : a1;
      j.angle = twistAngle(j.sa.q, j.sb.q);
    }
    j.limitK = j.limitAxis.dot(iAB * j.limitAxis);
  }
}

void ImpulseJoints::warmStart(SolverVelocity* vel, const Body* bodies) {
  // The accumulated impulses of the last substep, along the rows' current
  // directions (anchors and axes from the poses now). Positions do not
  // change until the solve sweeps are done, so the geometry computed here
  // serves them too; the relax sweeps (after the positions moved) refresh it.
  refreshGeometry(bodies);
  m_relaxing = false;
  for (Joint& j : m_joints) {
    const JointDef& d = *j.def;
    const Accum& acc = m_accum[j.slot];
    Vel v;
    if (j.movesA) v.vA = narrow(vel[j.a].linear), v.wA = narrow(vel[j.a].angular);
    if (j.movesB) v.vB = narrow(vel[j.b].linear), v.wB = narrow(vel[j.b].angular);
    const Side& sa = j.sa;
    const Side& sb = j.sb;
    Real change = 0, total = 0;
    Ctx x{j, v, change, total};
    x.linear(sa, sb, acc.linear);
    Vec3 L = acc.angular;
    const Vec3 a1 = sa.F.col(0), b1 = sb.F.col(0);
    if (d.type == JointType::Hinge) L += a1 * (acc.lower - acc.upper + acc.motor);
    if (d.type == JointType::ConeTwist) {
      Vec3 n = a1 + b1;
      n = n.squaredNorm() > Real(1e-12) ? Vec3(n.normalized()) : a1;
      L += n * (acc.lower - acc.upper);
      const Vec3 axb = a1.cross(b1);
      if (acc.swing != 0 && axb.norm() > Real(1e-6)) L -= axb.normalized() * acc.swing;
    }
    x.angular(L);
    if (j.movesA) vel[j.a].linear = wide(v.vA), vel[j.a].angular = wide(v.wA);
    if (j.movesB) vel[j.b].linear = wide(v.vB), vel[j.b].angular = wide(v.wB);
  }
}

Real ImpulseJoints::solve(SolverVelocity* vel, const Body* bodies, bool useBias) {
  if (!useBias && !m_relaxing) refreshGeometry(bodies), m_relaxing = true;  // positions moved
  if (useBias) m_relaxing = false;
  Real change = 0, total = 0;
  for (Joint& j : m_joints) {
    const JointDef& d = *j.def;
    Accum& acc = m_accum[j.slot];
    Vel v;
    if (j.movesA) v.vA = narrow(vel[j.a].linear), v.wA = narrow(vel[j.a].angular);
    if (j.movesB) v.vB = narrow(vel[j.b].linear), v.wB = narrow(vel[j.b].angular);
    const Side& sa = j.sa;
    const Side& sb = j.sb;
    Ctx x{j, v, change, total};
    const Mat3 iAB = j.iA + j.iB;
    const Vec3 a1 = sa.F.col(0);

    // Motor and limits first, the equality rows last (they matter most).
    if (d.type == JointType::Hinge) {
      const Real k = j.limitK;
      if (d.enableMotor && k > 0) {
        const Real cdot = (v.wB - v.wA).dot(a1) - d.motorSpeed_radps;
        const Real maxI = d.maxMotorTorque_Nm * m_h;
        Real dl = -cdot / k;
        const Real next = std::clamp(acc.motor + dl, -maxI, maxI);
        dl = next - acc.motor;
        acc.motor = next;
        x.angular(a1 * dl);
        change += dl * dl;
        total += acc.motor * acc.motor;
      }
      if (d.enableLimit) {
        const Real theta = j.angle;
        x.limit(a1, k, theta - d.lowerAngle_rad, (v.wB - v.wA).dot(a1), acc.lower, useBias, m_invH, m_biasRate,
                m_massScale, m_impulseScale);
        x.limit(-a1, k, d.upperAngle_rad - theta, -(v.wB - v.wA).dot(a1), acc.upper, useBias, m_invH, m_biasRate,
                m_massScale, m_impulseScale);
      }
    } else if (d.type == JointType::ConeTwist) {
      // Swing: only near the cone (far inside it the row's axis is undefined
      // and its impulse would be zero anyway).
      if (j.swingActive) {
        const Vec3& n = j.swingAxis;  // rotating a1 towards b1 is positive about n
        x.limit(-n, j.swingK, d.swingLimit_rad - j.swingAngle, -(v.wB - v.wA).dot(n), acc.swing, useBias, m_invH,
                m_biasRate, m_massScale, m_impulseScale);
      } else {
        acc.swing = 0;
      }
      const Vec3& n = j.limitAxis;
      const Real t = j.angle;
      x.limit(n, j.limitK, t - d.twistLower_rad, (v.wB - v.wA).dot(n), acc.lower, useBias, m_invH, m_biasRate,
              m_massScale, m_impulseScale);
      x.limit(-n, j.limitK, d.twistUpper_rad - t, -(v.wB - v.wA).dot(n), acc.upper, useBias, m_invH, m_biasRate,
              m_massScale, m_impulseScale);
    }

    // Angular equality rows.
    const bool hardRows = !j.soft;
    const Real ms = hardRows && useBias ? m_massScale : 1, is = hardRows && useBias ? m_impulseScale : 0;
    const Real bias = hardRows ? (useBias ? m_biasRate : 0) : j.betaAng * m_invH;
    const Real gamma = hardRows ? 0 : j.gammaAng;
    if (d.type == JointType::Hinge && !(j.soft && j.angularFree)) {
      const Vec3 vk[2] = {sb.F.col(1).cross(a1), sb.F.col(2).cross(a1)};
      const Real C[2] = {a1.dot(sb.F.col(1)), a1.dot(sb.F.col(2))};
      Eigen::Matrix<Real, 2, 2> K;
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) K(r, c) = vk[r].dot(iAB * vk[c]) + (r == c ? gamma : 0);
      const Vec3 dw = v.wB - v.wA;
      const Eigen::Matrix<Real, 2, 1> accK(acc.angular.dot(vk[0]), acc.angular.dot(vk[1]));
      Eigen::Matrix<Real, 2, 1> rhs(dw.dot(vk[0]) + bias * C[0], dw.dot(vk[1]) + bias * C[1]);
      rhs += gamma * accK;
      if (std::abs(K.determinant()) > Real(1e-12)) {
        const Eigen::Matrix<Real, 2, 1> dl = -ms * K.inverse() * rhs - is * accK;
        const Vec3 L = vk[0] * dl[0] + vk[1] * dl[1];
        acc.angular += L;
        x.angular(L);
        change += dl.squaredNorm();
        total += acc.angular.squaredNorm();
      }
    } else if (d.type == JointType::Fixed && !(j.soft && j.angularFree)) {
      Quat rel = sb.q * sa.q.conjugate();
      if (rel.w() < 0) rel.coeffs() = -rel.coeffs();
      const Vec3 C = 2 * rel.vec();
      Mat3 K = iAB;
      K.diagonal().array() += gamma;
      const Vec3 rhs = (v.wB - v.wA) + bias * C + gamma * acc.angular;
      const Mat3 Kinv = K.inverse();
      if (Kinv.allFinite()) {
        const Vec3 L = -ms * (Kinv * rhs) - is * acc.angular;
        acc.angular += L;
        x.angular(L);
        change += L.squaredNorm();
        total += acc.angular.squaredNorm();
      }
    }

    // Point rows (every type).
    {
      const Real g = hardRows ? 0 : j.gammaLin;
      const Vec3 C = sb.p - sa.p;
      const Vec3 cdot = v.vB + v.wB.cross(sb.r) - v.vA - v.wA.cross(sa.r);
      const Real pbias = hardRows ? (useBias ? m_biasRate : 0) : j.betaLin * m_invH;
      const Vec3 rhs = cdot + pbias * C + g * acc.linear;
      if (j.pointOk) {
        const Vec3 P = -ms * (j.pointKinv * rhs) - is * acc.linear;
        acc.linear += P;
        x.linear(sa, sb, P);
        change += P.squaredNorm();
        total += acc.linear.squaredNorm();
      }
    }
    if (j.movesA) vel[j.a].linear = wide(v.vA), vel[j.a].angular = wide(v.wA);
    if (j.movesB) vel[j.b].linear = wide(v.vB), vel[j.b].angular = wide(v.wB);
  }
  if (change == 0) return 0;
  return change / std::max(total, std::numeric_limits<Real>::min());
}

void ImpulseJoints::finish(const World&) {
  for (const Joint& j : m_joints) {
    const JointDef& d = *j.def;
    const Accum& acc = m_accum[j.slot];
    Output& o = m_out[j.slot];
    o.generation = acc.generation;
    o.force_N = acc.linear * m_invH;
    Vec3 L = acc.angular + j.limitAxis * (acc.lower - acc.upper);
    if (d.type == JointType::Hinge) L += j.limitAxis * acc.motor;
    if (d.type == JointType::ConeTwist) L -= j.swingAxis * acc.swing;
    o.torque_Nm = L * m_invH;
    if ((d.breakForce_N > 0 && o.force_N.norm() > d.breakForce_N) ||
        (d.breakTorque_Nm > 0 && o.torque_Nm.norm() > d.breakTorque_Nm))
      o.broken = true;
  }
}

}  // namespace tumble::physics
