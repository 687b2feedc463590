// Reference problems: the analytic answers they are measured against must
// themselves be right, checked against independent computations.
#include <gtest/gtest.h>

#include <cmath>
#include <Eigen/Eigenvalues>
#include <numbers>

#include "numerics/elliptic.h"
#include "numerics/integrator.h"
#include "numerics/reference_problems.h"
#include "numerics/systems.h"

namespace tumble::numerics {
namespace {

TEST(Elliptic, CompleteEllipticKMatchesClosedForms) {
  EXPECT_DOUBLE_EQ(completeEllipticK(0.0), std::numbers::pi / 2);
  // K(1/sqrt 2) = Gamma(1/4)^2 / (4 sqrt(pi)), the lemniscatic case.
  const double lemniscatic =
      std::tgamma(0.25) * std::tgamma(0.25) / (4.0 * std::sqrt(std::numbers::pi));
  EXPECT_NEAR(completeEllipticK(1.0 / std::sqrt(2.0)), lemniscatic, 1e-14);
  // Near k = 1: K = L + (k'^2/4)(L - 1) + O(k'^4 L), L = ln(4/k'). (k' = 1e-3
  // keeps k itself exactly representable enough; the input, not the AGM, is
  // what loses digits closer to 1.)
  const double kPrime = 1e-3;
  const double k = std::sqrt(1.0 - kPrime * kPrime);
  const double L = std::log(4.0 / kPrime);
  EXPECT_NEAR(completeEllipticK(k), L + kPrime * kPrime / 4.0 * (L - 1.0), 1e-9);
}

TEST(Elliptic, PeriodFollowsTheSmallAmplitudeSeries) {
  // T = T0 (1 + theta0^2/16 + 11 theta0^4/3072 + O(theta0^6)), T0 = 2 pi sqrt(L/g).
  const double t0 = 2.0 * std::numbers::pi / std::sqrt(9.81);
  const double a = 0.1;
  const double series = t0 * (1.0 + a * a / 16.0 + 11.0 * std::pow(a, 4) / 3072.0);
  EXPECT_NEAR(pendulumPeriod_s(9.81, a) / series, 1.0, 1e-9);
}

// Time when the pendulum's angular velocity next crosses zero from + to -
// after tStart: RK4 at fine dt, then the crossing step is re-taken with the
// step length found by the secant method (so the event is located to the
// method's accuracy, not to the step).
double returnTime(const Pendulum& system, double theta0, double dt, double tStart) {
  Integrator rk4(Method::Rk4, 2);
  Eigen::VectorXd y = Eigen::Vector2d(theta0, 0.0);
  double t = 0.0;
  for (;;) {
    Eigen::VectorXd next = y;
    rk4.step(system, t, next, dt);
    if (t > tStart && y[1] > 0.0 && next[1] <= 0.0) break;
    y = next;
    t += dt;
  }
  auto velocityAfter = [&](double h) {
    Eigen::VectorXd z = y;
    rk4.step(system, t, z, h);
    return z[1];
  };
  double h0 = 0.0, v0 = y[1], h1 = dt, v1 = velocityAfter(dt);
  for (int i = 0; i < 50 && std::abs(v1) > 1e-15; ++i) {
    const double h2 = h1 - v1 * (h1 - h0) / (v1 - v0);
    h0 = h1, v0 = v1, h1 = h2, v1 = velocityAfter(h2);
  }
  return t + h1;
}

TEST(Pendulum, EllipticPeriodMatchesAVeryFineRk4Integration) {
  for (double theta0 : {0.5, 2.0, 3.0}) {
    const Pendulum system(9.81);
    const double exact = pendulumPeriod_s(9.81, theta0);
    const double measured = returnTime(system, theta0, 1e-3, 0.75 * exact);
    EXPECT_NEAR(measured / exact, 1.0, 1e-6) << "theta0 = " << theta0;
  }
}

TEST(SpringChain, NormalModeSolutionMatchesAFineRk4Integration) {
  const SpringChain chain(7, 900.0);
  Eigen::VectorXd y0(14);
  y0 << 0.01, -0.02, 0.03, 0.0, 0.01, 0.02, -0.01, 0.1, 0.0, -0.2, 0.0, 0.3, 0.0, 0.05;
  Integrator rk4(Method::Rk4, 14);
  Eigen::VectorXd y = y0;
  integrateFixed(rk4, chain, 0.0, y, 5e-5, 10000);
  EXPECT_LT((y - chain.exactState(0.5, y0)).lpNorm<Eigen::Infinity>(), 1e-10);
}

TEST(SpringChain, ModeFrequenciesBoundTheSpectrum) {
  const SpringChain chain(10, 1e4);
  EXPECT_NEAR(chain.maxOmega_rad_s(), 200.0 * std::sin(10 * std::numbers::pi / 22), 1e-9);
  // The stiffness matrix's eigenvalues are -omega_j^2.
  Eigen::MatrixXd J;
  jacobian(chain, 0.0, Eigen::VectorXd::Zero(20), J);
  const Eigen::MatrixXd K = J.bottomLeftCorner(10, 10);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K);
  EXPECT_NEAR(-eig.eigenvalues().minCoeff(), std::pow(chain.maxOmega_rad_s(), 2), 1e-6);
  EXPECT_NEAR(-eig.eigenvalues().maxCoeff(), std::pow(chain.minOmega_rad_s(), 2), 1e-6);
}

TEST(ReferenceProblems, EveryBuiltinProblemIsSmallAtSmallDtWithRk4) {
  for (const PrecisionProblem& problem : builtinPrecisionProblems()) {
    Result<PreparedRun> run = problem.prepare(Method::Rk4, problem.dtMin_s);
    ASSERT_TRUE(run.ok()) << problem.name;
    run->integrate();
    EXPECT_LT(run->error(), 1e-6) << problem.name;
    EXPECT_LE(run->dt_s, problem.dtMin_s);
  }
}

TEST(ReferenceProblems, SymplecticMethodOnAFirstOrderProblemIsRefused) {
  const PrecisionProblem decay = toPrecisionProblem(stiffDecayProblem());
  Result<PreparedRun> run = decay.prepare(Method::Verlet, 1e-3);
  ASSERT_FALSE(run.ok());
  EXPECT_NE(run.error().find("second-order"), std::string::npos);
}

}  // namespace
}  // namespace tumble::numerics
