#pragma once
// `tumble sweep collect DIR`: the runs' reports merged into DIR/results.csv
// and DIR/summary.md with gnuplot plots in DIR/plots/ (pass rate per
// scenario, each collected metric against each swept parameter, error
// against run time with its Pareto front, the runs that failed and why).
#include <string>
#include <vector>

#include "core/result.h"
#include "tools/sweep/sweep_run.h"

namespace tumble::tools::sweep {

/// One job's row: its swept values, outcome and collected numbers.
struct ResultRow {
  std::string id, scenario;
  std::vector<std::string> keyValues;  ///< one per SweepFolder::keys
  std::string status;  ///< passed, expectation_failed, script_error, failed (no report), not_run
  std::string exitText, reason, stateHash, log;
  std::vector<std::optional<double>> metrics;  ///< one per SweepFolder::collect
};

std::vector<ResultRow> gatherRows(const SweepFolder& sweep);

/// The points on the Pareto front of (time, error), lower both better:
/// indices into the inputs, by increasing time. Points with a missing value
/// are left out.
std::vector<std::size_t> paretoFront(const std::vector<std::optional<double>>& time,
                                     const std::vector<std::optional<double>>& error);

/// Writes results.csv, summary.md and the plots. `plots` false skips gnuplot
/// (the summary then says so).
Status collectSweep(const SweepFolder& sweep, bool plots);

}  // namespace tumble::tools::sweep
