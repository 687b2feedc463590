#include "tools/report/report_commands.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "tools/report/accuracy.h"
#include "tools/report/rigid_body_cases.h"
#include "core/file_util.h"
#include "numerics/integrator.h"
#include "numerics/reference_problems.h"
#include "numerics/stability.h"
#include "numerics/work_precision.h"

namespace tumble::tools {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct ReportOptions {
  std::string outDir;
  bool quick = false;
  bool verbose = false;
};

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Problems and cases the reports run. Other modules add theirs here (the
// rigid-body world, joints, cloth), e.g.
//   auto more = physics::rigidBodyPrecisionProblems();
//   problems.insert(problems.end(), more.begin(), more.end());
std::vector<numerics::PrecisionProblem> precisionProblems() {
  auto problems = numerics::builtinPrecisionProblems();
  auto rigid = rigidBodyPrecisionProblems();
  problems.insert(problems.end(), rigid.begin(), rigid.end());
  return problems;
}
std::vector<numerics::StabilityCase> stabilityCases() {
  auto cases = numerics::builtinStabilityCases();
  auto rigid = rigidBodyStabilityCases();
  cases.insert(cases.end(), rigid.begin(), rigid.end());
  return cases;
}

bool prepareOutDir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    std::fprintf(stderr, "report: cannot create output folder '%s': %s\n", dir.c_str(),
                 ec.message().c_str());
    return false;
  }
  return true;
}

bool writeReportFile(const fs::path& path, const std::string& text) {
  if (Status s = writeFileAtomic(path.string(), text); !s) {
    std::fprintf(stderr, "report: %s\n", s.error().c_str());
    return false;
  }
  std::printf("  wrote %s\n", path.string().c_str());
  return true;
}

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool gnuplotAvailable() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

std::function<void(const std::string&)> progressPrinter(const ReportOptions& options) {
  if (!options.verbose) return {};
  return [](const std::string& line) { std::printf("  %s\n", line.c_str()); };
}

int runPrecisionReport(const ReportOptions& options) {
  const Clock::time_point start = Clock::now();
  if (!prepareOutDir(options.outDir)) return 1;
  const fs::path dir = fs::absolute(options.outDir);
  const std::vector<numerics::PrecisionProblem> problems = precisionProblems();
  std::vector<numerics::Method> methods;
  for (const numerics::MethodInfo& info : numerics::methodTable()) methods.push_back(info.method);

  numerics::PrecisionOptions runOptions =
      options.quick ? numerics::PrecisionOptions::quick() : numerics::PrecisionOptions::full();
  runOptions.progress = progressPrinter(options);
  std::printf("report precision: %zu problems x %zu methods x %d dt values%s\n", problems.size(),
              methods.size(), runOptions.dtCount, options.quick ? " (quick)" : "");
  const std::vector<numerics::PrecisionRow> rows =
      numerics::runPrecision(problems, methods, runOptions);

  bool ok = writeReportFile(dir / "precision.csv", numerics::precisionCsv(rows));

  std::string gnuplotNote;
  const bool haveGnuplot = gnuplotAvailable();
  if (!haveGnuplot) {
    gnuplotNote =
        "gnuplot was not found, so the PNG plots were not drawn. Install it (Debian: "
        "apt-get install gnuplot-nox) and rerun, or run the written precision_<problem>.gp "
        "scripts with gnuplot.";
    std::fprintf(stderr, "report precision: WARNING: %s\n", gnuplotNote.c_str());
  }
  for (const numerics::PrecisionProblem& problem : problems) {
    const fs::path png = dir / ("precision_" + problem.name + ".png");
    const fs::path script = dir / ("precision_" + problem.name + ".gp");
    ok = writeReportFile(script, numerics::precisionGnuplotScript(rows, problem, png.string())) &&
         ok;
    if (!haveGnuplot) continue;
    const std::string command = "gnuplot " + shellQuote(script.string()) + " 2>&1";
    if (std::system(command.c_str()) != 0 || !fs::exists(png)) {
      std::fprintf(stderr, "report precision: gnuplot failed on %s\n", script.c_str());
      ok = false;
    } else {
      std::printf("  wrote %s\n", png.string().c_str());
    }
  }
  ok = writeReportFile(dir / "precision.md",
                       numerics::precisionMarkdown(rows, problems, gnuplotNote)) &&
       ok;
  std::printf("report precision: %zu rows in %.1f s\n", rows.size(), secondsSince(start));
  return ok ? 0 : 1;
}

int runStabilityReport(const ReportOptions& options) {
  const Clock::time_point start = Clock::now();
  if (!prepareOutDir(options.outDir)) return 1;
  const fs::path dir = fs::absolute(options.outDir);
  const std::vector<numerics::StabilityCase> cases = stabilityCases();
  std::printf("report stability: %zu cases%s\n", cases.size(), options.quick ? " (quick)" : "");
  const std::vector<numerics::StabilityRow> rows =
      numerics::runStabilityCases(cases, options.quick, progressPrinter(options));
  const double casesSeconds = secondsSince(start);
  const std::vector<numerics::StabilityLimit> limits =
      numerics::measureStabilityLimits(options.quick);
  bool ok = writeReportFile(dir / "stability.csv", numerics::stabilityCsv(rows));
  ok = writeReportFile(dir / "stability_regions.csv", numerics::stabilityRegionsCsv(limits)) && ok;
  ok = writeReportFile(dir / "stability.md", numerics::stabilityMarkdown(rows, limits, cases)) && ok;
  std::printf("report stability: %zu case rows (%.1f s), %zu stability limits, %.1f s total\n",
              rows.size(), casesSeconds, limits.size(), secondsSince(start));
  return ok ? 0 : 1;
}

int runAccuracyReport(const ReportOptions& options) {
  const Clock::time_point start = Clock::now();
  if (!prepareOutDir(options.outDir)) return 1;
  const std::vector<AccuracyRow> rows = runAccuracyCases();
  int failed = 0, known = 0;
  for (const AccuracyRow& r : rows) {
    const bool pass = r.pass();
    if (!pass && r.knownLimit) ++known;
    if (!pass && !r.knownLimit) ++failed;
    if (options.verbose || !pass)
      std::printf("  %-14s %-70s analytic %-10.6g measured %-10.6g tolerance %-9.3g %s\n", r.group.c_str(),
                  r.name.c_str(), r.analytic, r.measured, r.tolerance, pass ? "pass" : r.knownLimit ? "known limit" : "FAIL");
  }
  const bool written = writeReportFile(fs::absolute(options.outDir) / "physics-accuracy.md", accuracyMarkdown(rows));
  std::printf("report accuracy: %zu cases, %d failed, %d known limits (%.1f s)\n", rows.size(), failed, known,
              secondsSince(start));
  return written && failed == 0 ? 0 : 1;
}

void addReportSubcommand(CLI::App& report, const char* name, const char* help,
                         int (*run)(const ReportOptions&), int& exitCode) {
  auto options = std::make_shared<ReportOptions>();
  CLI::App* sub = report.add_subcommand(name, help);
  sub->add_option("--out", options->outDir, "Folder for the report files (created if missing)")
      ->required();
  sub->add_flag("--quick", options->quick,
                "Small sweep for CI (seconds instead of minutes); same files and columns");
  sub->add_flag("-v,--verbose", options->verbose, "Print every measurement as it is made");
  sub->callback([options, run, &exitCode] { exitCode = run(*options); });
}

}  // namespace

void addReportCommands(CLI::App& report, int& exitCode) {
  report.require_subcommand(1);
  addReportSubcommand(report, "precision",
                      "Every integrator over a dt sweep on reference problems: error against "
                      "the exact answer and CPU time; CSV, Markdown and log-log PNG plots",
                      &runPrecisionReport, exitCode);
  addReportSubcommand(report, "stability",
                      "Stiff and extreme cases classified stable/drifting/blew_up, and each "
                      "method's largest stable step beside the theory",
                      &runStabilityReport, exitCode);
  addReportSubcommand(report, "accuracy",
                      "The physics world against analytic answers (free fall, bounces, friction, rolling, "
                      "pendulum, spring, cradle, stacks): physics-accuracy.md; exit 1 when a case fails",
                      &runAccuracyReport, exitCode);
}

}  // namespace tumble::tools
