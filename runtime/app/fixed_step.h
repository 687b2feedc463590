#pragma once
// The fixed step: the one place that steps a scene's systems
// (ARCHITECTURE.md "One frame"). `tumble run`, `play` and the tests all
// advance a scene through it; nothing else steps a system.
#include "app/run_report.h"

namespace tumble::app {

class Scene;

/// Where a step sits in simulated time.
struct StepTime {
  double start_s = 0;    ///< simulated time at the step's start
  long long index = 0;   ///< the step's index (0 for the first)
};

/// One fixed step of length scene.dt_s(), in order:
///   input actions -> Lua on_update -> joints -> vehicles -> physics (K
///   substeps) -> ropes and cloth -> after-step callbacks (contacts,
///   triggers, timers) -> particles.
/// Adds the wall time of each part to `t` and the step's time to t.stepMs.
void stepScene(Scene& scene, const StepTime& at, RunTimings& t);

}  // namespace tumble::app
