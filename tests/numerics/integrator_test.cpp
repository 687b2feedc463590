// Integrators against the harmonic oscillator's exact solution: convergence
// orders, energy behaviour over long runs, names, Jacobians.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "numerics/integrator.h"
#include "numerics/reference_problems.h"
#include "numerics/systems.h"
#include "numerics/work_precision.h"

namespace tumble::numerics {
namespace {

// Phase-space error at t_end = 5 s of the oscillator omega = 1 rad/s from (1, 0).
double oscillatorError(Method method, double dt) {
  const HarmonicOscillator system(1.0);
  const Eigen::VectorXd y0 = Eigen::Vector2d(1.0, 0.0);
  const double tEnd = 5.0;
  const int steps = stepsFor(tEnd, dt);
  Integrator integrator(method, 2);
  Eigen::VectorXd y = y0;
  integrateFixed(integrator, system, 0.0, y, tEnd / steps, steps);
  return (y - system.exactState(tEnd, y0)).norm();
}

double measuredOrder(Method method, std::vector<double> dts) {
  std::vector<double> errors;
  for (double dt : dts) errors.push_back(oscillatorError(method, dt));
  return fitOrder(dts, errors);
}

// dt ranges in the asymptotic regime: errors well above round-off
// (RK4 ~1e-8 at its smallest dt) and below O(1).
const std::vector<double> kFirstOrderDts = {0.01, 0.005, 0.0025, 0.00125, 0.000625};
const std::vector<double> kSecondOrderDts = {0.04, 0.02, 0.01, 0.005};
const std::vector<double> kFourthOrderDts = {0.2, 0.1, 0.05, 0.025};

TEST(IntegratorOrder, ExplicitEulerIsFirstOrder) {
  EXPECT_NEAR(measuredOrder(Method::ExplicitEuler, kFirstOrderDts), 1.0, 0.2);
}
TEST(IntegratorOrder, SymplecticEulerIsFirstOrder) {
  EXPECT_NEAR(measuredOrder(Method::SymplecticEuler, kFirstOrderDts), 1.0, 0.2);
}
TEST(IntegratorOrder, HeunIsSecondOrder) {
  EXPECT_NEAR(measuredOrder(Method::Heun, kSecondOrderDts), 2.0, 0.2);
}
TEST(IntegratorOrder, Rk4IsFourthOrder) {
  EXPECT_NEAR(measuredOrder(Method::Rk4, kFourthOrderDts), 4.0, 0.2);
}
TEST(IntegratorOrder, VerletIsSecondOrder) {
  EXPECT_NEAR(measuredOrder(Method::Verlet, kSecondOrderDts), 2.0, 0.2);
}
TEST(IntegratorOrder, ImplicitEulerIsFirstOrder) {
  EXPECT_NEAR(measuredOrder(Method::ImplicitEuler, kFirstOrderDts), 1.0, 0.2);
}
TEST(IntegratorOrder, ImplicitMidpointIsSecondOrder) {
  EXPECT_NEAR(measuredOrder(Method::ImplicitMidpoint, kSecondOrderDts), 2.0, 0.2);
}
TEST(IntegratorOrder, Sdirk2IsSecondOrder) {
  EXPECT_NEAR(measuredOrder(Method::Sdirk2, kSecondOrderDts), 2.0, 0.2);
}

TEST(IntegratorOrder, Sdirk2IsSecondOrderOnTheNonlinearPendulumWithoutAnalyticJacobian) {
  // Finite-difference Jacobian path and a nonlinear force: still order 2.
  struct FdPendulum final : SecondOrderSystem {
    int dofs() const override { return 1; }
    void acceleration(double, ConstRef q, ConstRef, Ref a) const override {
      a[0] = -9.81 * std::sin(q[0]);
    }
  } system;
  auto errorAt = [&](double dt) {
    const int steps = stepsFor(2.0, dt);
    Eigen::VectorXd coarse = Eigen::Vector2d(2.0, 0.0), fine = coarse;
    Integrator sdirk(Method::Sdirk2, 2), rk4(Method::Rk4, 2);
    integrateFixed(sdirk, system, 0.0, coarse, 2.0 / steps, steps);
    integrateFixed(rk4, system, 0.0, fine, 2.0 / 20000, 20000);
    return (coarse - fine).norm();
  };
  const std::vector<double> dts = {0.02, 0.01, 0.005, 0.0025};
  std::vector<double> errors;
  for (double dt : dts) errors.push_back(errorAt(dt));
  EXPECT_NEAR(fitOrder(dts, errors), 2.0, 0.2);
}

// Max |E - E0| over the first and the last third of 1e5 steps.
struct EnergyThirds {
  double first = 0.0;
  double last = 0.0;
};

EnergyThirds energyErrorThirds(Method method) {
  constexpr int kSteps = 100000;
  constexpr double kDt = 0.05;  // omega*dt = 0.05: 125 steps per period, 800 periods
  const HarmonicOscillator system(1.0);
  Integrator integrator(method, 2);
  Eigen::VectorXd y = Eigen::Vector2d(1.0, 0.0);
  const double e0 = *system.energy(y);
  EnergyThirds out;
  for (int i = 0; i < kSteps; ++i) {
    integrator.step(system, i * kDt, y, kDt);
    const double err = std::abs(*system.energy(y) - e0);
    if (i < kSteps / 3) out.first = std::max(out.first, err);
    if (i >= 2 * kSteps / 3) out.last = std::max(out.last, err);
  }
  return out;
}

TEST(IntegratorEnergy, SymplecticEulerEnergyErrorStaysBoundedOver1e5Steps) {
  const EnergyThirds e = energyErrorThirds(Method::SymplecticEuler);
  EXPECT_LT(e.last, 1.1 * e.first);
  EXPECT_LT(e.last, 0.05 * 0.5);  // ~ omega*dt/2 of E0 = 0.5, never growing
}

TEST(IntegratorEnergy, VerletEnergyErrorStaysBoundedOver1e5Steps) {
  const EnergyThirds e = energyErrorThirds(Method::Verlet);
  EXPECT_LT(e.last, 1.1 * e.first);
  EXPECT_LT(e.last, 1e-3 * 0.5);  // ~ (omega*dt)^2/8 of E0
}

TEST(IntegratorEnergy, ExplicitEulerEnergyErrorGrowsOver1e5Steps) {
  const EnergyThirds e = energyErrorThirds(Method::ExplicitEuler);
  // Each step multiplies E by 1 + (omega dt)^2: the last third is e^80 times worse.
  EXPECT_GT(e.last, 1e6 * e.first);
}

TEST(IntegratorNames, CanonicalNamesAndAliasesRoundTrip) {
  for (const MethodInfo& info : methodTable()) {
    Result<Method> m = parseMethod(info.name);
    ASSERT_TRUE(m.ok()) << info.name;
    EXPECT_EQ(*m, info.method);
  }
  EXPECT_EQ(*parseMethod("trapezoid"), Method::Heun);
  EXPECT_EQ(*parseMethod("leapfrog"), Method::Verlet);
  EXPECT_EQ(*parseMethod("semi_implicit_euler"), Method::SymplecticEuler);
}

TEST(IntegratorNames, BadNameListsEveryValidName) {
  Result<Method> m = parseMethod("rk5");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().find("rk5"), std::string::npos);
  for (const MethodInfo& info : methodTable())
    EXPECT_NE(m.error().find(info.name), std::string::npos) << m.error();
}

TEST(IntegratorNames, SymplecticMethodsRefuseFirstOrderSystems) {
  const LinearDecay decay(1.0);
  EXPECT_FALSE(checkMethodFor(Method::Verlet, decay).ok());
  EXPECT_FALSE(checkMethodFor(Method::SymplecticEuler, decay).ok());
  EXPECT_TRUE(checkMethodFor(Method::Rk4, decay).ok());
  EXPECT_TRUE(checkMethodFor(Method::Verlet, HarmonicOscillator(1.0)).ok());
}

TEST(Jacobian, FiniteDifferencesMatchTheAnalyticJacobian) {
  const SpringChain chain(6, 400.0);
  const Pendulum pendulum(9.81);
  Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(12, -0.3, 0.5);
  Eigen::MatrixXd analytic, numeric;
  jacobian(chain, 0.0, y, analytic);
  finiteDifferenceJacobian(chain, 0.0, y, numeric);
  EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-6 * 4 * 400.0);
  const Eigen::VectorXd yp = Eigen::Vector2d(1.3, -0.4);
  jacobian(pendulum, 0.0, yp, analytic);
  finiteDifferenceJacobian(pendulum, 0.0, yp, numeric);
  EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(Integrator, VerletReusesTheEndAccelerationAndMatchesAFreshStart) {
  const Pendulum system(9.81);
  Integrator cached(Method::Verlet, 2);
  Eigen::VectorXd a = Eigen::Vector2d(2.0, 0.0), b = a;
  for (int i = 0; i < 100; ++i) {
    cached.step(system, i * 0.01, a, 0.01);
    Integrator fresh(Method::Verlet, 2);  // no cache: evaluates the start acceleration
    fresh.step(system, i * 0.01, b, 0.01);
  }
  EXPECT_EQ(a, b);
  EXPECT_EQ(cached.stats().derivativeEvaluations, 101);  // one per step plus the first
}

TEST(Integrator, ImplicitMethodsConvergeOnLargePendulumSteps) {
  const Pendulum system(9.81);
  for (Method method : {Method::ImplicitEuler, Method::ImplicitMidpoint, Method::Sdirk2}) {
    Integrator integrator(method, 2);
    Eigen::VectorXd y = Eigen::Vector2d(2.0, 0.0);
    for (int i = 0; i < 100; ++i) {
      const StepInfo info = integrator.step(system, i * 0.2, y, 0.2);  // omega0*dt = 0.63
      ASSERT_TRUE(info.converged) << methodName(method) << " step " << i;
    }
    EXPECT_TRUE(y.allFinite());
    EXPECT_EQ(integrator.stats().newtonFailures, 0);
  }
}

}  // namespace
}  // namespace tumble::numerics
