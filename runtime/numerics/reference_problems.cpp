#include "numerics/reference_problems.h"

#include <algorithm>
#include <cmath>

#include "numerics/elliptic.h"
#include "numerics/systems.h"

namespace tumble::numerics {

int integrateFixed(Integrator& integrator, const OdeSystem& system, double t0_s,
                   Eigen::VectorXd& y, double dt_s, int steps) {
  for (int i = 0; i < steps; ++i) {
    integrator.step(system, t0_s + i * dt_s, y, dt_s);
    if (!y.allFinite()) return i + 1;
  }
  return steps;
}

int stepsFor(double tEnd_s, double dt_s) {
  // The 1e-9 keeps t_end/dt = 100.0000000001 from becoming 101 steps.
  return std::max(1, static_cast<int>(std::ceil(tEnd_s / dt_s * (1.0 - 1e-9))));
}

namespace {

// Everything one prepared run owns; shared by its two closures.
struct OdeRunState {
  std::unique_ptr<OdeSystem> system;
  std::unique_ptr<Integrator> integrator;
  Eigen::VectorXd y0, y;
  std::vector<Eigen::VectorXd> trajectory, referenceTrajectory;  // errorAlongTrajectory only
  Eigen::VectorXd referenceEnd;
  double dt_s = 0.0;
  int steps = 0;
};

}  // namespace

PrecisionProblem toPrecisionProblem(OdeProblem problem) {
  PrecisionProblem out;
  out.name = problem.name;
  out.description = problem.description;
  out.errorUnit = problem.errorUnit;
  out.tEnd_s = problem.tEnd_s;
  out.dtMin_s = problem.dtMin_s;
  out.dtMax_s = problem.dtMax_s;
  out.prepare = [p = std::move(problem)](Method method, double dt_s) -> Result<PreparedRun> {
    auto state = std::make_shared<OdeRunState>();
    state->system = p.makeSystem();
    if (Status ok = checkMethodFor(method, *state->system); !ok) return makeError(ok.error());
    state->integrator = std::make_unique<Integrator>(method, state->system->dimension());
    state->steps = stepsFor(p.tEnd_s, dt_s);
    state->dt_s = p.tEnd_s / state->steps;
    state->y0 = p.y0;
    state->y = p.y0;
    if (p.errorAlongTrajectory) {
      state->trajectory.assign(state->steps, p.y0);
      for (int i = 1; i <= state->steps; ++i)
        state->referenceTrajectory.push_back(p.reference(i * state->dt_s));
    } else {
      state->referenceEnd = p.reference(p.tEnd_s);
    }
    PreparedRun run;
    run.dt_s = state->dt_s;
    run.integrate = [state] {
      OdeRunState& s = *state;
      s.y = s.y0;
      for (int i = 0; i < s.steps; ++i) {
        s.integrator->step(*s.system, i * s.dt_s, s.y, s.dt_s);
        if (!s.trajectory.empty()) s.trajectory[i] = s.y;  // preallocated: no allocation
      }
    };
    run.error = [state, measure = p.errorMeasure] {
      const OdeRunState& s = *state;
      if (s.trajectory.empty()) return measure(s.y, s.referenceEnd);
      double worst = 0.0;
      for (int i = 0; i < s.steps; ++i) {
        const double e = measure(s.trajectory[i], s.referenceTrajectory[i]);
        if (!std::isfinite(e)) return e;
        worst = std::max(worst, e);
      }
      return worst;
    };
    return run;
  };
  return out;
}

namespace {
constexpr double kOscillatorOmega_rad_s = 1.0;
constexpr double kDecayRate_per_s = 1000.0;
constexpr int kChainMasses = 10;
constexpr double kChainStiffness_per_s2 = 1e4;  // k/m
}  // namespace

// Oscillator: omega = 1 rad/s, so omega*dt is dt; 10 s is ~1.6 periods, not a
// whole number, so phase and amplitude errors both show. Error: distance in
// phase space with v scaled by 1/omega (m).
OdeProblem harmonicOscillatorProblem() {
  constexpr double kOmega = kOscillatorOmega_rad_s;
  OdeProblem p;
  p.name = "harmonic_oscillator";
  p.description = "q'' = -omega^2 q, omega = 1 rad/s, q0 = 1 m, t_end = 10 s (exact solution)";
  p.errorUnit = "m";
  p.makeSystem = [] { return std::make_unique<HarmonicOscillator>(kOscillatorOmega_rad_s); };
  p.y0 = Eigen::Vector2d(1.0, 0.0);
  p.tEnd_s = 10.0;
  p.dtMin_s = 1e-3;
  p.dtMax_s = 0.3;
  p.reference = [y0 = p.y0](double t) {
    return HarmonicOscillator(kOscillatorOmega_rad_s).exactState(t, y0);
  };
  p.errorMeasure = [](const Eigen::VectorXd& y, const Eigen::VectorXd& r) {
    return std::hypot(y[0] - r[0], (y[1] - r[1]) / kOmega);
  };
  return p;
}

// Pendulum: L = 1 m, released at rest from 2 rad (115 deg), where the period
// is 1.35 times the small-angle one. After exactly three periods (K(k) by the
// AGM) the exact state is back at (theta0, 0).
OdeProblem pendulumProblem() {
  constexpr double kGOverL = kPendulumGOverL_per_s2;
  constexpr double kTheta0 = kPendulumTheta0_rad;
  constexpr int kPeriods = 3;
  const double period = pendulumPeriod_s(kGOverL, kTheta0);
  OdeProblem p;
  p.name = "pendulum";
  p.description =
      "theta'' = -(g/L) sin theta, g/L = 9.81 1/s^2, theta0 = 2 rad, 3 exact periods "
      "(elliptic integral K by AGM). Measured at the release point, where semi-implicit "
      "Euler's O(dt) half-step velocity offset cancels, so it shows order 2 here";
  p.errorUnit = "rad";
  p.makeSystem = [] { return std::make_unique<Pendulum>(kPendulumGOverL_per_s2); };
  p.y0 = Eigen::Vector2d(kTheta0, 0.0);
  p.tEnd_s = kPeriods * period;
  p.dtMin_s = 1e-3;
  p.dtMax_s = 0.2;
  p.reference = [y0 = p.y0, tEnd = p.tEnd_s](double t) {
    TUMBLE_ASSERT(std::abs(t - tEnd) < 1e-9 * tEnd,
                  "pendulum reference is known only after whole periods (t_end).");
    return y0;
  };
  p.errorMeasure = [omega0 = std::sqrt(kGOverL)](const Eigen::VectorXd& y,
                                                 const Eigen::VectorXd& r) {
    return std::hypot(y[0] - r[0], (y[1] - r[1]) / omega0);
  };
  return p;
}

// Stiff decay: c = 1000 1/s and dt from 1e-4 to 0.1 s, i.e. c*dt from 0.1 to
// 100. The end state is ~exp(-200), so the error is the largest deviation
// over the whole trajectory.
OdeProblem stiffDecayProblem() {
  constexpr double kRate = kDecayRate_per_s;
  OdeProblem p;
  p.name = "stiff_decay";
  p.description = "x' = -c x, c = 1000 1/s, x0 = 1, t_end = 0.2 s, c*dt from 0.1 to 100; "
                  "error = max over steps";
  p.errorUnit = "1";
  p.makeSystem = [] { return std::make_unique<LinearDecay>(kDecayRate_per_s); };
  p.y0 = Eigen::VectorXd::Ones(1);
  p.tEnd_s = 0.2;
  p.dtMin_s = 0.1 / kRate;
  p.dtMax_s = 100.0 / kRate;
  p.reference = [](double t) { return Eigen::VectorXd::Constant(1, std::exp(-kRate * t)); };
  p.errorMeasure = [](const Eigen::VectorXd& y, const Eigen::VectorXd& r) {
    return std::abs(y[0] - r[0]);
  };
  p.errorAlongTrajectory = true;
  return p;
}

// Stiff spring chain: 10 masses, k/m = 1e4 1/s^2; normal modes from 28 to
// 196 rad/s, so at dt = 1/60 s omega_max*dt = 3.3, past every explicit
// method's limit. Plucked: a triangle with 0.1 m at the middle, at rest,
// which excites every odd mode. Error: largest position error (m) at t_end.
OdeProblem stiffSpringChainProblem() {
  constexpr int kMasses = kChainMasses;
  OdeProblem p;
  p.name = "stiff_spring_chain";
  p.description = "10 masses between walls, k/m = 1e4 1/s^2 (modes 28..196 rad/s), plucked "
                  "0.1 m, t_end = 1 s (exact normal modes)";
  p.errorUnit = "m";
  p.makeSystem = [] { return std::make_unique<SpringChain>(kChainMasses, kChainStiffness_per_s2); };
  p.y0 = Eigen::VectorXd::Zero(2 * kMasses);
  for (int i = 1; i <= kMasses; ++i) {
    const double x = static_cast<double>(i) / (kMasses + 1);  // 0..1 along the chain
    p.y0[i - 1] = 0.1 * (x < 0.5 ? 2.0 * x : 2.0 * (1.0 - x));
  }
  p.tEnd_s = 1.0;
  p.dtMin_s = 1e-4;
  p.dtMax_s = 1.0 / 60.0;
  p.reference = [y0 = p.y0](double t) {
    return SpringChain(kChainMasses, kChainStiffness_per_s2).exactState(t, y0);
  };
  p.errorMeasure = [](const Eigen::VectorXd& y, const Eigen::VectorXd& r) {
    return (y.head(kMasses) - r.head(kMasses)).lpNorm<Eigen::Infinity>();
  };
  return p;
}

std::vector<OdeProblem> builtinOdeProblems() {
  return {harmonicOscillatorProblem(), pendulumProblem(), stiffDecayProblem(),
          stiffSpringChainProblem()};
}

std::vector<PrecisionProblem> builtinPrecisionProblems() {
  std::vector<PrecisionProblem> out;
  for (OdeProblem& p : builtinOdeProblems()) out.push_back(toPrecisionProblem(std::move(p)));
  return out;
}

}  // namespace tumble::numerics
