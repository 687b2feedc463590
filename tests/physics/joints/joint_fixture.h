#pragma once
// What the joint tests of both joint solvers share: a world without sleep, a
// box, a hanging chain of box links, and a one-link pendulum swung at a small
// angle whose period is measured against the analytic one.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics/joints/joint_system.h"
#include "physics/world.h"

namespace tumble::physics::test {

/// The Lagrange solver's settings (the default is the impulse solver; these
/// tests were written for the Lagrange one).
inline JointSettings lagrange() {
  JointSettings s;
  s.solver = JointSolverKind::Lagrange;
  return s;
}

inline WorldSettings quietSettings() {
  WorldSettings s;
  s.enableSleep = false;
  return s;
}

inline BodyId addBox(World& w, const Vec3& p, const Vec3& half, Real mass, Real friction = Real(0.6)) {
  BodyDef d;
  d.shape = Shape::box(half);
  d.position_m = p;
  d.mass_kg = mass;
  d.friction = friction;
  return w.createBody(d).value();
}

/// n links (boxes of length L along the chain) hanging from a world anchor
/// at `top`, laid out along `dir` (unit). Joints at the link ends.
struct Chain {
  std::vector<BodyId> links;
  std::vector<JointId> joints;
};
inline Chain makeChain(World& w, JointSystem& js, int n, const Vec3& top, const Vec3& dir, Real L = Real(0.25),
                       Real mass = Real(0.5), JointType type = JointType::Ball) {
  Chain c;
  const Vec3 half(Real(0.05), L / 2, Real(0.05));
  const Quat q = Quat::FromTwoVectors(Vec3(0, -1, 0), dir);
  for (int i = 0; i < n; ++i) {
    BodyDef d;
    d.shape = Shape::box(half);
    d.position_m = top + dir * (L * (Real(i) + Real(0.5)));
    d.orientation = q;
    d.mass_kg = mass;
    c.links.push_back(w.createBody(d).value());
    const BodyId parent = i == 0 ? BodyId{} : c.links[i - 1];
    // A joint's body A is the child (always dynamic), B the parent or world.
    auto joint = js.createJoint(makeJointDef(w, type, c.links[i], parent, top + dir * (L * Real(i)), Vec3::UnitZ()));
    EXPECT_TRUE(joint.ok());
    if (joint.ok()) c.joints.push_back(joint.value());
  }
  return c;
}

struct PendulumSwing {
  double analytic_s = 0, measured_s = 0;  ///< small-angle period, and the mean of the measured swings
  double anchorErrorMax_m = 0;
};

/// A 2 kg, 0.8 m box hanging by a ball joint at its top centre, released at
/// 0.05 rad and swung for 12 s at 60 Hz: downward zero crossings give the
/// period; the analytic one is 2 pi sqrt(I_pivot / (m g d)).
inline PendulumSwing swingPendulum(const JointSettings& settings) {
  World world(quietSettings());
  JointSystem joints(world, settings);
  const Vec3 half(0.05f, 0.4f, 0.05f);
  const Real m = 2;
  const Vec3 pivot(0, 2, 0);
  const BodyId box = addBox(world, pivot - Vec3(0, half.y(), 0), half, m);
  EXPECT_TRUE(joints.createJoint(makeJointDef(world, JointType::Ball, box, BodyId{}, pivot)).ok());
  const double d = half.y();
  const double Ipivot = m * (4 * half.x() * half.x() + 4 * half.y() * half.y()) / 12.0 + m * d * d;
  PendulumSwing out;
  out.analytic_s = 2 * M_PI * std::sqrt(Ipivot / (m * 9.81 * d));
  const double th0 = 0.05;
  const Quat q(Eigen::AngleAxis<Real>(Real(th0), Vec3::UnitZ()));
  world.setOrientation(box, q);
  world.setPosition(box, pivot + q * Vec3(0, -half.y(), 0));
  const Real dt = Real(1.0 / 60.0);
  double prev = th0, t = 0;
  std::vector<double> crossings;
  for (int i = 0; i < int(12 / dt); ++i) {
    joints.step(dt);
    t += dt;
    const Vec3 r = world.body(box).position_m - pivot;
    const double th = std::atan2(r.x(), -r.y());
    if (prev > 0 && th <= 0) crossings.push_back(t - dt * th / (th - prev));
    prev = th;
  }
  EXPECT_GE(crossings.size(), 4u);
  if (crossings.size() >= 2)
    out.measured_s = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  out.anchorErrorMax_m = joints.maxAnchorError_m();
  return out;
}

}  // namespace tumble::physics::test
