// The run report's error figures (app/error_audit.h, docs/report.md "Error
// figures"): each must read near zero where the physics is right and must
// show a known error where it is not.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "app/fixed_step.h"
#include "app/scene.h"
#include "physics/constraint_solver.h"
#include "physics/internal/contact_solver.h"

namespace tumble::app {
namespace {

std::unique_ptr<Scene> startScene(const std::string& ref, const std::string& integrator = "") {
  const char* source = std::getenv("TUMBLE_SOURCE_DIR");
  SceneOptions options;
  options.scenarioRef = ref;
  options.modDirs = {std::string(source ? source : ".") + "/tests/app/mods"};
  options.integrator = integrator;
  auto scene = Scene::create(options);
  EXPECT_TRUE(scene) << (scene ? "" : scene.error());
  if (!scene) return nullptr;
  (*scene)->start();
  return std::move(scene.value());
}

void runSteps(Scene& scene, int steps) {
  RunTimings t;
  for (int i = 0; i < steps; ++i) stepScene(scene, StepTime{i * scene.dt_s(), i}, t);
}

// Ball on a world.spring: k = 40 N/m, m = 1 kg (omega = 2 pi rad/s), 0.5 m
// out: E = 5 J. 10 s at 60 Hz with 8 substeps (h = 1/480 s).
constexpr double kSpringEnergy_J = 5, kOmega = 6.32455532, kSteps = 600, kSubsteps = 8;

TEST(ErrorAudit, SpringOscillatingUnderSymplecticEulerShowsNoDrift) {
  auto scene = startScene("audit:spring");
  ASSERT_TRUE(scene);
  runSteps(*scene, int(kSteps));
  const ErrorAudit& a = scene->errorAudit();
  std::printf("[audit] spring, symplectic Euler: gain %.3g J, scale %.3g J, rel %.3g\n", a.energyGainMax_J(),
              a.energyScale_J(), a.energyRelDriftMax());
  // Symplectic Euler keeps a shadow energy; the true energy swings about
  // it by a fraction omega h / 2 of E and never drifts. Bound: omega h E.
  const double h = 1.0 / 60 / kSubsteps;
  EXPECT_LT(a.energyGainMax_J(), kOmega * h * kSpringEnergy_J);
  // The scale counts the spring's energy: 1 J + the 5 J that swing.
  EXPECT_NEAR(a.energyScale_J(), 1 + kSpringEnergy_J, 0.05 * kSpringEnergy_J);
}

TEST(ErrorAudit, SpringUnderExplicitEulerShowsItsEnergyGrowth) {
  auto scene = startScene("audit:spring", "euler");
  ASSERT_TRUE(scene);
  runSteps(*scene, int(kSteps));
  const ErrorAudit& a = scene->errorAudit();
  // Explicit Euler multiplies a linear oscillator's energy by 1 + (omega h)^2
  // at every step: after N substeps E = E0 (1 + (omega h)^2)^N.
  const double h = 1.0 / 60 / kSubsteps, n = kSteps * kSubsteps;
  const double expected_J = kSpringEnergy_J * (std::pow(1 + kOmega * kOmega * h * h, n) - 1);
  std::printf("[audit] spring, explicit Euler: gain %.4g J (analytic %.4g J), rel %.3g\n", a.energyGainMax_J(),
              expected_J, a.energyRelDriftMax());
  EXPECT_NEAR(a.energyGainMax_J(), expected_J, 0.05 * expected_J);
  EXPECT_GT(a.energyRelDriftMax(), 0.5);
}

TEST(ErrorAudit, BlockRestingOnAStaticRampKeepsMomentumAccountedFor) {
  auto scene = startScene("audit:ramp");
  ASSERT_TRUE(scene);
  runSteps(*scene, int(kSteps));
  const ErrorAudit& a = scene->errorAudit();
  std::printf("[audit] ramp: momentum residual %.3g N s, scale %.3g N s, rel %.3g; energy gain %.3g J rel %.3g\n",
              a.momentumResidualMax_Ns(), a.momentumScale_Ns(), a.momentumRelDriftMax(), a.energyGainMax_J(),
              a.energyRelDriftMax());
  // Gravity gives the block m g t = 196 N s in 10 s and the ramp takes it
  // back; what is not accounted for is float rounding of the velocities
  // (2^-23 relative, some thousand substeps): far below 1e-3.
  EXPECT_LT(a.momentumRelDriftMax(), 1e-3);
  EXPECT_LT(a.energyRelDriftMax(), 1e-3);
}

/// A stand-in joint solver for two free bodies moving apart at 1 m/s each:
/// right, it does nothing (these bodies are not joined); faulty, it pushes
/// the first one by 0.01 m/s every substep (momentum from nowhere), or grows
/// both velocities by 0.1 % every substep (energy from nowhere).
class FaultySolver final : public physics::ConstraintSolver {
 public:
  enum class Fault { None, OneSided, AddsEnergy };
  explicit FaultySolver(Fault f) : m_fault(f) {}
  void prepare(const physics::World&, Real, int) override {}
  void warmStart(physics::SolverVelocity* vel, const physics::Body*) override {
    if (m_fault == Fault::OneSided) vel[0].linear += physics::wide(Vec3(Real(0.01), 0, 0));
    if (m_fault == Fault::AddsEnergy)
      for (int i : {0, 1}) vel[i].linear *= Real(1.001);
  }
  Real solve(physics::SolverVelocity*, const physics::Body*, bool) override { return 0; }
  void finish(const physics::World&) override {}

 private:
  Fault m_fault;
};

const ErrorAudit runFaulty(FaultySolver::Fault fault) {
  auto scene = startScene("audit:free");
  if (!scene) return ErrorAudit{};
  physics::World& w = scene->world();
  FaultySolver solver(fault);
  w.setConstraintSolver(&solver);
  runSteps(*scene, 120);
  w.setConstraintSolver(nullptr);
  const ErrorAudit a = scene->errorAudit();
  std::printf("[audit] solver fault %d: momentum residual %.4g N s rel %.3g, energy gain %.4g J rel %.3g\n", int(fault),
              a.momentumResidualMax_Ns(), a.momentumRelDriftMax(), a.energyGainMax_J(), a.energyRelDriftMax());
  return a;
}

TEST(ErrorAudit, AConstraintSolverThatMakesMomentumOrEnergyIsCaught) {
  const double substeps = 120 * kSubsteps;
  // Right: nothing gained, nothing unexplained (float rounding only).
  const ErrorAudit right = runFaulty(FaultySolver::Fault::None);
  EXPECT_LT(right.momentumResidualMax_Ns(), 1e-5);
  EXPECT_LT(right.energyGainMax_J(), 1e-5);
  // One-sided: 0.01 N s a substep, all of it unexplained.
  const ErrorAudit oneSided = runFaulty(FaultySolver::Fault::OneSided);
  EXPECT_NEAR(oneSided.momentumResidualMax_Ns(), 0.01 * substeps, 1e-3 * 0.01 * substeps);
  EXPECT_GT(oneSided.momentumRelDriftMax(), 0.5);
  // Adds energy: E = E0 1.001^(2 n) with E0 = 1 J; the momentum stays 0
  // (both grow alike, in opposite directions).
  const ErrorAudit adds = runFaulty(FaultySolver::Fault::AddsEnergy);
  const double expected_J = std::pow(1.001, 2 * substeps) - 1;
  EXPECT_NEAR(adds.energyGainMax_J(), expected_J, 1e-3 * expected_J);
  EXPECT_GT(adds.energyRelDriftMax(), 0.5);
  EXPECT_LT(adds.momentumResidualMax_Ns(), 1e-4);
}

}  // namespace
}  // namespace tumble::app
