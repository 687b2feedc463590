#pragma once
// The registry of work-precision problems: a plain table, so any module can
// add its own (the rigid-body world, joints, cloth) without Lua and without
// touching this file: build a PrecisionProblem and append it to the vector
// the report runs over.
//
// Two levels:
//   PrecisionProblem  what the runner needs: a name, a dt sweep, and
//                     prepare(method, dt) -> {integrate, error}. The runner
//                     times integrate() only, so a problem keeps its set-up
//                     and its reference computation out of the measurement.
//   OdeProblem        the common case: an OdeSystem, an initial state and an
//                     exact (or converged) reference; toPrecisionProblem()
//                     turns it into the level above.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/result.h"
#include "numerics/integrator.h"
#include "numerics/ode.h"

namespace tumble::numerics {

/// One (method, dt) run made ready to measure.
struct PreparedRun {
  std::function<void()> integrate;  // timed: a full run from the initial state to t_end
  std::function<double()> error;    // untimed: error of the last integrate()
  double dt_s = 0.0;                // the step actually used (t_end / whole number of steps)
};

struct PrecisionProblem {
  std::string name;         // CSV key and file-name part: [a-z0-9_]
  std::string description;  // one line for the Markdown
  const char* errorUnit = "";  // unit of error(): "m", "rad", "1" (a literal)
  double tEnd_s = 0.0;
  double dtMin_s = 0.0;  // the sweep is geometric between these
  double dtMax_s = 0.0;
  /// Prepares a run, or says why this method cannot run this problem.
  std::function<Result<PreparedRun>(Method method, double dt_s)> prepare;
};

struct OdeProblem {
  std::string name;
  std::string description;
  const char* errorUnit = "";  // a literal: "m", "rad", "1"
  std::function<std::unique_ptr<OdeSystem>()> makeSystem;
  Eigen::VectorXd y0;
  double tEnd_s = 0.0;
  double dtMin_s = 0.0;
  double dtMax_s = 0.0;
  /// Exact or converged state at time t. Needed at t_end, and at every step
  /// time when errorAlongTrajectory.
  std::function<Eigen::VectorXd(double t_s)> reference;
  /// Error of a state against the reference state, in errorUnit.
  std::function<double(const Eigen::VectorXd& y, const Eigen::VectorXd& yRef)> errorMeasure;
  /// Error = max over all steps (for decays, whose end state is ~0) instead
  /// of the error at t_end.
  bool errorAlongTrajectory = false;
};

/// Steps y from t0 with `steps` equal steps of dt. Stops early, returning
/// the number of steps done, if the state stops being finite.
int integrateFixed(Integrator& integrator, const OdeSystem& system, double t0_s,
                   Eigen::VectorXd& y, double dt_s, int steps);

/// Number of equal steps covering t_end with steps no longer than dt.
int stepsFor(double tEnd_s, double dt_s);

PrecisionProblem toPrecisionProblem(OdeProblem problem);

// The built-in problems (parameters in reference_problems.cpp, with why).
// The pendulum's parameters are shared with the stability-region measurement.
constexpr double kPendulumGOverL_per_s2 = 9.81;  // L = 1 m
constexpr double kPendulumTheta0_rad = 2.0;      // 115 deg: period 1.35x the small-angle one
OdeProblem harmonicOscillatorProblem();
OdeProblem pendulumProblem();
OdeProblem stiffDecayProblem();
OdeProblem stiffSpringChainProblem();
std::vector<OdeProblem> builtinOdeProblems();
std::vector<PrecisionProblem> builtinPrecisionProblems();

}  // namespace tumble::numerics
