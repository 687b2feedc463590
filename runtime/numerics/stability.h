#pragma once
// Stability: (1) the largest stable step of each method on the decay and
// pendulum problems, beside the linear theory; (2) a registry of stiff and
// extreme cases whose runs are classified stable / drifting / blew_up.
//
// Definitions (the measured numbers mean exactly this):
//   decay x' = -c x, x0 = 1 (c*dt is all that matters, so c = 1):
//     stable at c*dt  <=>  over 1000 steps every x_n is finite and
//     |x_n| <= |x0|. A sign-flipping growth (explicit Euler past c*dt = 2,
//     R < -1) exceeds |x0| at once. For this linear problem it is exactly
//     |R(-c dt)| <= 1.
//   pendulum theta'' = -(g/L) sin theta, theta0 = 2 rad (the work-precision
//     pendulum) and theta0 = 0.01 rad (pendulum_small_amplitude, where the
//     linear theory applies), omega0 = sqrt(g/L); over 20 exact periods:
//     stable at omega0*dt  <=>  every state finite, the energy stays below
//     the over-the-top energy 2 g/L (motion stays qualitatively right) and
//     below 101 E0 (the blow-up threshold of the stability cases; it catches
//     a fast growth that the nonlinearity then saturates), and the energy
//     does not keep growing: its maximum over the second half of the run is
//     at most 5% above its maximum over the first half (5% is above the
//     sampling jitter of a bounded oscillating energy error at large dt).
//     Symplectic Euler's bounded energy error peaks at E0/(1 - omega dt/2)
//     on the linear problem, so the 101 E0 bound puts its limit at 1.98.
//     Methods whose energy grows at every dt (explicit Euler, Heun; linear
//     theory limit 0) get a finite but horizon-dependent number.
//     A-stability is a property of linear problems: at large omega0*dt the
//     implicit equations of the nonlinear pendulum have several roots, and
//     Newton either stops converging or converges to one over the top,
//     which this test calls unstable.
// Largest stable step: scan upward geometrically (x1.25) from the lowest
// value until the first unstable one, then bisect between it and the last
// stable one. Scanning first (not bisecting [lo, hi] directly) copes with
// stability sets that are not a single interval.
//
// Outcome of a stability case run:
//   blew_up   a state became non-finite, or the energy grew past
//             (1 + blowUpEnergyGrowth) * E0; the run stops there and
//             time_to_failure_s says when. Never a crash.
//   drifting  finite throughout, but |E_end - E0| / |E0| > driftTolerance
//             (numerical damping counts: an implicit method that eats all
//             the energy of a stiff spring is drifting, not stable).
//   stable    otherwise.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "numerics/integrator.h"
#include "numerics/ode.h"
#include "numerics/reference_problems.h"

namespace tumble::numerics {

// --- Stability regions ------------------------------------------------------

/// Largest x in [lo, hi] with isStable(x): 0 if unstable already at lo,
/// +inf if stable at every scanned value up to hi. `bisections` halvings of
/// the last x1.25 bracket.
double largestStable(const std::function<bool(double)>& isStable, double lo, double hi,
                     int bisections);

/// Decay test at c*dt (definition above). Any method that can step a
/// first-order system.
bool decayIsStable(Method method, double cDt);

/// Pendulum test at omega0*dt (definition above), released at rest from
/// amplitude_rad, over horizonPeriods exact periods.
bool pendulumIsStable(Method method, double omega0Dt, double amplitude_rad = kPendulumTheta0_rad,
                      int horizonPeriods = 20);

/// RK4's real-axis stability limit: the root x in (2, 3) of
/// 1 - x/2 + x^2/6 - x^3/24 = 0 (R(-x) = 1), found by bisection. 2.7853...
double rk4RealStabilityLimit();

struct StabilityLimit {
  std::string problem;    // "stiff_decay", "pendulum" or "pendulum_small_amplitude"
  Method method;
  std::string scale;      // "c*dt" or "omega0*dt"
  double measured = 0.0;  // largest stable scaled step; 0 / inf, see note
  double measuredDt_s = 0.0;
  double theory = 0.0;    // linear-theory limit of the same scaled step (inf: unconditional)
  std::string note;       // why a 0 or inf is what it is
};

/// Measures every applicable (problem, method) pair. quick: fewer bisections.
std::vector<StabilityLimit> measureStabilityLimits(bool quick);

// --- Stability cases --------------------------------------------------------

enum class Outcome { Stable, Drifting, BlewUp };
const char* outcomeName(Outcome outcome);  // "stable", "drifting", "blew_up"

struct StabilityRow {
  std::string caseName;
  std::string method;
  double dt_s = 0.0;
  Outcome outcome = Outcome::Stable;
  std::optional<double> timeToFailure_s;   // set when blew_up
  std::optional<double> energyGrowth;      // (E_end - E0)/|E0|, at failure if it blew up
  std::optional<double> penetrationMax_m;  // rigid-body cases; empty for ODE cases
  std::optional<double> jointErrorMax_m;   // jointed cases; empty otherwise
  long nanEvents = 0;                      // steps that produced a non-finite state
  std::string failedBody;                  // blew_up: which body / particle failed first (empty: n/a)
};

/// A registry entry. Cases written by other modules (stacks, rag-dolls,
/// projectiles) supply their own run(); the report iterates methods x dts.
struct StabilityCase {
  std::string name;
  std::string description;
  std::vector<double> dts_s;
  std::vector<Method> methods;  // empty: every method in methodTable()
  /// One run; quick = shorter horizon for CI. Must not crash on blow-up.
  std::function<StabilityRow(Method method, double dt_s, bool quick)> run;
};

struct OutcomeThresholds {
  double blowUpEnergyGrowth = 100.0;  // E > 101 E0 is a blow-up
  double driftTolerance = 0.05;       // |E_end/E0 - 1| > 5% is drifting
};

/// Runs an ODE system with an energy from y0 for tEnd_s and classifies it.
StabilityRow monitorOdeRun(const std::string& caseName, const OdeSystem& system,
                           const Eigen::VectorXd& y0, Method method, double dt_s, double tEnd_s,
                           const OutcomeThresholds& thresholds = {});

/// Built-in ODE cases: a spring with k/m = 1e6 at dt = 1/60, a stiff spring chain.
std::vector<StabilityCase> builtinStabilityCases();

std::vector<StabilityRow> runStabilityCases(
    std::span<const StabilityCase> cases, bool quick,
    const std::function<void(const std::string&)>& progress = {});

/// Columns exactly: case,method,dt,outcome,time_to_failure_s,energy_growth,
/// penetration_max_m,joint_error_max_m,nan_events,failed_body (empty cell: not
/// applicable).
std::string stabilityCsv(std::span<const StabilityRow> rows);

/// Columns: problem,method,scale,max_stable_scaled,max_stable_dt_s,theory_scaled,note
/// (note is free text, quoted when it holds a comma).
std::string stabilityRegionsCsv(std::span<const StabilityLimit> limits);

std::string stabilityMarkdown(std::span<const StabilityRow> rows,
                              std::span<const StabilityLimit> limits,
                              std::span<const StabilityCase> cases);

}  // namespace tumble::numerics
