#include "numerics/work_precision.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

namespace tumble::numerics {
namespace {

// Error targets for "which method wins": the cheapest run at or below each.
constexpr double kTargets[] = {1e-2, 1e-4, 1e-6, 1e-8};

// Errors above this are blow-ups, not accuracy; plots leave them out.
constexpr double kPlotErrorCeiling = 1e2;

std::vector<double> dtSweep(double dtMin, double dtMax, int count) {
  std::vector<double> dts;
  if (count <= 1) return {dtMax};
  for (int i = 0; i < count; ++i)
    dts.push_back(dtMax * std::pow(dtMin / dtMax, static_cast<double>(i) / (count - 1)));
  return dts;
}

double timeRun(const std::function<void()>& run, const PrecisionOptions& options) {
  using Clock = std::chrono::steady_clock;
  run();  // warm-up: caches, page faults, lazy allocations
  double best = std::numeric_limits<double>::infinity();
  for (int b = 0; b < std::max(1, options.batches); ++b) {
    long reps = 0;
    const Clock::time_point start = Clock::now();
    double elapsed = 0.0;
    do {
      run();
      ++reps;
      elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    } while (elapsed < options.minBatchSeconds);
    best = std::min(best, elapsed / reps);
  }
  return best;
}

std::string microseconds(double seconds) {
  if (seconds >= 0.1) return formatNumber(seconds, 3) + " s";
  if (seconds >= 1e-4) return formatNumber(seconds * 1e3, 3) + " ms";
  return formatNumber(seconds * 1e6, 3) + " us";
}

std::vector<const PrecisionRow*> rowsOf(std::span<const PrecisionRow> rows,
                                        const std::string& problem) {
  std::vector<const PrecisionRow*> out;
  for (const PrecisionRow& r : rows)
    if (r.problem == problem) out.push_back(&r);
  return out;
}

std::vector<std::string> methodsIn(const std::vector<const PrecisionRow*>& rows) {
  std::vector<std::string> out;
  for (const MethodInfo& info : methodTable())
    for (const PrecisionRow* r : rows)
      if (r->method == info.name) {
        out.push_back(info.name);
        break;
      }
  // Methods from other registries (names not in our table) keep their order.
  for (const PrecisionRow* r : rows)
    if (std::find(out.begin(), out.end(), r->method) == out.end()) out.push_back(r->method);
  return out;
}

// Error window for the observed order (see the Markdown note).
constexpr double kOrderFitLow = 1e-11;
constexpr double kOrderFitHigh = 1e-2;

std::string observedOrder(const std::vector<const PrecisionRow*>& rows, const std::string& method) {
  std::vector<double> dts, errors;
  for (const PrecisionRow* r : rows)
    if (r->method == method && r->error >= kOrderFitLow && r->error <= kOrderFitHigh) {
      dts.push_back(r->dt_s);
      errors.push_back(r->error);
    }
  if (dts.size() < 3) return "";
  return formatNumber(fitOrder(dts, errors), 2);
}

const PrecisionRow* cheapestAtOrBelow(const std::vector<const PrecisionRow*>& rows, double target) {
  const PrecisionRow* best = nullptr;
  for (const PrecisionRow* r : rows)
    if (std::isfinite(r->error) && r->error <= target &&
        (best == nullptr || r->cpuSeconds < best->cpuSeconds))
      best = r;
  return best;
}

}  // namespace

PrecisionOptions PrecisionOptions::quick() {
  PrecisionOptions o;
  o.dtCount = 5;
  o.minBatchSeconds = 0.002;
  o.batches = 2;
  return o;
}

PrecisionOptions PrecisionOptions::full() {
  PrecisionOptions o;
  o.dtCount = 12;
  o.minBatchSeconds = 0.02;
  o.batches = 3;
  return o;
}

std::string formatNumber(double value, int significantDigits) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", significantDigits, value);
  return buffer;
}

std::vector<PrecisionRow> runPrecision(std::span<const PrecisionProblem> problems,
                                       std::span<const Method> methods,
                                       const PrecisionOptions& options) {
  std::vector<PrecisionRow> rows;
  for (const PrecisionProblem& problem : problems) {
    for (Method method : methods) {
      for (double dt : dtSweep(problem.dtMin_s, problem.dtMax_s, options.dtCount)) {
        Result<PreparedRun> run = problem.prepare(method, dt);
        if (!run) break;  // this method cannot run this problem at any dt
        PrecisionRow row;
        row.problem = problem.name;
        row.method = methodName(method);
        row.dt_s = run->dt_s;
        row.cpuSeconds = timeRun(run->integrate, options);
        row.error = run->error();
        if (options.progress)
          options.progress(row.problem + " " + row.method + " dt=" + formatNumber(row.dt_s, 4) +
                           " error=" + formatNumber(row.error, 3) +
                           " cpu=" + microseconds(row.cpuSeconds));
        rows.push_back(std::move(row));
      }
    }
  }
  return rows;
}

double fitOrder(std::span<const double> dts, std::span<const double> errors) {
  TUMBLE_ASSERT(dts.size() == errors.size() && dts.size() >= 2,
                "fitOrder needs at least two (dt, error) pairs of equal count.");
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(dts.size());
  for (std::size_t i = 0; i < dts.size(); ++i) {
    const double x = std::log(dts[i]);
    const double y = std::log(errors[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

std::string precisionCsv(std::span<const PrecisionRow> rows) {
  std::string out = "problem,method,dt,error,cpu_seconds\n";
  for (const PrecisionRow& r : rows)
    out += r.problem + "," + r.method + "," + formatNumber(r.dt_s, 9) + "," +
           formatNumber(r.error) + "," + formatNumber(r.cpuSeconds) + "\n";
  return out;
}

std::string precisionMarkdown(std::span<const PrecisionRow> rows,
                              std::span<const PrecisionProblem> problems,
                              const std::string& gnuplotNote) {
  std::string md = "# Work-precision report\n\n";
  md += "Error against the reference and CPU time of one run (steady_clock around the "
        "integration loop only, best of several batches). Raw data: `precision.csv`; "
        "plots: `precision_<problem>.png` (error against CPU time, log-log).\n\n";
  if (!gnuplotNote.empty()) md += "> " + gnuplotNote + "\n\n";

  md += "## Cheapest method reaching each error\n\n| problem |";
  for (double t : kTargets) md += " error <= " + formatNumber(t, 1) + " |";
  md += "\n|---|";
  for (std::size_t i = 0; i < std::size(kTargets); ++i) md += "---|";
  md += "\n";
  for (const PrecisionProblem& problem : problems) {
    const auto mine = rowsOf(rows, problem.name);
    if (mine.empty()) continue;
    md += "| " + problem.name + " |";
    for (double t : kTargets) {
      const PrecisionRow* best = cheapestAtOrBelow(mine, t);
      md += best ? " " + best->method + " (" + microseconds(best->cpuSeconds) + ", dt " +
                       formatNumber(best->dt_s, 3) + ") |"
                 : " none in sweep |";
    }
    md += "\n";
  }

  for (const PrecisionProblem& problem : problems) {
    const auto mine = rowsOf(rows, problem.name);
    if (mine.empty()) continue;
    md += "\n## " + problem.name + "\n\n" + problem.description + ". Error unit: " +
          std::string(problem.errorUnit) + ".\n\n";
    // One column per dt of the sweep (every method ran the same dts).
    std::vector<double> dts;
    for (const PrecisionRow* r : mine)
      if (std::find(dts.begin(), dts.end(), r->dt_s) == dts.end()) dts.push_back(r->dt_s);
    md += "| method | observed order |";
    for (double dt : dts) md += " dt " + formatNumber(dt, 3) + " s |";
    md += "\n|---|---|";
    for (std::size_t i = 0; i < dts.size(); ++i) md += "---|";
    md += "\n";
    for (const std::string& method : methodsIn(mine)) {
      md += "| " + method + " | " + observedOrder(mine, method) + " |";
      for (double dt : dts) {
        const PrecisionRow* cell = nullptr;
        for (const PrecisionRow* r : mine)
          if (r->method == method && r->dt_s == dt) cell = r;
        if (cell) {
          md += ' ';
          md += formatNumber(cell->error, 2) + " / " + microseconds(cell->cpuSeconds);
        }
        md += " |";
      }
      md += "\n";
    }
    md += "\nCells: error / CPU time per run. Observed order: least-squares slope of log "
          "error against log dt over the runs with " + formatNumber(kOrderFitLow) +
          " <= error <= " + formatNumber(kOrderFitHigh) +
          " (the asymptotic range: above it the error is not yet a power of dt, below it "
          "round-off takes over); blank with fewer than 3 such runs.\n";
    std::string skipped;
    for (const MethodInfo& info : methodTable()) {
      bool present = false;
      for (const PrecisionRow* r : mine) present = present || r->method == info.name;
      if (!present) skipped += (skipped.empty() ? "" : ", ") + std::string(info.name);
    }
    if (!skipped.empty())
      md += "Not run (method does not apply to this system): " + skipped + ".\n";
  }
  return md;
}

std::string precisionGnuplotScript(std::span<const PrecisionRow> rows,
                                   const PrecisionProblem& problem, const std::string& pngPath) {
  const auto mine = rowsOf(rows, problem.name);
  std::string gp = "# Generated by `tumble report precision`; rerun with: gnuplot THIS_FILE\n";
  gp += "set terminal pngcairo size 900,640 noenhanced font ',10'\n";
  gp += "set output '" + pngPath + "'\n";
  gp += "set logscale xy\nset grid\nset key outside right top\n";
  gp += "set format x '%.0e'\nset format y '%.0e'\n";
  gp += "set xlabel 'CPU time per run [s]'\n";
  gp += "set ylabel 'error [" + std::string(problem.errorUnit) + "]'\n";
  gp += "set title '" + problem.name + ": error against CPU time (runs with error > " +
        formatNumber(kPlotErrorCeiling) + " blew up and are left out)'\n";
  std::string plot;
  for (const std::string& method : methodsIn(mine)) {
    std::string block;
    for (const PrecisionRow* r : mine)
      if (r->method == method && std::isfinite(r->error) && r->error > 0.0 &&
          r->error <= kPlotErrorCeiling && r->cpuSeconds > 0.0)
        block += formatNumber(r->cpuSeconds) + " " + formatNumber(r->error) + "\n";
    if (block.empty()) continue;  // every run of this method blew up
    gp += "$" + method + " << EOD\n" + block + "EOD\n";
    plot += (plot.empty() ? "plot " : ", \\\n     ") + std::string("$") + method +
            " using 1:2 with linespoints title '" + method + "'";
  }
  if (plot.empty()) plot = "set label 'every run blew up' at graph 0.4, 0.5\nplot 1/0 notitle";
  gp += plot + "\n";
  return gp;
}

}  // namespace tumble::numerics
