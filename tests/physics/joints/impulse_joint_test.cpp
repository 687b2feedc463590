// Joint system, impulse solver (impulses inside the contact solver):
// pendulum period, chain error at rest, energy of a frictionless chain,
// limits, motor, springs, breaking, and both joint solvers on the ground.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "joint_fixture.h"
#include "physics/joints/joint_system.h"
#include "physics/joints/ragdoll.h"
#include "physics/world.h"

namespace tumble::physics {
namespace {

constexpr Real kDt = Real(1.0 / 60.0);

JointSettings impulseSettings() {
  JointSettings s;
  s.solver = JointSolverKind::Impulse;
  return s;
}

using test::addBox;
using test::quietSettings;

/// The chain's links (ball joints).
std::vector<BodyId> makeChain(World& w, JointSystem& js, int n, const Vec3& top, const Vec3& dir) {
  return test::makeChain(w, js, n, top, dir).links;
}

TEST(ImpulseJoints, PendulumPeriodWithinOnePercent) {
  {
    World world(quietSettings());
    JointSystem joints(world, impulseSettings());
    EXPECT_NE(world.constraintSolver(), nullptr) << "the impulse solver registers with the World";
  }
  const test::PendulumSwing p = test::swingPendulum(impulseSettings());
  std::printf("[B pendulum] analytic T = %.5f s, measured %.5f s (%.3f%%), anchor error max %.2e m\n", p.analytic_s,
              p.measured_s, 100 * (p.measured_s - p.analytic_s) / p.analytic_s, p.anchorErrorMax_m);
  EXPECT_NEAR(p.measured_s, p.analytic_s, 0.01 * p.analytic_s);
}

TEST(ImpulseJoints, TenLinkChainAtRestKeepsAnchorsWithinAMillimetre) {
  World world(quietSettings());
  JointSystem joints(world, impulseSettings());
  auto links = makeChain(world, joints, 10, Vec3(0, 5, 0), Vec3(0, -1, 0));
  world.applyImpulse(links.back(), Vec3(Real(0.05), 0, 0), world.body(links.back()).position_m);
  for (int i = 0; i < 5 * 60; ++i) joints.step(kDt);
  std::printf("[B chain at rest] 10 links, 5 s: anchor error max %.3e m, now %.3e m\n", joints.maxAnchorError_m(),
              joints.anchorError_m());
  EXPECT_LT(joints.maxAnchorError_m(), 1e-3);
}

TEST(ImpulseJoints, FrictionlessChainDoesNotGainEnergy) {
  World world(quietSettings());
  JointSystem joints(world, impulseSettings());
  // Ball joints have no friction; released horizontal, the largest swing.
  makeChain(world, joints, 10, Vec3(0, 5, 0), Vec3(1, 0, 0));
  const double e0 = world.totalEnergy();
  const double scale = 10 * 0.5 * 9.81 * 2.5;  // m g L of the whole chain
  double emax = e0;
  for (int i = 0; i < 10 * 60; ++i) {
    joints.step(kDt);
    emax = std::max(emax, world.totalEnergy());
  }
  std::printf("[B chain energy] 10 links, 10 s: E0 = %.3f J, max gain %.3e J (%.3f%% of m g L), end %.3f J, "
              "anchor error max %.3e m\n",
              e0, emax - e0, 100 * (emax - e0) / scale, world.totalEnergy(), joints.maxAnchorError_m());
  EXPECT_LE(emax - e0, 1e-3 * scale) << "energy grew";
  EXPECT_LT(joints.maxAnchorError_m(), 0.05);
}

TEST(ImpulseJoints, HingeLimitStopsAndMotorDrives) {
  World world(quietSettings());
  world.settings().gravity_mps2 = Vec3::Zero();
  JointSystem joints(world, impulseSettings());
  // A wheel on a world hinge about z. The hinge angle is the world's frame
  // (B) relative to the wheel's (A): a motor speed of -2 rad/s spins the
  // wheel at +2 rad/s, into the lower stop at -0.5 rad.
  const BodyId wheel = addBox(world, Vec3(0, 1, 0), Vec3(0.3f, 0.3f, 0.05f), 3);
  JointDef d = makeJointDef(world, JointType::Hinge, wheel, BodyId{}, Vec3(0, 1, 0), Vec3::UnitZ());
  d.enableMotor = true;
  d.motorSpeed_radps = -2;
  d.maxMotorTorque_Nm = 50;
  d.enableLimit = true;
  d.lowerAngle_rad = Real(-0.5);
  d.upperAngle_rad = Real(0.5);
  const JointId j = joints.createJoint(d).value();
  // After 0.1 s the motor has it at its target rate (I = 0.09 kg m^2, 50 N m).
  for (int i = 0; i < 6; ++i) joints.step(kDt);
  EXPECT_NEAR(world.body(wheel).angularVelocity_radps.z(), 2, 0.02);
  // The wheel is a hinged body: no spin about any other axis.
  EXPECT_NEAR(world.body(wheel).angularVelocity_radps.head<2>().norm(), 0, 1e-4);
  for (int i = 0; i < 60; ++i) joints.step(kDt);
  // The motor's torque is held by the stop: at the lower limit, at rest.
  const double angle = joints.jointAngle_rad(j);
  std::printf("[B hinge] angle at the stop %.4f rad (limit -0.5), rate %.2e rad/s\n", angle,
              double(world.body(wheel).angularVelocity_radps.z()));
  EXPECT_NEAR(angle, -0.5, 0.01);
  EXPECT_NEAR(world.body(wheel).angularVelocity_radps.z(), 0, 0.01);
}

TEST(ImpulseJoints, ConeTwistHoldsItsSwingCone) {
  World world(quietSettings());
  JointSystem joints(world, impulseSettings());
  // A limb hanging from a world cone-twist (twist axis down, 30 degree cone)
  // is kicked sideways hard: it swings out to the cone and stays inside.
  const BodyId limb = addBox(world, Vec3(0, 1.6f, 0), Vec3(0.05f, 0.4f, 0.05f), 2);
  JointDef d = makeJointDef(world, JointType::ConeTwist, limb, BodyId{}, Vec3(0, 2, 0), Vec3(0, -1, 0));
  d.swingLimit_rad = Real(M_PI / 6);
  d.twistLower_rad = Real(-0.2);
  d.twistUpper_rad = Real(0.2);
  const JointId j = joints.createJoint(d).value();
  world.setLinearVelocity(limb, Vec3(4, 0, 0));
  double swingMax = 0;
  for (int i = 0; i < 120; ++i) {
    joints.step(kDt);
    swingMax = std::max(swingMax, joints.swingAngle_rad(j));
  }
  std::printf("[B cone] largest swing %.4f rad (limit %.4f)\n", swingMax, M_PI / 6);
  EXPECT_GT(swingMax, M_PI / 6 - 0.05) << "the kick reaches the cone";
  EXPECT_LT(swingMax, M_PI / 6 + 0.03);
}

TEST(ImpulseJoints, SoftJointIsASpringWithItsOwnPeriod) {
  World world(quietSettings());
  world.settings().gravity_mps2 = Vec3::Zero();
  JointSystem joints(world, impulseSettings());
  // A 2 kg body on a ball-joint spring of k = 200 N/m, no damping, pulled
  // 0.1 m from its anchor: it oscillates at T = 2 pi sqrt(m / k).
  const BodyId b = addBox(world, Vec3(0, 1, 0), Vec3::Constant(0.1f), 2);
  JointDef d = makeJointDef(world, JointType::Ball, b, BodyId{}, Vec3(0, 1, 0));
  d.linearStiffness_Npm = 200;
  ASSERT_TRUE(joints.createJoint(d).ok());
  world.setPosition(b, Vec3(Real(0.1), 1, 0));
  const double T = 2 * M_PI * std::sqrt(2.0 / 200.0);
  double prev = 0.1, t = 0;
  std::vector<double> up;
  for (int i = 0; i < 4 * 60; ++i) {
    joints.step(kDt);
    t += kDt;
    const double x = world.body(b).position_m.x();
    if (prev < 0 && x >= 0) up.push_back(t - kDt * x / (x - prev));
    prev = x;
  }
  ASSERT_GE(up.size(), 3u);
  const double measured = (up.back() - up.front()) / double(up.size() - 1);
  std::printf("[B spring] analytic T = %.4f s, measured %.4f s\n", T, measured);
  EXPECT_NEAR(measured, T, 0.03 * T);
}

TEST(ImpulseJoints, BreakableJointBreaksAboveItsForce) {
  World world(quietSettings());
  JointSystem joints(world, impulseSettings());
  // 10 kg hanging: 98 N on the joint. A 150 N joint holds, an 80 N one breaks.
  const BodyId held = addBox(world, Vec3(0, 1.8f, 0), Vec3::Constant(0.1f), 10);
  const BodyId lost = addBox(world, Vec3(2, 1.8f, 0), Vec3::Constant(0.1f), 10);
  JointDef d = makeJointDef(world, JointType::Ball, held, BodyId{}, Vec3(0, 2, 0));
  d.breakForce_N = 150;
  const JointId a = joints.createJoint(d).value();
  d = makeJointDef(world, JointType::Ball, lost, BodyId{}, Vec3(2, 2, 0));
  d.breakForce_N = 80;
  const JointId b = joints.createJoint(d).value();
  int breaks = 0;
  for (int i = 0; i < 30; ++i) {
    joints.step(kDt);
    breaks += int(joints.brokenJoints().size());
  }
  EXPECT_TRUE(joints.isValid(a));
  EXPECT_FALSE(joints.isValid(b));
  EXPECT_EQ(breaks, 1);
  EXPECT_NEAR(joints.lastForce_N(a).norm(), 98.1, 1.0) << "holds the weight";
  EXPECT_LT(world.body(lost).position_m.y(), 1.0) << "the released body falls";
}

TEST(ImpulseJoints, SwitchingSolversWhileRunningKeepsTheChain) {
  World world(quietSettings());
  JointSystem joints(world, test::lagrange());
  makeChain(world, joints, 5, Vec3(0, 5, 0), Vec3(1, 0, 0));
  for (int i = 0; i < 60; ++i) joints.step(kDt);
  const ConstraintSolver* lagrange = world.constraintSolver();  // the Lagrange solver solves in the substeps too
  EXPECT_NE(lagrange, nullptr);
  joints.setSolver(JointSolverKind::Impulse);
  EXPECT_NE(world.constraintSolver(), nullptr);
  EXPECT_NE(world.constraintSolver(), lagrange);
  for (int i = 0; i < 60; ++i) joints.step(kDt);
  joints.setSolver(JointSolverKind::Lagrange);
  EXPECT_NE(world.constraintSolver(), nullptr);
  for (int i = 0; i < 60; ++i) joints.step(kDt);
  EXPECT_LT(joints.anchorError_m(), 0.05);
}

struct Drop {
  double errorMax_m, fastest_mps, asleepAt_s;
};

Drop dropRagdoll(JointSolverKind kind) {
  World world;
  JointSettings s;
  s.solver = kind;
  s.projectPositions = false;  // as app::Scene sets it for scenario joints
  JointSystem joints(world, s);
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  (void)world.createBody(ground).value();
  const Quat tilt(Eigen::AngleAxis<Real>(Real(0.3), Vec3::UnitX()));
  Ragdoll r = buildRagdoll(world, joints, defaultHuman(), Vec3(0, Real(0.3), 0), tilt).value();
  double asleepAt = -1;
  for (int i = 0; i < 5 * 60; ++i) {
    joints.step(kDt);
    bool all = true;
    for (BodyId b : r.bodies) all = all && !world.body(b).awake;
    if (asleepAt < 0 && all) asleepAt = (i + 1) * double(kDt);
  }
  Drop d{joints.maxAnchorError_m(), 0, asleepAt};
  for (BodyId b : r.bodies) d.fastest_mps = std::max<double>(d.fastest_mps, world.body(b).linearVelocity_mps.norm());
  std::printf("[drop %s] anchor error max %.2e m, fastest part %.4f m/s, asleep at %.2f s\n", jointSolverName(kind),
              d.errorMax_m, d.fastest_mps, d.asleepAt_s);
  return d;
}

TEST(ImpulseJoints, RagdollDroppedOnTheGroundSleepsWithinFiveSecondsUnderBothSolvers) {
  for (JointSolverKind kind : {JointSolverKind::Lagrange, JointSolverKind::Impulse}) {
    const Drop d = dropRagdoll(kind);
    EXPECT_GE(d.asleepAt_s, 0) << jointSolverName(kind) << ": never fell asleep";
    EXPECT_LE(d.asleepAt_s, 5) << jointSolverName(kind);
    EXPECT_LT(d.fastest_mps, 0.01) << jointSolverName(kind);
  }
}

TEST(ImpulseJoints, BreakingAndStaleBodiesNeverLeaveDanglingRows) {
  World world(quietSettings());
  JointSystem joints(world, impulseSettings());
  auto links = makeChain(world, joints, 4, Vec3(0, 5, 0), Vec3(0, -1, 0));
  world.destroyBody(links[2]);  // two joints lose a body
  for (int i = 0; i < 10; ++i) joints.step(kDt);
  EXPECT_EQ(joints.jointCount(), 2);
  for (BodyId b : {links[0], links[1]}) EXPECT_TRUE(world.body(b).position_m.allFinite());
}

}  // namespace
}  // namespace tumble::physics
