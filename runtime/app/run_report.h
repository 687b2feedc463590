#pragma once
// The run report (ARCHITECTURE.md): one JSON object with the error next to
// the run time. Every field is always present.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/result.h"

namespace tumble::app {

class Scene;

struct RunTimings {
  double total_s = 0, startup_s = 0, physics_s = 0, script_s = 0, particles_s = 0, render_s = 0;
  std::vector<double> stepMs;  ///< wall time of each fixed step (script + physics)
};

struct RunCounts {
  int bodiesMax = 0;
  int jointsMax = 0;
  int particlesMax = 0;
};

/// Median, 99th percentile and maximum of the step times.
struct StepMsSummary {
  double median = 0, p99 = 0, max = 0;
};
StepMsSummary summarizeSteps(std::vector<double> stepMs);

/// The state hash (16 hex digits) of everything the scene simulates: the
/// bodies, rope and cloth particles, live effect particles. Exact bits.
std::string stateHashText(Scene& scene);

/// How often a state went non-finite: bodies the world froze plus rope and
/// cloth steps undone (the report's error.nan_events).
long nonFiniteEvents(Scene& scene);

nlohmann::json buildReport(Scene& scene, long long steps, double simulatedSeconds, const RunTimings& timings,
                           const RunCounts& counts);

/// Exit status of `run` (ARCHITECTURE.md): 3 script error, 2 failed
/// expectation, 0 otherwise. A script error wins: expectations after one are
/// not trustworthy.
int exitStatusFor(const Scene& scene);

Status writeReport(const std::string& path, const nlohmann::json& report);

}  // namespace tumble::app
