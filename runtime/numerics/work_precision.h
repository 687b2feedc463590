#pragma once
// Work-precision runner: every problem x method x dt, its error against the
// reference and the CPU time of the integration loop; plus the report texts
// (CSV, Markdown, gnuplot scripts). Writing files and running gnuplot is the
// caller's business (tools/report/report_commands.cpp): numerics stays free of I/O.
//
// Timing: std::chrono::steady_clock around integrate() only. A run shorter
// than the clock's useful resolution is repeated until a batch lasts at least
// minBatchSeconds; the reported time is the best of `batches` batches
// divided by the repetitions, because on a shared machine noise only ever
// adds time.
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "numerics/integrator.h"
#include "numerics/reference_problems.h"

namespace tumble::numerics {

struct PrecisionOptions {
  int dtCount = 12;               // dt values per problem, geometric from dtMax down to dtMin
  double minBatchSeconds = 0.02;  // a timed batch lasts at least this long
  int batches = 3;                // best-of
  /// Called after each measurement (for progress output); may be empty.
  std::function<void(const std::string& line)> progress;

  static PrecisionOptions quick();  // small sweep for CI (seconds)
  static PrecisionOptions full();   // the published sweep (a minute or two)
};

struct PrecisionRow {
  std::string problem;
  std::string method;
  double dt_s = 0.0;
  double error = 0.0;  // in the problem's errorUnit; inf/nan when the run blew up
  double cpuSeconds = 0.0;  // one full run to t_end
};

/// Runs the sweep. Methods a problem cannot run (symplectic methods on a
/// first-order system) are skipped and produce no rows.
std::vector<PrecisionRow> runPrecision(std::span<const PrecisionProblem> problems,
                                       std::span<const Method> methods,
                                       const PrecisionOptions& options);

/// Least-squares slope of log(error) against log(dt): the observed order.
double fitOrder(std::span<const double> dts, std::span<const double> errors);

/// Columns exactly: problem,method,dt,error,cpu_seconds
std::string precisionCsv(std::span<const PrecisionRow> rows);

/// Per problem: description, table of error / CPU per method and dt, and the
/// cheapest method that reaches each of several target errors.
/// gnuplotNote is added under the title (e.g. that gnuplot was missing).
std::string precisionMarkdown(std::span<const PrecisionRow> rows,
                              std::span<const PrecisionProblem> problems,
                              const std::string& gnuplotNote);

/// Self-contained gnuplot script (data inline) drawing error against CPU time,
/// log-log, one curve per method, for one problem; writes pngPath.
std::string precisionGnuplotScript(std::span<const PrecisionRow> rows,
                                   const PrecisionProblem& problem, const std::string& pngPath);

/// printf("%.*g") text of a double, "inf"/"-inf"/"nan" for those.
std::string formatNumber(double value, int significantDigits = 6);

}  // namespace tumble::numerics
