#pragma once
// A sweep on disk and its jobs' runs. `tumble sweep SPEC --out DIR` writes
// DIR/sweep.json (the jobs), DIR/jobs.txt (one `tumble run` command a line,
// run in DIR), DIR/slurm.sh (a job array) and DIR/k8s-job.yaml (an indexed
// Job); `tumble sweep run DIR` runs the jobs still to do through GNU
// parallel; `exec` runs one job or one chunk (what parallel, Slurm and
// Kubernetes call). tools/sweep/README.md explains each.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/result.h"
#include "tools/sweep/sweep_spec.h"

namespace tumble::tools::sweep {

struct WriteOptions {
  int chunkSize = 0;         ///< jobs per Slurm array task / Kubernetes index; 0: at most 1000 tasks
  int parallelism = 4;       ///< Kubernetes pods at once
  std::string image = "tumble-sweep:latest";  ///< the container image (tools/sweep/Dockerfile)
  std::string volumeClaim = "tumble-sweep";   ///< the PersistentVolumeClaim holding the sweep folder
  std::string binDir;        ///< where tumble and tumble-sweep are (absolute)
};

/// The sweep folder's description (sweep.json).
struct SweepFolder {
  std::string dir;
  std::string name;
  std::vector<std::string> keys;     ///< swept keys, column order
  std::vector<std::string> collect;  ///< report fields
  std::string errorMetric;
  int chunkSize = 1;
  nlohmann::json jobs;  ///< [{id, scenario, values, seed, integrator, dt, substeps, argv, report}]
};

/// Writes the sweep folder. A folder that holds the same jobs already is
/// kept as it is (its finished runs count: resume); one holding a different
/// sweep is an error, so no result is overwritten.
Status writeSweepFolder(const SweepSpec& spec, const std::vector<Job>& jobs, const std::string& dir,
                        const WriteOptions& options);
Result<SweepFolder> readSweepFolder(const std::string& dir);

/// True when runs/<id>/report.json exists and is a complete run report
/// (reports are written atomically, so a present one is whole).
bool jobFinished(const SweepFolder& sweep, std::size_t index);

/// Runs job `index` unless it finished already: `tumble run ...` in the
/// sweep folder, output appended to runs/<id>/log.txt, and runs/<id>/status.json
/// (exit status, signal, wall time, reason). True when the run left a report.
bool execJob(const SweepFolder& sweep, std::size_t index, const std::string& tumbleBinary);

/// The jobs of chunk `chunk` (Slurm's array index, Kubernetes' completion index).
std::pair<std::size_t, std::size_t> chunkRange(const SweepFolder& sweep, std::size_t chunk);

/// Runs the unfinished jobs through GNU parallel with `jobsAtOnce` slots
/// (0: one per core), `batch` runs a GNU parallel job (0: 32 jobs a slot),
/// a progress bar and ETA, and DIR/joblog.txt; `timeout_s` > 0 stops a run
/// that takes longer (its reason says so). Returns
/// the exit status: 0 every job passed, 2 every job ran but some failed an
/// expectation or had a script error, 1 some jobs left no report.
int runLocal(const SweepFolder& sweep, int jobsAtOnce, int batch, double timeout_s, const std::string& tumbleBinary);

/// The job's exit status, signal and reason (why it did not pass; empty
/// when it passed), from runs/<id>/status.json (exec) or runs/<id>/exit
/// (a local run); null when it has not run.
nlohmann::json jobStatus(const SweepFolder& sweep, std::size_t index);
/// Why a finished run did not pass, from its report: the first script error
/// (file, line, message) or the failed expectations with their values.
std::string reportReason(const nlohmann::json& report);

/// Counts of finished runs by outcome (for the messages after a run).
std::string outcomeSummary(const SweepFolder& sweep, int* exitStatus);

/// The folder this program is in (to find tumble beside tumble-sweep).
std::string ownBinDir();
/// POSIX shell quoting when needed.
std::string shellQuote(const std::string& s);

}  // namespace tumble::tools::sweep
