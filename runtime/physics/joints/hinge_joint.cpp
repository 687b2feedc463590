// Hinge joint: the point rows (ball_joint.cpp), two rows keeping the hinge
// axes aligned, optional angle limits and a motor. The joint frames' +X axes
// are the hinge axis; the angle is that of B's frame relative to A's about
// A's +X, from +Y: theta = atan2(b2.a3, b2.a2) (a_i, b_i the frames' axes in
// the world).
//
// Lagrange multipliers:
//   alignment, two "axis" rows (n a unit axis fixed in A, C an angle error
//     about n; J_a = [ 0  n^T ], J_b = [ 0  -n^T ], J' q' = (w_a x n).(w_a - w_b)):
//     n = -a3, C = a2.b1 and n = a2, C = a3.b1 (the +X axes stay aligned).
//   angle limit, one inequality row each, active while violated:
//     C = theta - lower >= 0 or upper - theta >= 0, theta' = a1.(w_b - w_a),
//     J' q' ~ (w_a x a1).(w_b - w_a) (approximate: a limit row only has to
//     push back, Baumgarte absorbs the rest).
//   motor: not a row. An explicit servo torque tau = clamp(I_axial k_d
//     (speed - rate), +-maxTorque) about the hinge axis joins Q, on B (and
//     -tau on A), I_axial = 1 / (a1.(IA^-1 + IB^-1) a1): the rate reaches the
//     target with the Baumgarte time constant 1/k_d unless the torque
//     saturates. A bounded row would need a second active set; the impulse
//     solver does have the exact bounded row.
//
// Impulses (on B, their negative on A):
//   alignment (2 rows, one 2x2 block), b2, b3 = B's frame axes normal to its
//     hinge axis: C_k = a1.b_k, v_k = b_k x a1, Cdot_k = (wB - wA).v_k,
//     K_ij = v_i.(IA^-1 + IB^-1) v_j.
//   angle limits, one row each, lambda >= 0, about a1: C >= 0,
//     Cdot = +-(wB - wA).a1.
//   motor (1 row): Cdot = (wB - wA).a1 - motorSpeed, |lambda| <= maxTorque h.
#include <algorithm>
#include <cmath>

#include "physics/internal/joint_types.h"

namespace tumble::physics {
namespace {

using lagrange::JointPose, lagrange::M3, lagrange::RowBuilder, lagrange::V3;

double hingeAngle(const M3& FA, const M3& FB) { return std::atan2(FB.col(1).dot(FA.col(2)), FB.col(1).dot(FA.col(1))); }

void lagrangeAlignment(RowBuilder& rb, const JointPose& pa, const JointPose& pb) {
  const V3 a2 = pa.F.col(1), a3 = pa.F.col(2);
  const V3 b1 = pb.F.col(0);
  rb.axis(-a3, a2.dot(b1)), rb.axis(a2, a3.dot(b1));
}

void lagrangeLimits(RowBuilder& rb, const JointDef& d, const JointPose& pa, const JointPose& pb) {
  if (!d.enableLimit) return;
  const V3 a1 = pa.F.col(0);
  const double theta = hingeAngle(pa.F, pb.F);
  if (theta < d.lowerAngle_rad) rb.angleLimit(a1, theta - d.lowerAngle_rad, +1, rb.wa());
  if (theta > d.upperAngle_rad) rb.angleLimit(a1, d.upperAngle_rad - theta, -1, rb.wa());
}

void lagrangeMotor(const JointDef& d, lagrange::BodyState* A, lagrange::BodyState* B, const JointSettings& js) {
  if (!d.enableMotor) return;
  const V3 a1 = lagrange::poseOf(d.localAnchorA_m, d.localFrameA, A).F.col(0);
  const V3 wA = A ? A->w : V3::Zero(), wB = B ? B->w : V3::Zero();
  const double kinv = a1.dot(((A ? A->invI : M3::Zero()) + (B ? B->invI : M3::Zero())) * a1);
  if (!(kinv > 0)) return;
  const double maxT = d.maxMotorTorque_Nm;
  const double tau = std::clamp((d.motorSpeed_radps - (wB - wA).dot(a1)) / kinv * js.damping_per_s, -maxT, maxT);
  // In Q (the rows see it; integrateFree integrates Q) and in Tm, which
  // applyConstraintForces applies with the constraint torque.
  if (A && A->dynamic) A->Qt -= tau * a1, A->Tm -= tau * a1;
  if (B && B->dynamic) B->Qt += tau * a1, B->Tm += tau * a1;
}

void impulseSetup(ImpulseJoints::Joint& j, const JointDef& d, Real h) {
  j.motor = d.enableMotor;
  j.stops = d.enableLimit;
  j.lower_rad = d.lowerAngle_rad;
  j.upper_rad = d.upperAngle_rad;
  j.motorSpeed_radps = d.motorSpeed_radps;
  j.maxMotorImpulse = d.maxMotorTorque_Nm * h;
}

void impulseGeometry(ImpulseJoints::Joint& j, const Quat& qa, const Quat& qb, bool angularRows, Real gamma) {
  const Mat3 FA = qa.toRotationMatrix(), FB = qb.toRotationMatrix();
  const Vec3 a1 = FA.col(0);
  setLimitAxis(j, a1);
  j.angle = std::atan2(FB.col(1).dot(FA.col(2)), FB.col(1).dot(FA.col(1)));
  if (!angularRows) return;
  // Alignment: C_k = a1.b_k, v_k = b_k x a1 (b_2, b_3: B's axes normal to its hinge axis).
  setAngularAxis(j, 0, FB.col(1).cross(a1));
  setAngularAxis(j, 1, FB.col(2).cross(a1));
  Eigen::Matrix<Real, 2, 2> K2;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) K2(r, c) = j.ax[r].dot(j.axA[c] + j.axB[c]) + (r == c ? gamma : 0);
  if (std::abs(K2.determinant()) > Real(1e-12)) {
    j.angularRows = 2;
    j.angKinv.setZero();
    j.angKinv.topLeftCorner<2, 2>() = K2.inverse();
    j.angC = Vec4r(a1.dot(FB.col(1)), a1.dot(FB.col(2)), 0, 0);
  }
}

Vec4r warmStartAngular(const ImpulseJoints::Joint& j, const ImpulseJoints::Accum& acc) {
  Vec4r L = acc.angular;
  L += j.limitAxis * (acc.lower - acc.upper + acc.motor);
  return L;
}

Vec4r reportedAngular(const ImpulseJoints::Joint& j, const ImpulseJoints::Accum& acc) {
  Vec4r L = acc.angular + j.limitAxis * (acc.lower - acc.upper);
  L += j.limitAxis * acc.motor;
  return L;
}

}  // namespace

const JointTypeRows kHingeJointRows{
    "hinge",        lagrangeAlignment, lagrangeLimits,   lagrangeMotor,   hingeAngle,
    impulseSetup, impulseGeometry,   warmStartAngular, reportedAngular,
};

}  // namespace tumble::physics
