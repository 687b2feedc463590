// Joint system, Lagrange solver: pendulum period, chain error, energy,
// limits, breaking, linear scaling, integrator stability.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "joint_fixture.h"
#include "physics/joints/joint_system.h"
#include "physics/world.h"

namespace tumble::physics {
namespace {

using test::addBox;
using test::Chain;
using test::makeChain;
using test::quietSettings;

TEST(JointSystem, BallPendulumMatchesSmallAnglePeriod) {
  const test::PendulumSwing p = test::swingPendulum(test::lagrange());
  std::printf("[pendulum] analytic T = %.5f s, measured %.5f s (%.3f%%), anchor error max %.2e m\n", p.analytic_s,
              p.measured_s, 100 * (p.measured_s - p.analytic_s) / p.analytic_s, p.anchorErrorMax_m);
  EXPECT_NEAR(p.measured_s, p.analytic_s, 0.01 * p.analytic_s);
}

// A bob on a massless rod (a ball joint to the world) keeps its swing
// energy at every amplitude, under both joint solvers: released at rest
// from 5 to 170 degrees, 12 s at 60 Hz with the default 8 substeps, the
// energy stays within 1 % of m g L of where it started. The Lagrange
// solver's relax sweeps used to project the velocity onto J v = 0 after
// each substep's position update, taking the chord's curvature term out of
// it: it lost energy at O(h) per unit time, 17 % of m g L at 90 degrees and
// 55 % at 150 in 12 s (see "Relax target" in lagrange_substeps.cpp).
TEST(JointSystem, PendulumKeepsItsEnergyAtEveryAmplitude) {
  for (JointSolverKind solver : {JointSolverKind::Lagrange, JointSolverKind::Impulse}) {
    for (double deg : {5.0, 30.0, 60.0, 90.0, 120.0, 150.0, 170.0}) {
      World world;
      JointSettings js;
      js.solver = solver;
      JointSystem joints(world, js);
      const double L = 1.1, m = 0.8, a = deg * kPi / 180;
      const Vec3 pivot(0, 3, 0);
      BodyDef d;
      d.shape = Shape::sphere(Real(0.05));
      d.position_m = pivot + Vec3(Real(L * std::sin(a)), -Real(L * std::cos(a)), 0);
      d.mass_kg = Real(m);
      const BodyId bob = world.createBody(d).value();
      joints.createJoint(makeJointDef(world, JointType::Ball, bob, BodyId{}, pivot)).value();
      const double e0 = world.totalEnergy(), mgL = m * 9.81 * L;
      double worst = 0;
      int crossings = 0;  // passes under the pivot: a world that does not step keeps its energy too
      double lastX = d.position_m.x() - pivot.x();
      for (int i = 0; i < 12 * 60; ++i) {
        joints.step(Real(1.0 / 60.0));
        worst = std::max(worst, std::abs(world.totalEnergy() - e0) / mgL);
        const double x = world.body(bob).position_m.x() - pivot.x();
        crossings += (x < 0) != (lastX < 0);
        lastX = x;
      }
      // The slowest swing (170 degrees) has a 5.1 s period: 4 passes in 12 s.
      EXPECT_GE(crossings, 4) << jointSolverName(solver) << " at " << deg << " degrees: the bob swings";
      std::printf("[pendulum energy] %-8s %5.0f deg: largest |E - E0| %.4f of m g L, anchor error max %.2e m\n",
                  jointSolverName(solver), deg, worst, joints.maxAnchorError_m());
      EXPECT_LT(worst, 0.01) << jointSolverName(solver) << " at " << deg << " degrees";
    }
  }
}

TEST(JointSystem, TenLinkChainAtRestKeepsAnchorsWithinAMillimetre) {
  World world(quietSettings());
  JointSystem joints(world, test::lagrange());
  Chain c = makeChain(world, joints, 10, Vec3(0, 5, 0), Vec3(0, -1, 0));
  // Hanging straight down, with a small sideways nudge to the bottom link so
  // the solver has real work (a perfectly still chain is trivially exact).
  world.applyImpulse(c.links.back(), Vec3(Real(0.05), 0, 0), world.body(c.links.back()).position_m);
  for (int i = 0; i < 5 * 60; ++i) joints.step(Real(1.0 / 60.0));
  std::printf("[chain at rest] 10 links, 5 s at 60 Hz: anchor error max %.3e m, now %.3e m\n",
              joints.maxAnchorError_m(), joints.anchorError_m());
  EXPECT_LT(joints.maxAnchorError_m(), 1e-3);
  EXPECT_EQ(joints.lastSolve().fillIn, 0) << "chain ordered along its length must factorize without fill-in";
}

// The rows' compliance (JointSettings::compliance) is relative to the
// whole system along each row, not to the row's own links: the top joint of
// a long hanging chain carries all of it and must not sag. With a
// compliance relative to the own links (before) 100 links opened by 7.7 mm.
TEST(JointSystem, HundredLinkHangingChainDoesNotSag) {
  World world(quietSettings());
  JointSystem joints(world, test::lagrange());
  Chain c = makeChain(world, joints, 100, Vec3(0, 60, 0), Vec3(0, -1, 0));
  // Neighbours do not collide, as in a rag-doll: links touching end to end
  // would count as contacts and get the compliance of touched assemblies.
  for (std::size_t i = 1; i < c.links.size(); ++i) world.disableCollision(c.links[i], c.links[i - 1]);
  world.applyImpulse(c.links.back(), Vec3(Real(0.05), 0, 0), world.body(c.links.back()).position_m);
  for (int i = 0; i < 3 * 60; ++i) joints.step(Real(1.0 / 60.0));
  std::printf("[hanging chain] 100 links, 3 s at 60 Hz: anchor error max %.3e m, now %.3e m\n",
              joints.maxAnchorError_m(), joints.anchorError_m());
  EXPECT_LT(joints.maxAnchorError_m(), 1e-3);
}

TEST(JointSystem, SwingingChainDoesNotGainEnergy) {
  World world(quietSettings());
  JointSystem joints(world, test::lagrange());
  // Released horizontal: the largest swing a chain can have.
  makeChain(world, joints, 10, Vec3(0, 5, 0), Vec3(1, 0, 0));
  const double e0 = world.totalEnergy();
  const double scale = 10 * 0.5 * 9.81 * 2.5;  // m g L of the whole chain
  double emax = e0, emin = e0, errMax = 0;
  for (int i = 0; i < 10 * 60; ++i) {
    joints.step(Real(1.0 / 60.0));
    emax = std::max(emax, world.totalEnergy());
    emin = std::min(emin, world.totalEnergy());
  }
  errMax = joints.maxAnchorError_m();
  std::printf("[chain energy] 10 links, 10 s at 60 Hz: E0 = %.3f J, max gain %.3e J (%.3f%% of m g L), "
              "final %.3f J, anchor error max %.3e m\n",
              e0, emax - e0, 100 * (emax - e0) / scale, world.totalEnergy(), errMax);
  EXPECT_LE(emax - e0, 0.01 * scale);
}

// The Lagrange solver works with every integrator the World offers. A
// chain whose links do not collide (as world.joint and the rag-doll builder
// set it up) released horizontally, 5 s at 60 Hz with the default 8
// substeps: the joints hold and the energy does not grow (explicit Euler,
// which gains energy on any oscillator, is allowed 0.5 % of m g L).
// With symplectic and backward Euler the solver keeps the swing's
// curvature term (lagrange_substeps.cpp, "Relax target"), so their energy
// error is no longer one-sided: the released chain's whip overshoots once,
// in its first second, by 0.11 % of m g L (then, over 60 s, never again,
// while the whip loses about 30 %). That overshoot is a step error, not
// growth: it halves with the substep (0.057 % at 16 substeps, 0.029 % at
// 32), which the test checks, and it stays under 0.2 % of m g L.
double freeChainEnergyGain(BodyIntegrator method, int substeps, double* anchorErrorMax_m, int* nanEvents) {
  WorldSettings ws = quietSettings();
  ws.integrator = method;
  ws.substeps = substeps;
  World world(ws);
  JointSystem joints(world, test::lagrange());
  Chain c = makeChain(world, joints, 10, Vec3(0, 5, 0), Vec3(1, 0, 0));
  for (std::size_t i = 1; i < c.links.size(); ++i) world.disableCollision(c.links[i], c.links[i - 1]);
  const double e0 = world.totalEnergy(), scale = 10 * 0.5 * 9.81 * 2.5;  // m g L of the chain
  double emax = e0;
  for (int i = 0; i < 5 * 60; ++i) {
    joints.step(Real(1.0 / 60.0));
    emax = std::max(emax, world.totalEnergy());
  }
  if (anchorErrorMax_m) *anchorErrorMax_m = joints.maxAnchorError_m();
  if (nanEvents) *nanEvents = world.errorStats().nanEvents;
  return (emax - e0) / scale;
}

TEST(JointSystem, FreeChainHoldsWithEveryIntegrator) {
  for (const BodyIntegratorInfo& info : bodyIntegrators()) {
    double anchorError = 0;
    int nan = 0;
    const double gain = freeChainEnergyGain(info.method, 8, &anchorError, &nan);
    std::printf("[free chain] %-17s anchor error max %.2e m, energy gain max %.2e of m g L, nan %d\n", info.name,
                anchorError, gain, nan);
    EXPECT_EQ(nan, 0) << info.name;
    EXPECT_LT(anchorError, 0.03) << info.name;
    const bool endVelocity = info.method == BodyIntegrator::SymplecticEuler || info.method == BodyIntegrator::ImplicitEuler;
    if (!endVelocity) {
      EXPECT_LE(gain, info.method == BodyIntegrator::Euler ? 5e-3 : 1e-4) << info.name;
      continue;
    }
    const double finer = freeChainEnergyGain(info.method, 16, nullptr, nullptr);
    std::printf("[free chain] %-17s energy gain max %.2e of m g L at 16 substeps\n", info.name, finer);
    EXPECT_LE(gain, 2e-3) << info.name;
    EXPECT_LE(finer, 0.6 * gain + 1e-6) << info.name << ": the overshoot is a step error and shrinks with the substep";
  }
}

TEST(JointSystem, HingeKeepsItsAxisAndItsLimits) {
  World world(quietSettings());
  JointSystem joints(world, test::lagrange());
  const Vec3 pivot(0, 3, 0);
  const BodyId box = addBox(world, pivot - Vec3(0, Real(0.3), 0), Vec3(Real(0.1), Real(0.3), Real(0.1)), 1);
  JointDef def = makeJointDef(world, JointType::Hinge, box, BodyId{}, pivot, Vec3::UnitZ());
  def.enableLimit = true;
  def.lowerAngle_rad = Real(-0.5);
  def.upperAngle_rad = Real(0.5);
  const JointId j = joints.createJoint(def).value();
  // Swing it hard about the hinge axis (8 rad/s about the pivot: 3.9 J,
  // enough to rise 0.66 m, so both stops are hit hard) plus a little about a
  // wrong axis. The centre moves with the pivot at rest (v = w x r): a spin
  // about the centre alone would, once projected onto the hinge, keep only
  // I_c / I_pivot of its rate and swing to 0.45 rad, short of the stops.
  const Vec3 w0(Real(0.5), 0, 8);
  world.setAngularVelocity(box, w0);
  world.setLinearVelocity(box, w0.cross(world.body(box).position_m - pivot));
  double lo = 0, hi = 0, offAxis = 0;
  for (int i = 0; i < 3 * 60; ++i) {
    joints.step(Real(1.0 / 60.0));
    const double th = joints.jointAngle_rad(j);
    lo = std::min(lo, th), hi = std::max(hi, th);
    const Vec3 axis = world.body(box).orientation * Vec3::UnitZ();
    offAxis = std::max(offAxis, double(std::acos(std::min<Real>(1, axis.z()))));
  }
  std::printf("[hinge] limits [-0.5, 0.5] rad: angle range [%.4f, %.4f], axis tilt max %.2e rad, anchor error max "
              "%.2e m\n",
              lo, hi, offAxis, joints.maxAnchorError_m());
  EXPECT_GT(hi - lo, 0.9) << "the box should reach both limits";
  EXPECT_LT(hi, 0.5 + 0.05);
  EXPECT_GT(lo, -0.5 - 0.05);
  EXPECT_LT(offAxis, 0.01);
  EXPECT_LT(joints.maxAnchorError_m(), 5e-3);
}

TEST(JointSystem, ConeTwistHoldsSwingAndTwistLimits) {
  World world(quietSettings());
  JointSystem joints(world, test::lagrange());
  const Vec3 pivot(0, 3, 0);
  const BodyId rod = addBox(world, pivot - Vec3(0, Real(0.4), 0), Vec3(Real(0.06), Real(0.4), Real(0.06)), 1);
  JointDef def = makeJointDef(world, JointType::ConeTwist, rod, BodyId{}, pivot, -Vec3::UnitY());
  def.swingLimit_rad = Real(0.4);
  def.twistLower_rad = Real(-0.3);
  def.twistUpper_rad = Real(0.3);
  const JointId j = joints.createJoint(def).value();
  // Swing and twist at once, the centre moving with the pivot at rest.
  const Vec3 w0(4, 6, 3);
  world.setAngularVelocity(rod, w0);
  world.setLinearVelocity(rod, w0.cross(world.body(rod).position_m - pivot));
  double swing = 0, twist = 0;
  for (int i = 0; i < 3 * 60; ++i) {
    joints.step(Real(1.0 / 60.0));
    swing = std::max(swing, joints.swingAngle_rad(j));
    twist = std::max(twist, std::abs(joints.jointAngle_rad(j)));
  }
  std::printf("[cone-twist] swing limit 0.4 rad: max %.4f; twist limit 0.3 rad: max |twist| %.4f; anchor error max "
              "%.2e m\n",
              swing, twist, joints.maxAnchorError_m());
  EXPECT_LT(swing, 0.4 + 0.05);
  EXPECT_GT(swing, 0.35);
  EXPECT_LT(twist, 0.3 + 0.05);
  EXPECT_GT(twist, 0.25);
}

TEST(JointSystem, FixedJointHoldsPoseUnderGravity) {
  World world(quietSettings());
  JointSystem joints(world, test::lagrange());
  const BodyId a = addBox(world, Vec3(Real(0.25), 3, 0), Vec3(Real(0.25), Real(0.05), Real(0.05)), 1);
  const BodyId b = addBox(world, Vec3(Real(0.75), 3, 0), Vec3(Real(0.25), Real(0.05), Real(0.05)), 1);
  // A cantilever: a welded to the world at its left end, b welded to a.
  ASSERT_TRUE(joints.createJoint(makeJointDef(world, JointType::Fixed, a, BodyId{}, Vec3(0, 3, 0))).ok());
  ASSERT_TRUE(joints.createJoint(makeJointDef(world, JointType::Fixed, b, a, Vec3(Real(0.5), 3, 0))).ok());
  for (int i = 0; i < 3 * 60; ++i) joints.step(Real(1.0 / 60.0));
  const Vec3 tip = world.body(b).position_m + world.body(b).orientation * Vec3(Real(0.25), 0, 0);
  std::printf("[fixed] cantilever tip sag after 3 s: %.2e m, anchor error max %.2e m\n", 3 - tip.y(),
              joints.maxAnchorError_m());
  EXPECT_NEAR(tip.y(), 3, 1e-3);
  EXPECT_NEAR(tip.x(), 1, 1e-3);
}

TEST(JointSystem, SoftJointStretchesLikeASpring) {
  World world(quietSettings());
  JointSystem joints(world, test::lagrange());
  const Real k = 500, m = 2;
  const BodyId box = addBox(world, Vec3(0, Real(2.9), 0), Vec3::Constant(Real(0.1)), m);
  JointDef def = makeJointDef(world, JointType::Ball, box, BodyId{}, Vec3(0, 3, 0));
  def.linearStiffness_Npm = k;
  def.linearDamping_Nspm = 2 * std::sqrt(k * m);  // critically damped
  ASSERT_TRUE(joints.createJoint(def).ok());
  for (int i = 0; i < 3 * 60; ++i) joints.step(Real(1.0 / 60.0));
  const double stretch = joints.anchorError_m();
  std::printf("[soft] spring k = %.0f N/m, m = %.1f kg: stretch %.5f m, Hooke m g / k = %.5f m\n", k, m, stretch,
              m * 9.81 / k);
  EXPECT_NEAR(stretch, m * 9.81 / k, 0.02 * m * 9.81 / k);
}

TEST(JointSystem, BreakableJointBreaksAboveItsThresholdOnly) {
  for (double fraction : {1.5, 0.5}) {
    World world(quietSettings());
    JointSystem joints(world, test::lagrange());
    const Real m = 3;
    const BodyId box = addBox(world, Vec3(0, Real(2.8), 0), Vec3::Constant(Real(0.2)), m);
    JointDef def = makeJointDef(world, JointType::Ball, box, BodyId{}, Vec3(0, 3, 0));
    def.breakForce_N = Real(fraction * m * 9.81);  // it carries m g at rest
    const JointId j = joints.createJoint(def).value();
    int broke = 0;
    for (int i = 0; i < 2 * 60; ++i) {
      joints.step(Real(1.0 / 60.0));
      for (const JointBreakEvent& e : joints.brokenJoints()) {
        ++broke;
        EXPECT_EQ(e.id, j);
        EXPECT_NEAR(e.force_N, m * 9.81, 0.05 * m * 9.81);
      }
    }
    std::printf("[break] threshold %.1f m g: %s, box y = %.2f m\n", fraction, broke ? "broke" : "held",
                world.body(box).position_m.y());
    if (fraction > 1) {
      EXPECT_EQ(broke, 0);
      EXPECT_TRUE(joints.isValid(j));
      EXPECT_NEAR(world.body(box).position_m.y(), 2.8, 1e-3);
    } else {
      EXPECT_EQ(broke, 1);
      EXPECT_FALSE(joints.isValid(j));
      EXPECT_LT(world.body(box).position_m.y(), 2.8 - 10);  // fell freely for ~2 s
    }
  }
}

TEST(JointSystem, SolveTimeGrowsLinearlyWithLinks) {
  std::printf("[scaling] links  rows   nnz(A)  nnz(L)  fill  solve_ms  us/link\n");
  double perLink10 = 0, perLink1000 = 0;
  double factorPerLink10 = 0, factorPerLink1000 = 0;
  for (int n : {10, 100, 1000}) {
    World world(quietSettings());
    JointSystem joints(world, test::lagrange());
    makeChain(world, joints, n, Vec3(0, 0, 0), Vec3(1, 0, 0).normalized());
    for (int i = 0; i < 3; ++i) joints.step(Real(1.0 / 60.0));  // warm up, set the chain moving
    const int reps = n >= 1000 ? 10 : 50;
    double total = 0, best = 1e9;
    for (int i = 0; i < reps; ++i) {
      joints.step(Real(1.0 / 60.0));
      total += joints.lastSolve().solveMs;
      best = std::min(best, joints.lastSolve().solveMs);
    }
    const JointSolveStats& s = joints.lastSolve();
    const double ms = total / reps;
    std::printf("[scaling] %5d %6d %8ld %7ld %5ld %9.4f %8.3f\n", n, s.rows, s.nonZerosA, s.nonZerosL, s.fillIn, ms,
                1000 * ms / n);
    EXPECT_EQ(s.fillIn, 0);
    if (n == 10) perLink10 = best / n, factorPerLink10 = double(s.nonZerosL + s.rows) / n;
    if (n == 1000) perLink1000 = best / n, factorPerLink1000 = double(s.nonZerosL + s.rows) / n;
  }
  std::printf("[scaling] per-link cost ratio 1000 links / 10 links = %.2f (1 = linear, 100 = quadratic)\n",
              perLink1000 / perLink10);
  // The factor's size per link is the same for 10 and 1000 links (a chain
  // is a tree: no fill-in, a constant number of rows per joint), within the
  // end effects of the first and last link: the solve's work (a sparse
  // LDL^T factor and its two triangular solves, proportional to the
  // factor's entries) grows linearly. Wall time is printed, not asserted:
  // on a shared, loaded machine the best-of-50 per-link time ratio read 13
  // while the mean ratio read 1.7 in the same run.
  EXPECT_NEAR(factorPerLink1000, factorPerLink10, 0.2 * factorPerLink10);
}

// The wheel: a 5 kg hub hanging from a pivot at its corner, 40 spokes of
// 0.2 kg round it, each on a ball joint (a chandelier's arms).
struct Wheel {
  BodyId hub;
  std::vector<JointId> spokes;
};
Wheel makeWheel(World& world, JointSystem& joints) {
  Wheel w;
  w.hub = addBox(world, Vec3(0, 10, 0), Vec3(Real(0.2), Real(0.2), Real(0.2)), 5);
  EXPECT_TRUE(joints.createJoint(makeJointDef(world, JointType::Ball, w.hub, BodyId{}, Vec3(Real(0.2), Real(10.2), 0))).ok());
  for (int i = 0; i < 40; ++i) {
    const Real a = Real(2 * M_PI * i / 40);
    const Vec3 dir(std::cos(a), 0, std::sin(a));
    const BodyId s = addBox(world, Vec3(0, 10, 0) + dir * Real(0.6), Vec3::Constant(Real(0.02)), Real(0.2));
    world.disableCollision(s, w.hub);
    w.spokes.push_back(joints.createJoint(makeJointDef(world, JointType::Ball, s, w.hub, Vec3(0, 10, 0) + dir * Real(0.3))).value());
  }
  return w;
}

// The Lagrange solver's cost cap (JointSettings::lagrangeMaxFactorWorkPerRow).
// The hub's 40 joints couple all 123 rows: the factorization costs about
// 2.8 k^2 per row for k joints (6.3e5 here, 5100 per row; 50 joints took
// 117 ms a step). Past the cap the impulse solver holds the joints about as
// well as the Lagrange solver does, the count says so, and once the hub
// carries few joints the Lagrange solver takes over again. A chain of 300
// links (26 per row) stays under the cap.
TEST(JointSystem, ABodyCarryingManyJointsIsSolvedByTheImpulseSolverUntilItCarriesFewer) {
  World world(quietSettings());
  JointSystem joints(world, test::lagrange());
  ASSERT_EQ(joints.solver(), JointSolverKind::Lagrange);
  Wheel wheel = makeWheel(world, joints);
  for (int i = 0; i < 60; ++i) joints.step(Real(1.0 / 60.0));
  // The same wheel, the Lagrange solver with no cap.
  World uncappedWorld(quietSettings());
  JointSettings uncapped = test::lagrange();
  uncapped.lagrangeMaxFactorWorkPerRow = std::numeric_limits<double>::infinity();
  JointSystem uncappedJoints(uncappedWorld, uncapped);
  makeWheel(uncappedWorld, uncappedJoints);
  for (int i = 0; i < 60; ++i) uncappedJoints.step(Real(1.0 / 60.0));
  std::printf("[cost cap] hub with 40 spokes, 1 s: %ld steps over the cap, work %.3g per row; anchor error max %.2e m "
              "(Lagrange uncapped: %.2e m, %ld steps over)\n",
              joints.stepsOverCostCap(), joints.overCostCapWorkPerRow(), joints.maxAnchorError_m(),
              uncappedJoints.maxAnchorError_m(), uncappedJoints.stepsOverCostCap());
  EXPECT_EQ(joints.solver(), JointSolverKind::Lagrange) << "the request stays";
  EXPECT_EQ(joints.runningSolver(), JointSolverKind::Impulse);
  EXPECT_EQ(joints.stepsOverCostCap(), 60) << "every step, the first included";
  EXPECT_GT(joints.overCostCapWorkPerRow(), 500.0);
  EXPECT_EQ(uncappedJoints.stepsOverCostCap(), 0);
  EXPECT_EQ(uncappedJoints.runningSolver(), JointSolverKind::Lagrange);
  // The stand-in holds the joints as the Lagrange solver does, and the
  // wheel swung down on its pivot (from 10 m towards 9.92 m).
  EXPECT_LT(joints.maxAnchorError_m(), 1.5 * uncappedJoints.maxAnchorError_m());
  EXPECT_LT(world.body(wheel.hub).position_m.y(), Real(9.98));
  EXPECT_NEAR(world.body(wheel.hub).position_m.y(), uncappedWorld.body(wheel.hub).position_m.y(), 0.01);
  // Down to 5 spokes: the Lagrange solver again.
  for (std::size_t i = 5; i < wheel.spokes.size(); ++i) ASSERT_TRUE(joints.destroyJoint(wheel.spokes[i]));
  for (int i = 0; i < 10; ++i) joints.step(Real(1.0 / 60.0));
  EXPECT_EQ(joints.runningSolver(), JointSolverKind::Lagrange);
  EXPECT_EQ(joints.stepsOverCostCap(), 60);
  EXPECT_LT(joints.lastSolve().factorWork, 500.0 * joints.lastSolve().rows);

  World chainWorld(quietSettings());
  JointSystem chainJoints(chainWorld, test::lagrange());
  makeChain(chainWorld, chainJoints, 300, Vec3(0, 0, 0), Vec3(1, 0, 0));
  for (int i = 0; i < 10; ++i) chainJoints.step(Real(1.0 / 60.0));
  EXPECT_EQ(chainJoints.runningSolver(), JointSolverKind::Lagrange);
  EXPECT_EQ(chainJoints.stepsOverCostCap(), 0);
  std::printf("[cost cap] chain of 300 links: %.1f multiply-adds per row\n",
              chainJoints.lastSolve().factorWork / chainJoints.lastSolve().rows);
  EXPECT_LT(chainJoints.lastSolve().factorWork, 50.0 * chainJoints.lastSolve().rows);
}

// A hub on a ball joint with `spokes` rods on hinges round it, each hinge
// stopped at +-limit_rad and its rod held level at the start: gravity
// swings the rods onto their stops, and the stops' rows enter the system.
struct StoppedWheel {
  BodyId hub;
  std::vector<BodyId> rods;
};
StoppedWheel makeStoppedWheel(World& world, JointSystem& joints, int spokes, Real limit_rad) {
  StoppedWheel w;
  w.hub = addBox(world, Vec3(0, 10, 0), Vec3::Constant(Real(0.2)), 5);
  EXPECT_TRUE(joints.createJoint(makeJointDef(world, JointType::Ball, w.hub, BodyId{}, Vec3(0, Real(10.2), 0))).ok());
  for (int i = 0; i < spokes; ++i) {
    const Real a = Real(2 * M_PI * i / spokes);
    const Vec3 dir(std::cos(a), 0, std::sin(a));
    const BodyId rod = addBox(world, Vec3(0, 10, 0) + dir * Real(0.6), Vec3::Constant(Real(0.05)), Real(0.5));
    world.disableCollision(rod, w.hub);
    // The hinge axis is horizontal and across the rod, so the rod swings down.
    JointDef d = makeJointDef(world, JointType::Hinge, rod, w.hub, Vec3(0, 10, 0) + dir * Real(0.3),
                              Vec3(-dir.z(), 0, dir.x()));
    d.enableLimit = true;
    d.lowerAngle_rad = -limit_rad;
    d.upperAngle_rad = limit_rad;
    EXPECT_TRUE(joints.createJoint(d).ok());
    w.rods.push_back(rod);
  }
  return w;
}

// The cost cap found inside a step: the system fits the cap when the joints
// are made, then the stops' rows enter (the rods swing onto them) and the
// factorization's work per row grows past it. That step the joints are not
// solved; from the next step on the impulse solver stands in. The cap here
// is set between the work per row of the system without and with its stop
// rows, as measured in the same run with no cap, so that only the stops
// take it over.
TEST(JointSystem, StopRowsThatGrowTheSystemPastTheCapInAStepHandItToTheImpulseSolver) {
  const int spokes = 8;
  const Real limit = Real(0.1);
  World uncappedWorld(quietSettings());
  JointSettings uncapped = test::lagrange();
  uncapped.lagrangeMaxFactorWorkPerRow = std::numeric_limits<double>::infinity();
  JointSystem uncappedJoints(uncappedWorld, uncapped);
  makeStoppedWheel(uncappedWorld, uncappedJoints, spokes, limit);
  uncappedJoints.step(Real(1.0 / 60.0));
  const int rowsFree = uncappedJoints.lastSolve().rows;
  const double workFree = uncappedJoints.lastSolve().factorWork / rowsFree;
  int rowsStopped = rowsFree;
  double workStopped = workFree;
  for (int i = 1; i < 60; ++i) {
    uncappedJoints.step(Real(1.0 / 60.0));
    if (uncappedJoints.lastSolve().rows > rowsStopped) {
      rowsStopped = uncappedJoints.lastSolve().rows;
      workStopped = uncappedJoints.lastSolve().factorWork / rowsStopped;
    }
  }
  std::printf("[cost cap in a step] %d rows, %.0f multiply-adds per row free; %d rows, %.0f per row on the stops\n",
              rowsFree, workFree, rowsStopped, workStopped);
  ASSERT_EQ(rowsStopped, rowsFree + spokes) << "every rod reached a stop";
  ASSERT_GT(workStopped, workFree);

  World world(quietSettings());
  JointSettings capped = test::lagrange();
  capped.lagrangeMaxFactorWorkPerRow = std::sqrt(workFree * workStopped);
  JointSystem joints(world, capped);
  const StoppedWheel wheel = makeStoppedWheel(world, joints, spokes, limit);
  joints.step(Real(1.0 / 60.0));
  EXPECT_EQ(joints.runningSolver(), JointSolverKind::Lagrange) << "fits the cap as made";
  EXPECT_EQ(joints.stepsOverCostCap(), 0);
  int handedOverAt = -1;
  for (int i = 1; i < 60; ++i) {
    joints.step(Real(1.0 / 60.0));
    if (handedOverAt < 0 && joints.runningSolver() == JointSolverKind::Impulse) handedOverAt = i;
  }
  std::printf("[cost cap in a step] cap %.0f: handed over at step %d, %ld steps over; anchor error max %.2e m "
              "(uncapped %.2e m)\n",
              capped.lagrangeMaxFactorWorkPerRow, handedOverAt, joints.stepsOverCostCap(), joints.maxAnchorError_m(),
              uncappedJoints.maxAnchorError_m());
  EXPECT_GT(handedOverAt, 0) << "found in a step, not when the joints were made";
  EXPECT_EQ(joints.solver(), JointSolverKind::Lagrange) << "the request stays";
  EXPECT_GT(joints.stepsOverCostCap(), 0);
  EXPECT_GT(joints.overCostCapWorkPerRow(), capped.lagrangeMaxFactorWorkPerRow);
  // The step in which nothing was solved and the stand-in after it keep the
  // wheel together and finite; the rods hang on their stops as without the cap.
  EXPECT_EQ(world.errorStats().nanEvents, 0);
  EXPECT_LT(joints.maxAnchorError_m(), 0.01);
  for (std::size_t i = 0; i < wheel.rods.size(); ++i) {
    const Vec3 p = world.body(wheel.rods[i]).position_m;
    ASSERT_TRUE(p.allFinite());
    EXPECT_LT(p.y(), Real(10)) << "rod " << i << " swung down";
  }
}

/// Largest stable dt of integrateFree for a 5-link chain released at 45
/// degrees, for 5 s: stable = no blow-up: finite, anchor error < 5 cm and
/// |E - E0| below the chain's m g L. (Explicit Euler gains energy at every dt
/// on the undamped pendulum modes; "stable" here is the paper's sense: the
/// joints hold together.) Every smaller dt of the grid must be stable too.
double largestStableDt(JointIntegrator method, double ks, double kd) {
  const double grid[] = {0.001, 0.002, 0.004, 0.006, 0.008, 0.01, 0.0125, 0.015, 0.0175, 0.02,
                         0.0225, 0.025, 0.0275, 0.03, 0.035, 0.04, 0.05, 0.06, 0.08, 0.1};
  double best = 0;
  for (double dt : grid) {
    World world(quietSettings());
    JointSettings js = test::lagrange();
    js.stiffness_per_s2 = ks;
    js.damping_per_s = kd;
    JointSystem joints(world, js);
    makeChain(world, joints, 5, Vec3(0, 5, 0), Vec3(1, -1, 0).normalized());
    const double e0 = world.totalEnergy(), scale = 5 * 0.5 * 9.81 * 1.25;
    bool ok = true;
    for (int i = 0; i < int(std::lround(5 / dt)) && ok; ++i) {
      joints.integrateFree(method, dt);
      const double e = world.totalEnergy();
      ok = std::isfinite(e) && std::abs(e - e0) < scale && joints.anchorError_m() < 0.05;
    }
    if (!ok) break;
    best = dt;
  }
  return best;
}

TEST(JointSystem, StabilityTableExplicitEulerVersusTrapezoid) {
  const double pairs[][2] = {{0, 0}, {25, 10}, {100, 20}, {400, 40}, {900, 60}, {2500, 100}, {100, 60}, {400, 10}};
  const JointSettings defaults;
  std::printf("[stability] largest stable dt (s), 5-link chain, 5 s; grid 0.001..0.1\n");
  std::printf("[stability]    k_s    k_d  explicit_euler  trapezoid  semi_implicit  rk4\n");
  for (const auto& p : pairs) {
    const double ee = largestStableDt(JointIntegrator::ExplicitEuler, p[0], p[1]);
    const double tr = largestStableDt(JointIntegrator::Trapezoid, p[0], p[1]);
    const double si = largestStableDt(JointIntegrator::SemiImplicitEuler, p[0], p[1]);
    const double rk = largestStableDt(JointIntegrator::Rk4, p[0], p[1]);
    const bool isDefault = p[0] == defaults.stiffness_per_s2 && p[1] == defaults.damping_per_s;
    std::printf("[stability] %6.0f %6.0f  %14.4f  %9.4f  %13.4f  %6.4f%s\n", p[0], p[1], ee, tr, si, rk,
                isDefault ? "   <- defaults" : "");
    // The trapezoid rule is at least as stable as explicit Euler.
    EXPECT_GE(tr + 1e-12, ee);
  }
}

}  // namespace
}  // namespace tumble::physics
