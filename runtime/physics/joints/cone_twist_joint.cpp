// Cone-twist joint: the point rows (ball_joint.cpp) plus a swing cone and
// twist limits, inequality rows active when violated. Shoulders, hips, neck,
// spine. The joint frames' +X axes are the twist axes (a1 in A, b1 in B);
// swing is the angle between them, twist the rotation about them, from +Y.
//
// Lagrange multipliers:
//   cone, an angular "dot" row (u fixed in A, w fixed in B: C = u.w - c0,
//     J_a = [ 0  (u x w)^T ], J_b = [ 0  -(u x w)^T ],
//     J' q' = (w_a x (w_a x u)).w + 2 (w_a x u).(w_b x w) + u.(w_b x (w_b x w))):
//     a1.b1 - cos(swingLimit) >= 0. The row's J = u x w vanishes where u.w is
//     extreme, so only this limit uses a dot row: u.w there is
//     cos(swingLimit), far from +-1 (see "Robustness" in lagrange_substeps.cpp).
//   twist limits: the twist part of the relative rotation, about n = the
//     bisector of a1 and b1: C = theta - lower >= 0 or upper - theta >= 0,
//     theta' = n.(w_b - w_a), J' q' ~ (w_m x n).(w_b - w_a), w_m = (w_a + w_b)/2
//     (approximate: a limit row only has to push back, Baumgarte absorbs the rest).
//
// Impulses (on B, their negative on A), one row each, lambda >= 0:
//   twist about the bisector of the twist axes: C >= 0, Cdot = +-(wB - wA).n;
//   swing about n = a1 x b1 / |a1 x b1|, C = swingLimit - acos(a1.b1),
//     solved only beyond half the cone (far inside it the axis is undefined
//     and the impulse would be zero anyway).
#include <cmath>

#include "physics/internal/joint_types.h"

namespace tumble::physics {
namespace {

using lagrange::JointPose, lagrange::M3, lagrange::Qd, lagrange::RowBuilder, lagrange::V3;

/// Twist of frame B relative to frame A about A's +X (rad, in [-pi, pi]).
double twistAngle(const M3& FA, const M3& FB) {
  const Qd rel(FA.transpose() * FB);  // B's frame in A's frame
  double t = 2 * std::atan2(rel.x(), rel.w());
  if (t > M_PI) t -= 2 * M_PI;
  if (t < -M_PI) t += 2 * M_PI;
  return t;
}

/// The same for the impulse solver's frames (quaternions, world).
Real twistAngle(const Quat& qa, const Quat& qb) {
  const Quat rel = qa.conjugate() * qb;  // B's frame in A's frame
  Real t = 2 * std::atan2(rel.x(), rel.w());
  if (t > kPi) t -= 2 * kPi;
  if (t < -kPi) t += 2 * kPi;
  return t;
}

/// The rotated +X axis, q (1, 0, 0): the first column of q's matrix (a
/// third of the work of rotating a vector).
Vec3 xAxis(const Quat& q) {
  const Real x = q.x(), y = q.y(), z = q.z(), w = q.w();
  return Vec3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y));
}

double angle(const M3& FA, const M3& FB) { return twistAngle(FA, FB); }

void lagrangeLimits(RowBuilder& rb, const JointDef& d, const JointPose& pa, const JointPose& pb) {
  const V3 a1 = pa.F.col(0);
  const V3 b1 = pb.F.col(0);
  const double cosLimit = std::cos(double(d.swingLimit_rad));
  if (a1.dot(b1) < cosLimit) rb.dot(a1, b1, cosLimit).limit = true;
  const double t = twistAngle(pa.F, pb.F);
  V3 n = a1 + b1;
  n = n.squaredNorm() > 1e-12 ? V3(n.normalized()) : a1;
  const V3 wm = (rb.wa() + rb.wb()) / 2;
  if (t < d.twistLower_rad) rb.angleLimit(n, t - d.twistLower_rad, +1, wm);
  if (t > d.twistUpper_rad) rb.angleLimit(n, d.twistUpper_rad - t, -1, wm);
}

void impulseSetup(ImpulseJoints::Joint& j, const JointDef& d, Real) {
  j.stops = true;
  j.swingRow = true;
  j.lower_rad = d.twistLower_rad;
  j.upper_rad = d.twistUpper_rad;
  j.swingLimit_rad = d.swingLimit_rad;
  j.cosHalfSwing = std::cos(Real(0.5) * d.swingLimit_rad);
}

void impulseGeometry(ImpulseJoints::Joint& j, const Quat& qa, const Quat& qb, bool, Real) {
  const Vec3 a1 = xAxis(qa), b1 = xAxis(qb);
  const Vec3 axb = a1.cross(b1);
  const Real sn = axb.norm(), cs = a1.dot(b1);
  j.swingAxisOk = sn > Real(1e-6);
  // Swing row only beyond half the cone (angle > limit / 2, compared as
  // cosines): far inside it the row's axis is undefined and its impulse
  // would be zero anyway.
  j.swingActive = j.swingAxisOk && cs < j.cosHalfSwing * std::sqrt(sn * sn + cs * cs);
  if (j.swingAxisOk) j.swingAxis = wide(Vec3(axb / sn));
  if (j.swingActive) {
    const Vec3 n = axb / sn, nA = j.iA * n, nB = j.iB * n;
    j.swingA = wide(nA);
    j.swingB = wide(nB);
    j.swingK = n.dot(nA + nB);
    j.swingAngle = std::atan2(sn, cs);
  }
  const Vec3 n = a1 + b1;
  setLimitAxis(j, n.squaredNorm() > Real(1e-12) ? Vec3(n.normalized()) : a1);
  j.angle = twistAngle(qa, qb);
}

Vec4r warmStartAngular(const ImpulseJoints::Joint& j, const ImpulseJoints::Accum& acc) {
  Vec4r L = acc.angular;
  L += j.limitAxis * (acc.lower - acc.upper);
  if (acc.swing != 0 && j.swingAxisOk) L -= j.swingAxis * acc.swing;
  return L;
}

Vec4r reportedAngular(const ImpulseJoints::Joint& j, const ImpulseJoints::Accum& acc) {
  Vec4r L = acc.angular + j.limitAxis * (acc.lower - acc.upper);
  L -= j.swingAxis * acc.swing;
  return L;
}

}  // namespace

const JointTypeRows kConeTwistJointRows{
    "cone_twist", nullptr,         lagrangeLimits,   nullptr,        angle,
    impulseSetup, impulseGeometry, warmStartAngular, reportedAngular,
};

}  // namespace tumble::physics
