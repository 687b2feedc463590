// Fixed joint: the point rows (ball_joint.cpp) plus three rows locking the
// relative orientation of the two joint frames.
//
// Lagrange multipliers: three "axis" rows (n a unit axis fixed in A, C an
// angle error about n; J_a = [ 0  n^T ], J_b = [ 0  -n^T ],
// J' q' = (w_a x n).(w_a - w_b)) along A's frame axes a_i, C = -phi.a_i,
// phi the rotation vector of B's frame relative to A's (from their relative
// quaternion, the shorter way round).
//
// Impulses (one 3x3 block, on B, their negative on A): C = 2 vec(qB qA^-1)
// (the small-angle rotation vector, world axes), Cdot = wB - wA,
// K = IA^-1 + IB^-1.
#include "physics/internal/joint_types.h"

namespace tumble::physics {
namespace {

using lagrange::JointPose, lagrange::Qd, lagrange::RowBuilder, lagrange::V3;

void lagrangeOrientation(RowBuilder& rb, const JointPose& pa, const JointPose& pb) {
  const V3 a1 = pa.F.col(0), a2 = pa.F.col(1), a3 = pa.F.col(2);
  // phi: the rotation vector of B's frame relative to A's (in A's frame,
  // the shorter way round); C = -phi along each axis.
  Qd rel(pa.F.transpose() * pb.F);
  if (rel.w() < 0) rel.coeffs() = -rel.coeffs();
  const V3 phi = 2 * rel.vec();
  rb.axis(a1, -phi.x()), rb.axis(a2, -phi.y()), rb.axis(a3, -phi.z());
}

void impulseGeometry(ImpulseJoints::Joint& j, const Quat& qa, const Quat& qb, bool angularRows, Real gamma) {
  if (!angularRows) return;
  // C = 2 vec(qB qA^-1) (the small-angle rotation vector), rows along the world axes.
  Quat rel = qb * qa.conjugate();
  if (rel.w() < 0) rel.coeffs() = -rel.coeffs();
  for (int k = 0; k < 3; ++k) setAngularAxis(j, k, Vec3::Unit(k));
  Mat3 K3 = j.iA + j.iB;
  K3.diagonal().array() += gamma;
  const Mat3 K3inv = K3.inverse();
  if (K3inv.allFinite()) {
    j.angularRows = 3;
    j.angKinv = wide(K3inv);
    j.angC = wide(Vec3(2 * rel.vec()));
  }
}

Vec4r warmStartAngular(const ImpulseJoints::Joint&, const ImpulseJoints::Accum& acc) { return acc.angular; }

Vec4r reportedAngular(const ImpulseJoints::Joint& j, const ImpulseJoints::Accum& acc) {
  return acc.angular + j.limitAxis * (acc.lower - acc.upper);
}

}  // namespace

const JointTypeRows kFixedJointRows{
    "fixed",  lagrangeOrientation, nullptr,          nullptr,         nullptr,
    nullptr, impulseGeometry,     warmStartAngular, reportedAngular,
};

}  // namespace tumble::physics
