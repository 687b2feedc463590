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
// IB^-1 [rB]x and the cross matrices, precomputed once per solve phase by
// impulsePointRows. That one is inline in internal/impulse_joints.h, inlined
// into the impulse solver's refreshGeometry (it runs for every joint twice
// per substep): compiled here as a call, with timesCross and crossTimes
// inlined into it, a hanging chain of 1000 ball joints stepped 8 % slower
// (tumble_bench_joints; perf put 27 % of the time in it).
#include "physics/internal/joint_types.h"

namespace tumble::physics {
namespace {

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

const JointTypeRows kBallJointRows{
    "ball", nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, warmStartAngular, reportedAngular,
};

}  // namespace tumble::physics
