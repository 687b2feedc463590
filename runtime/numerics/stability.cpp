#include "numerics/stability.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "numerics/elliptic.h"
#include "numerics/reference_problems.h"
#include "numerics/systems.h"
#include "numerics/work_precision.h"

namespace tumble::numerics {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kDecaySteps = 1000;
constexpr double kScanFactor = 1.25;
// Scan ranges of the scaled step.
constexpr double kDecayLo = 1e-2, kDecayHi = 1e6;
constexpr double kPendulumLo = 1e-3, kPendulumHi = 1e2;
constexpr double kPendulumGrowthTolerance = 0.05;
constexpr double kSmallAmplitude_rad = 0.01;  // 101 E0 is reached at 0.1 rad, still linear

std::string caseCell(const std::optional<double>& value) {
  return value ? formatNumber(*value) : std::string();
}

double theoryLimit(const std::string& problem, Method method) {
  const bool decay = problem == "stiff_decay";
  switch (method) {
    case Method::ExplicitEuler: return decay ? 2.0 : 0.0;  // |1 + i w| > 1 for all w
    case Method::Heun: return decay ? 2.0 : 0.0;           // |R(i w)|^2 = 1 + w^4/4
    case Method::Rk4: return decay ? rk4RealStabilityLimit() : 2.0 * std::numbers::sqrt2;
    case Method::SymplecticEuler:
    case Method::Verlet: return 2.0;  // trace of the step matrix 2 - (omega dt)^2 >= -2
    case Method::ImplicitEuler:
    case Method::ImplicitMidpoint:
    case Method::Sdirk2: return kInf;  // A-stable
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// A plucked chain: a triangle of height peak_m at rest, exciting every odd mode.
Eigen::VectorXd pluckedChain(int masses, double peak_m) {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * masses);
  for (int i = 1; i <= masses; ++i) {
    const double x = static_cast<double>(i) / (masses + 1);
    y[i - 1] = peak_m * (x < 0.5 ? 2.0 * x : 2.0 * (1.0 - x));
  }
  return y;
}

// RFC 4180 quoting for free text.
std::string csvText(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

double largestStable(const std::function<bool(double)>& isStable, double lo, double hi,
                     int bisections) {
  if (!isStable(lo)) return 0.0;
  double stable = lo;
  double unstable = kInf;
  for (double x = lo * kScanFactor; x <= hi * (1.0 + 1e-12); x *= kScanFactor) {
    if (!isStable(x)) {
      unstable = x;
      break;
    }
    stable = x;
  }
  if (!std::isfinite(unstable)) return kInf;
  for (int i = 0; i < bisections; ++i) {
    const double mid = 0.5 * (stable + unstable);
    (isStable(mid) ? stable : unstable) = mid;
  }
  return stable;
}

bool decayIsStable(Method method, double cDt) {
  const LinearDecay system(1.0);
  Integrator integrator(method, 1);
  Eigen::VectorXd x = Eigen::VectorXd::Ones(1);
  for (int i = 0; i < kDecaySteps; ++i) {
    integrator.step(system, i * cDt, x, cDt);
    if (!std::isfinite(x[0]) || std::abs(x[0]) > 1.0) return false;
  }
  return true;
}

bool pendulumIsStable(Method method, double omega0Dt, double amplitude_rad, int horizonPeriods) {
  const Pendulum system(kPendulumGOverL_per_s2);
  const double omega0 = std::sqrt(kPendulumGOverL_per_s2);
  const double dt = omega0Dt / omega0;
  const double horizon = horizonPeriods * pendulumPeriod_s(kPendulumGOverL_per_s2, amplitude_rad);
  const int steps = stepsFor(horizon, dt);
  const double separatrix = 2.0 * kPendulumGOverL_per_s2;
  Integrator integrator(method, 2);
  Eigen::VectorXd y = Eigen::Vector2d(amplitude_rad, 0.0);
  const double e0 = *system.energy(y);
  double maxFirst = e0;
  double maxSecond = 0.0;
  for (int i = 0; i < steps; ++i) {
    integrator.step(system, i * dt, y, dt);
    if (!y.allFinite()) return false;
    const double e = *system.energy(y);
    if (e >= separatrix || e > (1.0 + OutcomeThresholds{}.blowUpEnergyGrowth) * e0) return false;
    double& halfMax = 2 * i < steps ? maxFirst : maxSecond;
    halfMax = std::max(halfMax, e);
  }
  return maxSecond <= (1.0 + kPendulumGrowthTolerance) * maxFirst;
}

double rk4RealStabilityLimit() {
  // p(x) = 1 - x/2 + x^2/6 - x^3/24: p(2) = 1/3 > 0, p(3) = -1/8 < 0, one root.
  auto p = [](double x) { return 1.0 - x / 2.0 + x * x / 6.0 - x * x * x / 24.0; };
  double lo = 2.0, hi = 3.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (p(mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<StabilityLimit> measureStabilityLimits(bool quick) {
  const int bisections = quick ? 14 : 30;
  const double omega0 = std::sqrt(kPendulumGOverL_per_s2);
  const LinearDecay decay(1.0);
  std::vector<StabilityLimit> out;
  for (const MethodInfo& info : methodTable()) {
    if (checkMethodFor(info.method, decay).ok()) {
      StabilityLimit l;
      l.problem = "stiff_decay";
      l.method = info.method;
      l.scale = "c*dt";
      l.measured = largestStable([&](double x) { return decayIsStable(info.method, x); },
                                 kDecayLo, kDecayHi, bisections);
      l.measuredDt_s = l.measured;  // c = 1 1/s
      l.theory = theoryLimit(l.problem, info.method);
      out.push_back(l);
    }
    for (const bool small : {false, true}) {
      const double amplitude = small ? kSmallAmplitude_rad : kPendulumTheta0_rad;
      StabilityLimit l;
      l.problem = small ? "pendulum_small_amplitude" : "pendulum";
      l.method = info.method;
      l.scale = "omega0*dt";
      l.measured = largestStable(
          [&](double x) { return pendulumIsStable(info.method, x, amplitude); }, kPendulumLo,
          kPendulumHi, bisections);
      l.measuredDt_s = l.measured / omega0;
      l.theory = theoryLimit(l.problem, info.method);
      if (l.theory == 0.0)
        l.note = "energy grows at every dt; the measured limit depends on the 20-period horizon";
      else if (std::isinf(l.theory) && !small)
        l.note = "nonlinear: past this step Newton stops converging or lands on a root over "
                 "the top";
      out.push_back(l);
    }
  }
  for (StabilityLimit& l : out) {
    const bool decay = l.problem == "stiff_decay";
    const double lo = decay ? kDecayLo : kPendulumLo;
    const double hi = decay ? kDecayHi : kPendulumHi;
    if (l.measured == 0.0)
      l.note = "unstable at the smallest value tried (" + formatNumber(lo) + ")";
    else if (std::isinf(l.measured))
      l.note = "stable at every value tried, up to " + formatNumber(hi);
  }
  return out;
}

const char* outcomeName(Outcome outcome) {
  switch (outcome) {
    case Outcome::Stable: return "stable";
    case Outcome::Drifting: return "drifting";
    case Outcome::BlewUp: return "blew_up";
  }
  return "unknown";
}

StabilityRow monitorOdeRun(const std::string& caseName, const OdeSystem& system,
                           const Eigen::VectorXd& y0, Method method, double dt_s, double tEnd_s,
                           const OutcomeThresholds& thresholds) {
  TUMBLE_ASSERT(system.energy(y0).has_value(),
                "monitorOdeRun classifies by energy; the system must implement energy().");
  StabilityRow row;
  row.caseName = caseName;
  row.method = methodName(method);
  row.dt_s = dt_s;
  const double e0 = *system.energy(y0);
  double e = e0;
  Integrator integrator(method, system.dimension());
  Eigen::VectorXd y = y0;
  const int steps = stepsFor(tEnd_s, dt_s);
  for (int i = 0; i < steps; ++i) {
    integrator.step(system, i * dt_s, y, dt_s);
    const double t = (i + 1) * dt_s;
    if (!y.allFinite()) {
      row.outcome = Outcome::BlewUp;
      row.timeToFailure_s = t;
      row.nanEvents = 1;  // the run stops at the first one
      break;
    }
    e = *system.energy(y);
    if (e > (1.0 + thresholds.blowUpEnergyGrowth) * std::abs(e0)) {
      row.outcome = Outcome::BlewUp;
      row.timeToFailure_s = t;
      break;
    }
  }
  row.energyGrowth = (e - e0) / std::abs(e0);
  if (row.outcome != Outcome::BlewUp && std::abs(*row.energyGrowth) > thresholds.driftTolerance)
    row.outcome = Outcome::Drifting;
  return row;
}

std::vector<StabilityCase> builtinStabilityCases() {
  std::vector<StabilityCase> cases;
  {
    StabilityCase c;
    c.name = "spring_k1e6";
    c.description = "one mass on a spring, k/m = 1e6 1/s^2 (omega = 1000 rad/s, omega*dt = 16.7 "
                    "at 60 Hz), x0 = 1 cm; 10 s (quick: 1 s)";
    c.dts_s = {1.0 / 60.0};
    c.run = [name = c.name](Method method, double dt, bool quick) {
      const HarmonicOscillator spring(1000.0);
      return monitorOdeRun(name, spring, Eigen::Vector2d(0.01, 0.0), method, dt,
                           quick ? 1.0 : 10.0);
    };
    cases.push_back(std::move(c));
  }
  {
    StabilityCase c;
    c.name = "spring_chain_stiff";
    c.description = "20 masses between walls, k/m = 1e6 1/s^2 per spring (modes 150..2000 "
                    "rad/s), plucked 1 cm; 10 s (quick: 1 s)";
    c.dts_s = {1.0 / 60.0, 1.0 / 600.0};
    c.run = [name = c.name](Method method, double dt, bool quick) {
      constexpr int kMasses = 20;
      const SpringChain chain(kMasses, 1e6);
      return monitorOdeRun(name, chain, pluckedChain(kMasses, 0.01), method, dt,
                           quick ? 1.0 : 10.0);
    };
    cases.push_back(std::move(c));
  }
  return cases;
}

std::vector<StabilityRow> runStabilityCases(std::span<const StabilityCase> cases, bool quick,
                                            const std::function<void(const std::string&)>& progress) {
  std::vector<StabilityRow> rows;
  for (const StabilityCase& c : cases) {
    std::vector<Method> methods = c.methods;
    if (methods.empty())
      for (const MethodInfo& info : methodTable()) methods.push_back(info.method);
    for (double dt : c.dts_s)
      for (Method method : methods) {
        rows.push_back(c.run(method, dt, quick));
        const StabilityRow& r = rows.back();
        if (progress)
          progress(r.caseName + " " + r.method + " dt=" + formatNumber(r.dt_s, 4) + " " +
                   outcomeName(r.outcome));
      }
  }
  return rows;
}

std::string stabilityCsv(std::span<const StabilityRow> rows) {
  std::string out =
      "case,method,dt,outcome,time_to_failure_s,energy_growth,penetration_max_m,"
      "joint_error_max_m,nan_events,failed_body\n";
  for (const StabilityRow& r : rows)
    out += r.caseName + "," + r.method + "," + formatNumber(r.dt_s, 9) + "," +
           outcomeName(r.outcome) + "," + caseCell(r.timeToFailure_s) + "," +
           caseCell(r.energyGrowth) + "," + caseCell(r.penetrationMax_m) + "," +
           caseCell(r.jointErrorMax_m) + "," + std::to_string(r.nanEvents) + "," + csvText(r.failedBody) + "\n";
  return out;
}

std::string stabilityRegionsCsv(std::span<const StabilityLimit> limits) {
  std::string out = "problem,method,scale,max_stable_scaled,max_stable_dt_s,theory_scaled,note\n";
  for (const StabilityLimit& l : limits)
    out += l.problem + "," + methodName(l.method) + "," + l.scale + "," +
           formatNumber(l.measured) + "," + formatNumber(l.measuredDt_s) + "," +
           formatNumber(l.theory) + "," + csvText(l.note) + "\n";
  return out;
}

std::string stabilityMarkdown(std::span<const StabilityRow> rows,
                              std::span<const StabilityLimit> limits,
                              std::span<const StabilityCase> cases) {
  std::string md = "# Stability report\n\n";
  md += "Raw data: `stability.csv` (cases) and `stability_regions.csv` (largest stable steps).\n\n";
  md += "Outcomes: **blew_up** = a state became non-finite or the energy grew past 101x its "
        "start (the run stops; time to failure says when); **drifting** = finite, but the "
        "energy at the end differs from the start by more than 5% (numerical damping counts); "
        "**stable** = otherwise. Energy growth = (E_end - E0)/|E0| (-1: all energy "
        "damped away). Empty cells: not applicable to the case.\n\n";
  md += "## Cases\n\n";
  for (const StabilityCase& c : cases) md += "- `" + c.name + "`: " + c.description + "\n";
  md += "\n| case | method | dt (s) | outcome | time to failure (s) | energy growth | "
        "penetration max (m) | joint error max (m) | NaN events | failed body |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const StabilityRow& r : rows)
    md += "| " + r.caseName + " | " + r.method + " | " + formatNumber(r.dt_s, 4) + " | " +
          outcomeName(r.outcome) + " | " + caseCell(r.timeToFailure_s) + " | " +
          (r.energyGrowth ? formatNumber(*r.energyGrowth, 3) : "") + " | " +
          caseCell(r.penetrationMax_m) + " | " + caseCell(r.jointErrorMax_m) + " | " +
          std::to_string(r.nanEvents) + " | " + r.failedBody + " |\n";

  md += "\n## Stability regions\n\n";
  md += "Largest stable scaled step, measured, beside the linear theory (|R(z)| <= 1 for the "
        "test equation y' = lambda y; derivations in runtime/numerics/integrator.cpp).\n\n"
        "- stiff_decay, x' = -c x: stable = 1000 steps finite with |x_n| <= |x_0|; scale c*dt.\n"
        "- pendulum (theta0 = 2 rad) and pendulum_small_amplitude (theta0 = 0.01 rad), "
        "omega0 = sqrt(g/L): stable = 20 periods finite, never over the top, energy below 101 E0, "
        "energy maximum of the second half within 5% of the first half's; scale omega0*dt. The theory column is "
        "for the linearised pendulum: the small-amplitude rows test it, the 2 rad rows show "
        "how far a strongly nonlinear problem departs from it (symplectic methods' bounded "
        "energy error is large enough at big steps to carry the pendulum over the top; for "
        "the implicit methods Newton stops converging, or converges to a spurious root over "
        "the top, which StepInfo::converged reports).\n"
        "- Semi-implicit Euler and Verlet need a second-order system, so they have no decay "
        "row.\n\n";
  md += "| problem | method | measured | theory | largest stable dt (s) | note |\n";
  md += "|---|---|---|---|---|---|\n";
  for (const StabilityLimit& l : limits)
    md += "| " + l.problem + " | " + methodName(l.method) + " | " + l.scale + " = " +
          formatNumber(l.measured, 5) + " | " +
          (std::isinf(l.theory) ? std::string("unconditional") : formatNumber(l.theory, 5)) +
          " | " + formatNumber(l.measuredDt_s, 4) + " | " + l.note + " |\n";
  return md;
}

}  // namespace tumble::numerics
