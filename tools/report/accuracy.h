#pragma once
// `tumble report accuracy`: the physics against analytic answers, one table
// (case, analytic value, measured value, error, tolerance, pass / fail),
// written as physics-accuracy.md (docs/physics-accuracy.md is its output).
#include <string>
#include <vector>

namespace tumble::tools {

struct AccuracyRow {
  std::string group;     ///< "free fall", "pendulum", ...
  std::string name;      ///< the case and its parameters
  std::string unit;      ///< of the values
  double analytic = 0;
  double measured = 0;
  double tolerance = 0;  ///< on |measured - analytic|, same unit
  std::string toleranceWhy;  ///< where the tolerance comes from
  /// Pass when |measured - analytic| <= tolerance. A known limit is shown
  /// with its figures and does not fail the run.
  bool knownLimit = false;
  std::string note;
  bool pass() const;
};

/// Runs every case (about a minute of simulated time each, a few seconds).
std::vector<AccuracyRow> runAccuracyCases();
/// The Markdown page: how tolerances are set, then the table.
std::string accuracyMarkdown(const std::vector<AccuracyRow>& rows);

}  // namespace tumble::tools
