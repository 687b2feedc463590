// Report fields shared by the one-setting comparison (main.cpp) and the
// work-precision sweep (sweep.cpp): what each run measured, and every solver
// setting of each engine, so a report says whatever differs between them.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "scenes.h"

namespace tumble::compare {

/// Nearest-rank percentile of a sample (p in [0, 1]).
double percentile(std::vector<double> v, double p);
double median(std::vector<double> v);

/// The measured figures of one run (times, penetration, drift, energy, joints).
nlohmann::json measured(const RunResult& r);
/// Every solver setting of each engine for one run.
nlohmann::json tumbleSettings(const TumbleConfig& c);
nlohmann::json bulletSettings(const SceneSpec& scene, const BulletConfig& c);
nlohmann::json odeSettings(const OdeConfig& c);

}  // namespace tumble::compare
