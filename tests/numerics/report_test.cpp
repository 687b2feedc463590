// Work-precision runner and report texts.
#include <gtest/gtest.h>

#include <cmath>

#include "numerics/reference_problems.h"
#include "numerics/work_precision.h"

namespace tumble::numerics {
namespace {

TEST(WorkPrecision, FitOrderRecoversAPowerLaw) {
  const std::vector<double> dts = {0.1, 0.05, 0.02, 0.01};
  std::vector<double> errors;
  for (double dt : dts) errors.push_back(3.0 * std::pow(dt, 2.5));
  EXPECT_NEAR(fitOrder(dts, errors), 2.5, 1e-12);
}

TEST(WorkPrecision, RunsEveryApplicableMethodAndWritesTheAgreedCsv) {
  std::vector<PrecisionProblem> problems = {toPrecisionProblem(harmonicOscillatorProblem()),
                                            toPrecisionProblem(stiffDecayProblem())};
  PrecisionOptions options = PrecisionOptions::quick();
  options.dtCount = 3;
  options.minBatchSeconds = 1e-4;
  const std::vector<Method> methods = {Method::Rk4, Method::Verlet};
  const std::vector<PrecisionRow> rows = runPrecision(problems, methods, options);
  // Verlet cannot run the first-order decay: 2 x 3 + 1 x 3 rows.
  ASSERT_EQ(rows.size(), 9u);
  for (const PrecisionRow& r : rows) {
    EXPECT_GT(r.cpuSeconds, 0.0);
    EXPECT_FALSE(r.problem == "stiff_decay" && r.method == "verlet");
  }
  // Smaller dt, smaller error for RK4 on the oscillator.
  EXPECT_LT(rows[2].error, rows[0].error);
  const std::string csv = precisionCsv(rows);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "problem,method,dt,error,cpu_seconds");
  const std::string md = precisionMarkdown(rows, problems, "");
  EXPECT_NE(md.find("## harmonic_oscillator"), std::string::npos);
  EXPECT_NE(md.find("Not run (method does not apply to this system)"), std::string::npos);
  const std::string gp = precisionGnuplotScript(rows, problems[0], "/tmp/x.png");
  EXPECT_NE(gp.find("set logscale xy"), std::string::npos);
  EXPECT_NE(gp.find("$rk4 << EOD"), std::string::npos);
}

}  // namespace
}  // namespace tumble::numerics
