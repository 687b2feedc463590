// tumble-sweep: parameter sweeps of `tumble run` on GNU parallel, Slurm or
// Kubernetes, and their collected results (tools/sweep/README.md).
#include <CLI/CLI.hpp>

#include <cstdio>

#include "core/cli_finite.h"
#include "tools/sweep/sweep_collect.h"
#include "tools/sweep/sweep_run.h"
#include "tools/sweep/sweep_spec.h"

using namespace tumble::tools::sweep;

namespace {

int fail(const std::string& message) {
  std::fprintf(stderr, "sweep: %s\n", message.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"Parameter sweeps: a spec (JSON or Lua) -> one `tumble run` per job, run through GNU parallel, a "
               "Slurm job array or a Kubernetes indexed Job; `collect` merges the reports",
               "tumble sweep"};
  std::string spec, out, dir;
  bool force = false, run = false, noPlots = false;
  int jobsAtOnce = 0;
  int batch = 0;
  double timeout_s = 0;
  long long index = -1, chunk = -1;
  WriteOptions wo;
  cli.add_option("spec", spec, "the sweep spec, a .json or .lua file");
  cli.add_option("--out", out, "the sweep folder to write (default: sweep-NAME here)");
  cli.add_flag("--force", force, "write a sweep larger than " + std::to_string(kMaxJobsWithoutForce) + " jobs");
  cli.add_flag("--run", run, "after writing, run the jobs here through GNU parallel");
  cli.add_option("-j,--jobs", jobsAtOnce, "runs at once with --run (default: one per core)")->check(CLI::NonNegativeNumber);
  cli.add_option("--timeout", timeout_s, "with --run: stop a run after this many seconds of wall time (default: never)")
      ->check(tumble::kFinite)->check(CLI::PositiveNumber);
  cli.add_option("--batch", batch, "with --run: runs a GNU parallel job runs one after another (default: 32 batches a slot)")
      ->check(CLI::PositiveNumber);
  cli.add_option("--chunk-size", wo.chunkSize, "runs per Slurm array task / Kubernetes index (default: at most 1000 tasks)")
      ->check(CLI::PositiveNumber);
  cli.add_option("--image", wo.image, "container image for the Kubernetes Job (built from tools/sweep/Dockerfile)");
  cli.add_option("--volume-claim", wo.volumeClaim, "PersistentVolumeClaim holding the sweep folder on Kubernetes");
  cli.add_option("--parallelism", wo.parallelism, "Kubernetes pods at once")->check(CLI::PositiveNumber);

  CLI::App* runCmd = cli.add_subcommand("run", "run a written sweep's unfinished jobs here through GNU parallel (resumes)");
  runCmd->add_option("dir", dir, "the sweep folder")->required();
  runCmd->add_option("-j,--jobs", jobsAtOnce, "runs at once (default: one per core)")->check(CLI::NonNegativeNumber);
  runCmd->add_option("--timeout", timeout_s, "stop a run after this many seconds of wall time (default: never)")
      ->check(tumble::kFinite)->check(CLI::PositiveNumber);
  runCmd->add_option("--batch", batch, "runs a GNU parallel job runs one after another (default: 32 batches a slot)")
      ->check(CLI::PositiveNumber);

  CLI::App* execCmd = cli.add_subcommand("exec", "run one job (--index) or one chunk (--chunk) of a sweep; what parallel, "
                                                  "Slurm and Kubernetes call");
  execCmd->add_option("dir", dir, "the sweep folder")->required();
  auto* indexOpt = execCmd->add_option("--index", index, "the job's index (0-based line of jobs.txt)")->check(CLI::NonNegativeNumber);
  auto* chunkOpt = execCmd->add_option("--chunk", chunk, "the chunk's index (Slurm array task, Kubernetes completion index)")
                       ->check(CLI::NonNegativeNumber);
  indexOpt->excludes(chunkOpt);

  CLI::App* collectCmd = cli.add_subcommand("collect", "merge a sweep's reports: results.csv, summary.md and plots");
  collectCmd->add_option("dir", dir, "the sweep folder")->required();
  collectCmd->add_flag("--no-plots", noPlots, "skip gnuplot");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? 0 : 1;
  }
  if (*execCmd) {
    auto sweep = readSweepFolder(dir);
    if (!sweep) return fail(sweep.error());
    if (index < 0 && chunk < 0) return fail("exec: give --index I or --chunk C");
    std::size_t begin = std::size_t(index), end = begin + 1;
    if (chunk >= 0) std::tie(begin, end) = chunkRange(*sweep, std::size_t(chunk));
    if (begin >= sweep->jobs.size() || begin >= end)
      return fail("exec: " + std::string(chunk >= 0 ? "chunk " + std::to_string(chunk) : "index " + std::to_string(index)) +
                  " is past the sweep's " + std::to_string(sweep->jobs.size()) + " jobs");
    bool all = true;
    for (std::size_t i = begin; i < end; ++i) all &= execJob(*sweep, i, ownBinDir() + "/tumble");
    return all ? 0 : 1;
  }
  if (*runCmd) {
    auto sweep = readSweepFolder(dir);
    if (!sweep) return fail(sweep.error());
    return runLocal(*sweep, jobsAtOnce, batch, timeout_s, ownBinDir() + "/tumble");
  }
  if (*collectCmd) {
    auto sweep = readSweepFolder(dir);
    if (!sweep) return fail(sweep.error());
    if (auto st = collectSweep(*sweep, !noPlots); !st) return fail(st.error());
    int status = 0;
    std::printf("sweep %s: %s\n", sweep->name.c_str(), outcomeSummary(*sweep, &status).c_str());
    std::printf("wrote %s/results.csv and %s/summary.md\n", sweep->dir.c_str(), sweep->dir.c_str());
    return 0;
  }
  if (spec.empty()) return fail("give a spec file (tumble sweep SPEC), or run, exec or collect; see tumble sweep --help");
  auto s = readSpec(spec);
  if (!s) return fail(s.error());
  if (auto st = validateSpec(*s, force); !st) return fail(st.error());
  const std::vector<Job> jobs = expandJobs(*s);
  if (out.empty()) out = "sweep-" + s->name;
  if (auto st = writeSweepFolder(*s, jobs, out, wo); !st) return fail(st.error());
  auto sweep = readSweepFolder(out);
  if (!sweep) return fail(sweep.error());
  std::size_t done = 0;
  for (std::size_t i = 0; i < jobs.size(); ++i) done += jobFinished(*sweep, i);
  std::printf("sweep %s: %zu jobs (%zu finished already) in %s: jobs.txt, sweep.json, slurm.sh, k8s-job.yaml\n",
              s->name.c_str(), jobs.size(), done, sweep->dir.c_str());
  if (!run) {
    std::printf("run them here: tumble sweep run %s   (or sbatch %s/slurm.sh; kubectl apply -f %s/k8s-job.yaml)\n",
                shellQuote(sweep->dir).c_str(), shellQuote(sweep->dir).c_str(), shellQuote(sweep->dir).c_str());
    return 0;
  }
  return runLocal(*sweep, jobsAtOnce, batch, timeout_s, ownBinDir() + "/tumble");
}
