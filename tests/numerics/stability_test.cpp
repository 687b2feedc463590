// Stability: limits on the decay problem against the theory, the stiff
// spring cases, and blow-up detection that reports instead of crashing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "numerics/stability.h"
#include "numerics/systems.h"

namespace tumble::numerics {
namespace {

TEST(DecayStability, ImplicitEulerIsStableAtCDt100) {
  EXPECT_TRUE(decayIsStable(Method::ImplicitEuler, 100.0));
  // And it decays monotonically: x1 = 1/(1 + 100).
  const LinearDecay decay(1000.0);
  Integrator integrator(Method::ImplicitEuler, 1);
  Eigen::VectorXd x = Eigen::VectorXd::Ones(1);
  integrator.step(decay, 0.0, x, 0.1);
  EXPECT_NEAR(x[0], 1.0 / 101.0, 1e-14);
}

TEST(DecayStability, ExplicitEulerLimitIsCDt2) {
  EXPECT_TRUE(decayIsStable(Method::ExplicitEuler, 1.98));
  EXPECT_FALSE(decayIsStable(Method::ExplicitEuler, 2.02));
}

TEST(DecayStability, MeasuredRk4LimitIsTheTheoreticalOne) {
  const double theory = rk4RealStabilityLimit();
  EXPECT_NEAR(theory, 2.785, 1e-3);
  const double measured =
      largestStable([](double x) { return decayIsStable(Method::Rk4, x); }, 1e-2, 1e6, 30);
  EXPECT_NEAR(measured / 2.785, 1.0, 0.02);
  EXPECT_NEAR(measured, theory, 1e-6);
}

TEST(DecayStability, AStableMethodsHaveNoLimit) {
  for (Method m : {Method::ImplicitEuler, Method::ImplicitMidpoint, Method::Sdirk2})
    EXPECT_TRUE(std::isinf(
        largestStable([m](double x) { return decayIsStable(m, x); }, 1e-2, 1e6, 10)))
        << methodName(m);
}

TEST(DecayStability, Sdirk2DampsStiffModesButMidpointDoesNot) {
  // L-stability: at c*dt = 1e4 SDIRK2 takes x to ~0 in one step, while the
  // implicit midpoint rule flips its sign with |R| ~ 1.
  const LinearDecay decay(1.0);
  Eigen::VectorXd a = Eigen::VectorXd::Ones(1), b = a;
  Integrator sdirk(Method::Sdirk2, 1), midpoint(Method::ImplicitMidpoint, 1);
  sdirk.step(decay, 0.0, a, 1e4);
  midpoint.step(decay, 0.0, b, 1e4);
  EXPECT_LT(std::abs(a[0]), 1e-3);
  EXPECT_NEAR(b[0], -1.0, 1e-3);
}

TEST(PendulumStability, SmallAmplitudeLimitsMatchTheLinearTheory) {
  constexpr double kSmall = 0.01;  // rad
  for (Method m : {Method::SymplecticEuler, Method::Verlet}) {
    EXPECT_TRUE(pendulumIsStable(m, 1.9, kSmall)) << methodName(m);
    EXPECT_FALSE(pendulumIsStable(m, 2.1, kSmall)) << methodName(m);
  }
  const double rk4 = largestStable(
      [&](double x) { return pendulumIsStable(Method::Rk4, x, kSmall); }, 1.0, 10.0, 16);
  EXPECT_NEAR(rk4 / (2.0 * std::sqrt(2.0)), 1.0, 0.01);
  EXPECT_FALSE(pendulumIsStable(Method::ExplicitEuler, 0.05, kSmall));  // energy grows
  EXPECT_TRUE(pendulumIsStable(Method::ImplicitEuler, 10.0, kSmall));
  EXPECT_TRUE(pendulumIsStable(Method::Sdirk2, 10.0, kSmall));
}

TEST(PendulumStability, LargeAmplitudeSymplecticLimitIsBelowTheLinearOne) {
  // At 2 rad the bounded energy error of semi-implicit Euler at big steps
  // carries the pendulum over the top before omega0*dt reaches 2.
  EXPECT_TRUE(pendulumIsStable(Method::SymplecticEuler, 0.5));
  EXPECT_FALSE(pendulumIsStable(Method::SymplecticEuler, 1.5));
}

TEST(StabilityCases, StiffSpringAt60HzBlowsUpExplicitlyAndNeverCrashes) {
  const std::vector<StabilityCase> cases = builtinStabilityCases();
  ASSERT_FALSE(cases.empty());
  const StabilityCase& spring = cases.front();
  ASSERT_EQ(spring.name, "spring_k1e6");
  for (Method m : {Method::ExplicitEuler, Method::Rk4, Method::Verlet, Method::SymplecticEuler}) {
    const StabilityRow row = spring.run(m, 1.0 / 60.0, true);
    EXPECT_EQ(row.outcome, Outcome::BlewUp) << methodName(m);
    ASSERT_TRUE(row.timeToFailure_s.has_value());
    EXPECT_LT(*row.timeToFailure_s, 1.0);
  }
  // Implicit midpoint keeps a linear spring's energy exactly: stable.
  EXPECT_EQ(spring.run(Method::ImplicitMidpoint, 1.0 / 60.0, true).outcome, Outcome::Stable);
  // L-stable methods damp the unresolvable 1000 rad/s mode away: drifting.
  for (Method m : {Method::ImplicitEuler, Method::Sdirk2}) {
    const StabilityRow row = spring.run(m, 1.0 / 60.0, true);
    EXPECT_EQ(row.outcome, Outcome::Drifting) << methodName(m);
    EXPECT_LT(*row.energyGrowth, -0.9);
  }
}

TEST(StabilityCases, NonFiniteStateIsReportedWithItsTime) {
  // A force that becomes NaN at t = 0.5 s: reported as blew_up at ~0.5 s.
  struct Poisoned final : SecondOrderSystem {
    int dofs() const override { return 1; }
    void acceleration(double t, ConstRef q, ConstRef, Ref a) const override {
      a[0] = t >= 0.5 ? std::numeric_limits<double>::quiet_NaN() : -q[0];
    }
    std::optional<double> energy(const Eigen::VectorXd& y) const override {
      return 0.5 * (y[0] * y[0] + y[1] * y[1]);
    }
  } system;
  const StabilityRow row =
      monitorOdeRun("poisoned", system, Eigen::Vector2d(1.0, 0.0), Method::Rk4, 0.01, 2.0);
  EXPECT_EQ(row.outcome, Outcome::BlewUp);
  EXPECT_EQ(row.nanEvents, 1);
  ASSERT_TRUE(row.timeToFailure_s.has_value());
  EXPECT_NEAR(*row.timeToFailure_s, 0.5, 0.011);
  EXPECT_TRUE(std::isfinite(*row.energyGrowth));
}

TEST(StabilityCases, CsvHasTheAgreedColumnsAndEmptyCellsForNotApplicable) {
  StabilityRow row;
  row.caseName = "c";
  row.method = "rk4";
  row.dt_s = 0.5;
  row.energyGrowth = 0.25;
  const std::vector<StabilityRow> rows = {row};
  EXPECT_EQ(stabilityCsv(rows),
            "case,method,dt,outcome,time_to_failure_s,energy_growth,penetration_max_m,"
            "joint_error_max_m,nan_events,failed_body\n"
            "c,rk4,0.5,stable,,0.25,,,0,\n");
  row.outcome = Outcome::BlewUp;
  row.failedBody = "box 3";
  EXPECT_EQ(stabilityCsv(std::vector<StabilityRow>{row}).substr(stabilityCsv(rows).find('\n') + 1),
            "c,rk4,0.5,blew_up,,0.25,,,0,box 3\n");
}

}  // namespace
}  // namespace tumble::numerics
