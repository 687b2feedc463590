// Ball joint: the anchors coincide, rotation is free. Its three point rows
// are part of every joint type (hinge, cone-twist and fixed add theirs on
// top), so they are here for both solvers.
//
// Lagrange multipliers (Baraff's point-to-point rows; r_a = R_a *
// localAnchorA, the anchor's offset from A's centre, p_a = x_a + r_a;
// likewise for B; for a world anchor v_b = w_b = 0):
//   C = p_a - p_b,  J_a = [ 1  -[r_a]x ],  J_b = [ -1  [r_b]x ],
//   J' q' = w_a x (w_a x r_a) - w_b x (w_b x r_b).
//
// Impulses (one 3x3 block; impulses act on B, their negative on A):
//   C = pB - pA,  Cdot = vB + wB x rB - vA - wA x rA,
//   K = (mA + mB) 1 - [rA] IA^-1 [rA] - [rB] IB^-1 [rB]   ([r] = cross matrix).
// The sweep (impulse_solver.cpp) reads (K + gamma)^-1, IA^-1 [rA]x,
// IB^-1 [rB]x and the cross matrices, precomputed here once per solve phase.
#include "physics/internal/joint_types.h"

namespace tumble::physics {
namespace {

/// I [r]x, column by column ([r]x e_k = r x e_k has two non-zero entries):
/// 18 multiplies instead of a 3x3 product's 27.
Mat3 timesCross(const Mat3& I, const Vec3& r) {
  Mat3 m;
  m.col(0) = r.z() * I.col(1) - r.y() * I.col(2);
  m.col(1) = r.x() * I.col(2) - r.z() * I.col(0);
  m.col(2) = r.y() * I.col(0) - r.x() * I.col(1);
  return m;
}

/// [r]x M, column by column (r x each column).
Mat3 crossTimes(const Vec3& r, const Mat3& M) {
  Mat3 m;
  for (int k = 0; k < 3; ++k) m.col(k) = r.cross(M.col(k));
  return m;
}

Vec4r warmStartAngular(const ImpulseJoints::Joint&, const ImpulseJoints::Accum& acc) { return acc.angular; }

Vec4r reportedAngular(const ImpulseJoints::Joint& j, const ImpulseJoints::Accum& acc) {
  return acc.angular + j.limitAxis * (acc.lower - acc.upper);
}

}  // namespace

void lagrangePointRows(lagrange::RowBuilder& rb, const lagrange::JointPose& pa, const lagrange::JointPose& pb) {
  using lagrange::M3, lagrange::V3;
  const V3 c = pa.p - pb.p;
  const V3 jdq = rb.wa().cross(rb.wa().cross(pa.r)) - rb.wb().cross(rb.wb().cross(pb.r));
  const M3 sa = -lagrange::RowBuilder::skew3(pa.r), sb = lagrange::RowBuilder::skew3(pb.r);
  for (int i = 0; i < 3; ++i) {
    lagrange::Row& r = rb.add();
    r.ja.head<3>() = V3::Unit(i);
    r.ja.tail<3>() = sa.row(i).transpose();
    r.jb.head<3>() = -V3::Unit(i);
    r.jb.tail<3>() = sb.row(i).transpose();
    r.c = c[i];
    r.jdq = jdq[i];
  }
}

void impulsePointRows(ImpulseJoints::Joint& j, const Vec3& rA, const Vec3& rB, const Vec3& pA, const Vec3& pB) {
  // K = (mA + mB) 1 - [rA] IA^-1 [rA] - [rB] IB^-1 [rB].
  const Mat3 MA = timesCross(j.iA, rA), MB = timesCross(j.iB, rB);
  Mat3 K = (j.mA + j.mB) * Mat3::Identity() - crossTimes(rA, MA) - crossTimes(rB, MB);
  if (j.soft) K.diagonal().array() += j.gammaLin;
  const Mat3 Kinv = K.inverse();
  j.pointOk = Kinv.allFinite();
  j.pointKinv = wide(Kinv);
  j.MA = wide(MA);
  j.MB = wide(MB);
  j.SA = wide(skew(rA));
  j.SB = wide(skew(rB));
  j.C = wide(Vec3(pB - pA));
}

const JointTypeRows kBallJointRows{
    "ball", nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, warmStartAngular, reportedAngular,
};

}  // namespace tumble::physics
