#pragma once
// A sweep: what `tumble sweep SPEC` reads (a JSON or Lua file) and the jobs
// it expands to, one `tumble run` each. tools/sweep/README.md describes the
// file; this header the data.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/result.h"

namespace tumble::tools::sweep {

/// Sweeps larger than this many jobs need --force. A typo (a range written
/// as a thousand values, one axis too many) multiplies a sweep; 10 000 runs
/// of the base scenarios (0.1 to 5 s each) take one to fourteen hours on a
/// 2-core machine and leave 10 000 report folders, which is past what a
/// designer means without saying so.
constexpr std::size_t kMaxJobsWithoutForce = 10000;

/// One swept or fixed --set value: KEY=TEXT as the command line writes it.
struct SetValue {
  std::string key;
  std::string text;
};

/// A random design: `samples` points, each parameter drawn uniformly from
/// its [min, max] (numbers) with a generator seeded by `seed`.
struct RandomDesign {
  int samples = 0;
  std::uint64_t seed = 1;
  std::map<std::string, std::pair<double, double>> ranges;
};

struct SweepSpec {
  std::string name;                   ///< the sweep's name (default: the file's stem)
  std::string file;                   ///< where it was read from
  std::vector<std::string> scenarios; ///< MOD:SCENARIO
  std::vector<std::string> modDirs;   ///< --mods folders, absolute
  double seconds = -1;                ///< simulated seconds per run; < 0: the scenario's duration
  long long steps = -1;               ///< fixed steps per run instead of seconds; < 0: not given
  /// Grid axes: each KEY with its values (the cross product is swept).
  std::vector<std::pair<std::string, std::vector<std::string>>> grid;
  RandomDesign random;                ///< samples == 0: no random design
  std::vector<SetValue> fixed;        ///< --set for every job
  std::vector<std::uint64_t> seeds{1};
  std::vector<std::string> integrators;  ///< empty: the scenario's own
  std::vector<double> dts;               ///< s; empty: the default 1/60
  std::vector<int> substeps;             ///< empty: the world's default
  /// Report fields to collect (dotted paths into the run report).
  std::vector<std::string> collect;
  /// The field plotted against run time (with its Pareto front).
  std::string errorMetric = "error.energy_rel_drift_max";
};

struct Job {
  std::string id;        ///< "000017": the index, zero padded
  std::string scenario;
  std::vector<SetValue> values;  ///< the swept --set values of this job (not the fixed ones)
  std::uint64_t seed = 1;
  std::string integrator;  ///< empty: the scenario's
  double dt_s = 0;         ///< 0: default
  int substeps = 0;        ///< 0: default
  std::vector<std::string> argv;  ///< "tumble" "run" ...; the report path is relative to the sweep folder
  std::string reportPath;         ///< runs/<id>/report.json
};

/// Reads a spec: `.json` with nlohmann-json, `.lua` run in the sandbox mod
/// files run in (no io, os.execute, require outside the spec's folder) and
/// returning a table of the same shape. Every problem names the file and the
/// field.
Result<SweepSpec> readSpec(const std::string& path);
/// The same from parsed JSON (`file` names it in messages, `baseDir` is
/// where relative mod folders are).
Result<SweepSpec> specFromJson(const nlohmann::json& j, const std::string& file, const std::string& baseDir);

/// Number of jobs the spec expands to (without expanding it).
std::size_t jobCount(const SweepSpec& spec);

/// Checks everything that can be checked before a run: scenarios exist,
/// every swept or fixed parameter is one the scenario declares (its
/// `params`) with a value of the right type, physics.* settings, integrator
/// names, dt and substeps, the report fields, and the size (see
/// kMaxJobsWithoutForce). All problems at once, one a line.
Status validateSpec(const SweepSpec& spec, bool force);

/// The jobs, in a fixed order: scenario, design point, integrator, dt,
/// substeps, seed (the last varies fastest).
std::vector<Job> expandJobs(const SweepSpec& spec);

/// Shortest decimal text that reads back as the same double ("0.1", "16").
std::string numberText(double v);

/// The keys swept by the spec, in column order: grid axes with more than
/// one value, random ranges, then seed, integrator, dt, substeps when given
/// more than one value.
std::vector<std::string> sweptKeys(const SweepSpec& spec);

}  // namespace tumble::tools::sweep
