// Work-precision comparison: each engine run over its own accuracy settings
// on one scene, quality against CPU time per step, with each engine's Pareto
// front and the headline figures read off the fronts.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "scenes.h"

namespace tumble::compare {

struct SweepOptions {
  std::string outDir = ".";  ///< where SCENE_sweep.csv, .gp, .png and the front files go
  bool quick = false;        ///< a small grid (2 x 2 per engine) for smoke tests
  std::string jointSolver = "impulse";  ///< Tumble's joint solver: "impulse" or "lagrange"
  int threads = 1;                      ///< Tumble's WorldSettings::threads (the peers use one)
};

/// Runs every setting of every engine on the scene (`steps` of `dt` each),
/// writes the CSV, the front data, the gnuplot script and (when gnuplot is
/// installed) the PNG into options.outDir, and returns the JSON report.
/// Throws std::runtime_error when a file cannot be written.
nlohmann::json runSweep(const SceneSpec& scene, int steps, double dt, const SweepOptions& options);

}  // namespace tumble::compare
