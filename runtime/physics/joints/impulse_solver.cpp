// The impulse joint solver: joints by sequential impulses inside the
// contact solver (after Catto's "soft step" in Box2D v3 and Jolt's
// constraint parts). Each joint type's rows are in its own file
// (ball_joint.cpp, hinge_joint.cpp, cone_twist_joint.cpp, fixed_joint.cpp);
// this file runs them.
//
// ---- What runs when ---------------------------------------------------------
// World::step calls this through the ConstraintSolver hook (constraint_solver.h):
// prepare once per step (bodies, masses, inverse world inertia at the start
// of the step, as the contact rows take them), then in every substep of
// length h: warm start (apply last substep's accumulated impulses), one
// sweep before each of the contacts' solve sweeps (with position feedback)
// and one over the contacts' push-out velocities after each ("Push-out"
// below), positions integrated, one sweep before each relax sweep (no
// feedback).
// Joints and contacts thus see each other's impulses within a substep: a
// limb pressed into the ground by its neighbours is held by the contact, not
// by a stretched joint.
//
// ---- Rows ---------------------------------------------------------------------
// Anchors and frames are taken from the bodies' current poses in every solve
// phase (rA = qA localAnchorA, ...), so the rows follow the bodies through
// the substeps. Impulses act on B, their negative on A. Every type has the
// point block (ball_joint.cpp); hinges add two alignment rows, a motor and
// angle stops (hinge_joint.cpp), cone-twists a swing row and twist stops
// (cone_twist_joint.cpp), fixed joints a 3x3 orientation block
// (fixed_joint.cpp). The sweep is the same for every type: an angular
// equality block of 0, 2 or 3 rows, the point block, and the limit rows the
// type's flags switch on.
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
//
// ---- Data layout -----------------------------------------------------------------
// A sweep runs 48 times per step (8 substeps x (4 solve + 2 relax)), the
// geometry changes only twice per substep (before the solve sweeps, and
// after the positions moved, before the relax sweeps). So refreshGeometry
// computes per joint everything a sweep needs from the poses: anchor
// offsets, the point error, (K + gamma)^-1 of the point block, IA^-1 [rA]x
// and IB^-1 [rB]x (the angular change per point impulse), each angular row's
// axis with IA^-1 axis and IB^-1 axis, the angular block's inverse, the
// angles. A sweep then reads only the Joint and the velocities, all 4-wide
// (w = 0) like the contact rows, and applies an impulse with packed
// multiply-adds instead of 3x3 products, cross products and quaternion
// rotations. Before (perf, ragdolls_100, 1000 joints): solve 27 % of
// Tumble's time, refreshGeometry 14 % (sideOf, atan2), the Eigen 3x3
// products called out of line 3 %. A joint whose bodies have not moved
// keeps its rows (kGeometryTolerance below). After both, with the contact
// solver's one-sided rows and the World's cheaper bookkeeping
// (tumble_bench_ragdolls sleep:0/rolling:0, CPU time per step): 7.8 ms ->
// 5.0 ms, joint error unchanged.
// Tried and dropped (no measurable gain, 3 interleaved runs): splitting the
// Joint into hot rows, cold setup and a separate hinge block (928 -> ~530
// bytes a joint); sorting the joints into levels that share no body (the
// same results, to break the chain of velocity loads and stores between
// consecutive joints of a rag-doll). Rejected: refreshing only before the
// solve sweeps and relaxing with those rows (faster, but a 10-link chain's
// joint error grew from 0.70 to 0.83 mm).
#include "physics/internal/impulse_joints.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/internal/joint_types.h"
#include "physics/joints/joint_system.h"
#include "physics/world.h"

namespace tumble::physics {

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
  m_joints.clear();  // keeps its capacity: no allocation once warm
  m_system.solveOrder(m_order);
  for (std::uint32_t slot : m_order) {
    const JointId id{slot, m_system.generationOf(slot)};
    const JointDef& d = m_system.jointDef(id);
    if (id.index >= m_accum.size()) m_accum.resize(id.index + 1), m_out.resize(id.index + 1);
    Accum& acc = m_accum[id.index];
    if (acc.generation != id.generation) acc = Accum{}, acc.generation = id.generation;
    if (!world.isValid(d.bodyA) || (!d.bodyB.isNull() && !world.isValid(d.bodyB))) continue;
    Joint& j = m_joints.emplace_back();
    j.def = &d;
    j.slot = id.index;
    j.type = d.type;
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
      m_joints.pop_back();
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
    if (const JointTypeRows& rows = jointTypeRows(d.type); rows.impulseSetup) rows.impulseSetup(j, d, m_h);
  }
}

namespace {

/// A joint's rows are recomputed only when one of its bodies moved by more
/// than this since they were last computed: kGeometryTolerance m, or a
/// quaternion change of kGeometryTolerance (a rotation of about twice that
/// in rad, which moves a 0.5 m anchor arm by 1e-5 m). The rows are rebuilt
/// every step (prepare), so a skipped joint's rows are at most one step old
/// and off by at most that much; the contact rows are computed once per step
/// regardless. What it saves: bodies at rest (a settled pile with sleeping
/// off, a resting rag-doll before it sleeps) cost one refresh per step
/// instead of two per substep.
constexpr Real kGeometryTolerance = Real(1e-5);

bool movedSince(const Body& b, const Vec3& position, const Quat& orientation) {
  constexpr Real tol2 = kGeometryTolerance * kGeometryTolerance;
  return (b.position_m - position).squaredNorm() > tol2 ||
         (b.orientation.coeffs() - orientation.coeffs()).squaredNorm() > tol2;
}

}  // namespace

void ImpulseJoints::refreshGeometry(const Body* bodies) {
  for (Joint& j : m_joints) {
    const JointDef& d = *j.def;
    const Body& A = bodies[j.a];
    if (j.geometryValid && !movedSince(A, j.refPositionA_m, j.refOrientationA) &&
        (j.world || !movedSince(bodies[j.b], j.refPositionB_m, j.refOrientationB)))
      continue;
    j.geometryValid = true;
    j.refPositionA_m = A.position_m;
    j.refOrientationA = A.orientation;
    // The inverse world inertia as of these poses (the World refreshes it
    // for turning bodies in every substep; see world_step.cpp).
    if (j.movesA) j.iA = A.invInertiaWorld;
    if (!j.world && j.movesB) j.iB = bodies[j.b].invInertiaWorld;
    if (!j.world) j.refPositionB_m = bodies[j.b].position_m, j.refOrientationB = bodies[j.b].orientation;
    // The two sides: anchor offsets, anchor points, joint frames (world).
    const Vec3 rA = A.orientation * d.localAnchorA_m;
    const Vec3 pA = A.position_m + rA;
    const Quat qa = A.orientation * d.localFrameA;
    Vec3 rB = Vec3::Zero(), pB = d.localAnchorB_m;
    Quat qb = d.localFrameB;
    if (!j.world) {
      const Body& B = bodies[j.b];
      rB = B.orientation * d.localAnchorB_m;
      pB = B.position_m + rB;
      qb = B.orientation * d.localFrameB;
    }
    impulsePointRows(j, rA, rB, pA, pB);
    // The type's angular rows.
    j.angularRows = 0;
    const bool angularRows = !(j.soft && j.angularFree);
    const Real gamma = j.soft ? j.gammaAng : 0;
    if (const JointTypeRows& rows = jointTypeRows(j.type); rows.impulseGeometry)
      rows.impulseGeometry(j, qa, qb, angularRows, gamma);
  }
}

void ImpulseJoints::warmStart(SolverVelocity* vel, const Body* bodies) {
  // The accumulated impulses of the last substep, along the rows' current
  // directions (anchors and axes from the poses now). Positions do not
  // change until the solve sweeps are done, so the geometry computed here
  // serves them too; the relax sweeps (after the positions moved) refresh it.
  refreshGeometry(bodies);
  m_relaxing = false;
  for (const Joint& j : m_joints) {
    const Accum& acc = m_accum[j.slot];
    const Vec3 L3 = narrow(jointTypeRows(j.type).impulseWarmStartAngular(j, acc));
    const Vec4r& P = acc.linear;
    if (j.movesA) {
      vel[j.a].linear -= j.mA * P;
      vel[j.a].angular -= j.MA * P + wide(Vec3(j.iA * L3));
    }
    if (j.movesB) {
      vel[j.b].linear += j.mB * P;
      vel[j.b].angular += j.MB * P + wide(Vec3(j.iB * L3));
    }
  }
}

Real ImpulseJoints::solve(SolverVelocity* vel, const Body* bodies, bool useBias) {
  if (!useBias && !m_relaxing) refreshGeometry(bodies), m_relaxing = true;  // positions moved
  if (useBias) m_relaxing = false;
  // Hard rows: soft position correction in the solve sweeps, none in the relax sweeps.
  const Real hardMs = useBias ? m_massScale : 1, hardIs = useBias ? m_impulseScale : 0,
             hardBias = useBias ? m_biasRate : 0;
  const Real h = m_h, invH = m_invH, biasRate = m_biasRate, massScale = m_massScale, impulseScale = m_impulseScale;
  Real change = 0, total = 0;
  // The vector rows' squares are summed lane by lane and reduced once at
  // the end (two horizontal sums less per joint and sweep).
  Vec4r changeV = Vec4r::Zero(), totalV = Vec4r::Zero();
  for (const Joint& j : m_joints) {
    Accum& acc = m_accum[j.slot];
    Vec4r vA = Vec4r::Zero(), wA = Vec4r::Zero(), vB = Vec4r::Zero(), wB = Vec4r::Zero();
    if (j.movesA) vA = vel[j.a].linear, wA = vel[j.a].angular;
    if (j.movesB) vB = vel[j.b].linear, wB = vel[j.b].angular;

    // One inequality row about sign * n (impulse +sign n lambda on B),
    // lambda >= 0; nA, nB = IA^-1 n, IB^-1 n; k = n.(IA^-1 + IB^-1) n.
    auto limit = [&](const Vec4r& n, const Vec4r& nA, const Vec4r& nB, Real sign, Real k, Real C, Real& accRow) {
      if (!(k > 0)) return;
      const Real cdot = sign * (wB - wA).dot(n);
      // Ahead of its stop and not closing the gap within this substep: no
      // impulse (the speculative row would compute zero), none to take back.
      if (C > 0 && accRow == 0 && cdot * h + C >= 0) return;
      Real bias = 0, ms = 1, is = 0;
      if (C > 0) bias = C * invH;  // speculative: may close the gap in this substep
      else if (useBias) bias = biasRate * C, ms = massScale, is = impulseScale;
      Real d = -ms * (cdot + bias) / k - is * accRow;
      const Real next = std::max(accRow + d, Real(0));
      d = next - accRow;
      accRow = next;
      wA -= nA * (sign * d);
      wB += nB * (sign * d);
      change += d * d;
      total += accRow * accRow;
    };
    // The two stops about the limit axis (hinge angle or twist). Mostly both
    // are idle: inside the range, nothing accumulated, and not closing
    // either gap within this substep. That case is tested with one dot
    // product and one well-predicted branch; it is exactly the case in which
    // each limit() call would return at once, so the result is the same.
    auto stops = [&](Real k) {
      const Real cLower = j.angle - j.lower_rad, cUpper = j.upper_rad - j.angle;
      if (acc.lower == 0 && acc.upper == 0 && cLower > 0 && cUpper > 0) {
        const Real travel = (wB - wA).dot(j.limitAxis) * h;  // this substep's angle change, rad
        if (travel + cLower >= 0 && cUpper - travel >= 0) return;
      }
      limit(j.limitAxis, j.limitA, j.limitB, 1, k, cLower, acc.lower);
      limit(j.limitAxis, j.limitA, j.limitB, -1, k, cUpper, acc.upper);
    };

    // Motor and limits first, the equality rows last (they matter most).
    // Which of them a joint has is set by its type (impulseSetup): a hinge
    // the motor and the stops, a cone-twist the swing row and the stops.
    // The rows' data (limitK and on) is read only by joints that have them.
    if (j.motor && j.limitK > 0) {
      const Real k = j.limitK;
      const Real cdot = (wB - wA).dot(j.limitAxis) - j.motorSpeed_radps;
      const Real maxI = j.maxMotorImpulse;
      Real dl = -cdot / k;
      const Real next = std::clamp(acc.motor + dl, -maxI, maxI);
      dl = next - acc.motor;
      acc.motor = next;
      wA -= j.limitA * dl;
      wB += j.limitB * dl;
      change += dl * dl;
      total += acc.motor * acc.motor;
    }
    if (j.swingRow) {
      // Rotating a1 towards b1 is positive about the swing axis: the row pushes back.
      if (j.swingActive)
        limit(j.swingAxis, j.swingA, j.swingB, -1, j.swingK, j.swingLimit_rad - j.swingAngle, acc.swing);
      else
        acc.swing = 0;
    }
    if (j.stops) stops(j.limitK);

    const bool hardRows = !j.soft;
    const Real ms = hardRows ? hardMs : 1, is = hardRows ? hardIs : 0;
    // Angular equality rows (hinge alignment, fixed orientation): one block.
    if (j.angularRows > 0) {
      const Real bias = hardRows ? hardBias : j.betaAng * invH;
      const Real gamma = hardRows ? 0 : j.gammaAng;
      const Vec4r dw = wB - wA;
      Vec4r accK = Vec4r::Zero(), rhs = Vec4r::Zero();
      for (int k = 0; k < j.angularRows; ++k) {
        accK[k] = acc.angular.dot(j.ax[k]);
        rhs[k] = dw.dot(j.ax[k]);
      }
      rhs += bias * j.angC + gamma * accK;
      const Vec4r dl = -ms * (j.angKinv * rhs) - is * accK;
      for (int k = 0; k < j.angularRows; ++k) {
        acc.angular += j.ax[k] * dl[k];
        wA -= j.axA[k] * dl[k];
        wB += j.axB[k] * dl[k];
      }
      changeV += dl.cwiseAbs2();
      totalV += acc.angular.cwiseAbs2();
    }

    // Point rows (every type).
    if (j.pointOk) {
      const Real g = hardRows ? 0 : j.gammaLin;
      const Real pbias = hardRows ? hardBias : j.betaLin * invH;
      const Vec4r cdot = vB - vA + j.SA * wA - j.SB * wB;  // vB + wB x rB - vA - wA x rA
      const Vec4r rhs = cdot + pbias * j.C + g * acc.linear;
      const Vec4r P = -ms * (j.pointKinv * rhs) - is * acc.linear;
      acc.linear += P;
      vA -= j.mA * P;
      wA -= j.MA * P;
      vB += j.mB * P;
      wB += j.MB * P;
      changeV += P.cwiseAbs2();
      totalV += acc.linear.cwiseAbs2();
    }
    if (j.movesA) vel[j.a].linear = vA, vel[j.a].angular = wA;
    if (j.movesB) vel[j.b].linear = vB, vel[j.b].angular = wB;
  }
  change += changeV.sum();
  total += totalV.sum();
  if (change == 0) return 0;
  return change / std::max(total, std::numeric_limits<Real>::min());
}

// ---- Push-out ----------------------------------------------------------------
// The contacts remove overlap with split-impulse pseudo-velocities that move
// the positions in this substep and are then dropped (contact_solver.cpp).
// When the joints never saw them, a limb pushed out of the ground moved
// without the part it hangs on, and the joint opened by the push; more
// substeps push out faster than the joints' feedback closes, so it grew
// with them: a rag-doll dropped flat from 0.3 m (tests/physics/joints/
// ragdoll_test.cpp) opened a joint by 2.2, 4.0, 6.6 and 11.3 mm at 4, 8, 16
// and 32 substeps. So after each contact solve sweep (which adds to the
// push-out), the hard equality rows (the point block and the angular block;
// springs are forces, and limits keep what the push gives them) sweep the
// push-out velocities too, with the solve phase's rows and no bias: one
// Gauss-Seidel iteration over contacts and joints together, whose contact
// rows push (never pull) and whose joint rows keep the parts together. The
// jointed parts are then pushed out together. The Lagrange solver projects
// the push-out once, with its factorization (JointSystem::substepProjectPushout).
void ImpulseJoints::solvePushout(SolverVelocity* pseudo) {
  // Equality rows need no accumulated impulse: each sweep's change is
  // found from the velocities alone (no clamping, no warm start).
  for (const Joint& j : m_joints) {
    if (j.soft) continue;
    Vec4r vA = Vec4r::Zero(), wA = Vec4r::Zero(), vB = Vec4r::Zero(), wB = Vec4r::Zero();
    if (j.movesA) vA = pseudo[j.a].linear, wA = pseudo[j.a].angular;
    if (j.movesB) vB = pseudo[j.b].linear, wB = pseudo[j.b].angular;
    if (vA == Vec4r::Zero() && wA == Vec4r::Zero() && vB == Vec4r::Zero() && wB == Vec4r::Zero())
      continue;  // nothing pushed either part: every row's change is 0
    if (j.angularRows > 0) {
      const Vec4r dw = wB - wA;
      Vec4r rhs = Vec4r::Zero();
      for (int r = 0; r < j.angularRows; ++r) rhs[r] = dw.dot(j.ax[r]);
      const Vec4r dl = -(j.angKinv * rhs);
      for (int r = 0; r < j.angularRows; ++r) {
        wA -= j.axA[r] * dl[r];
        wB += j.axB[r] * dl[r];
      }
    }
    if (j.pointOk) {
      const Vec4r P = -(j.pointKinv * (vB - vA + j.SA * wA - j.SB * wB));
      vA -= j.mA * P;
      wA -= j.MA * P;
      vB += j.mB * P;
      wB += j.MB * P;
    }
    if (j.movesA) pseudo[j.a].linear = vA, pseudo[j.a].angular = wA;
    if (j.movesB) pseudo[j.b].linear = vB, pseudo[j.b].angular = wB;
  }
}

void ImpulseJoints::finish(const World&) {
  for (const Joint& j : m_joints) {
    const JointDef& d = *j.def;
    const Accum& acc = m_accum[j.slot];
    Output& o = m_out[j.slot];
    o.generation = acc.generation;
    o.force_N = narrow(acc.linear) * m_invH;
    o.torque_Nm = narrow(jointTypeRows(j.type).impulseReportedAngular(j, acc)) * m_invH;
    if ((d.breakForce_N > 0 && o.force_N.norm() > d.breakForce_N) ||
        (d.breakTorque_Nm > 0 && o.torque_Nm.norm() > d.breakTorque_Nm))
      o.broken = true;
  }
}

}  // namespace tumble::physics
