#pragma once
// What run and play share about showing a scene: where the camera looks at
// the start, the HUD's figures, and the renderer for a scene.
#include <memory>

#include "app/run_report.h"
#include "app/scene.h"
#include "render/renderer.h"

namespace tumble::app {

/// Live particles now (0 without a particle system).
int particleCount(Scene& scene);
/// Points the camera at the scene: the first vehicle from 12 m, otherwise
/// an orbit around the dynamic bodies, far enough to see them all.
void frameCamera(Scene& scene, render::Camera& cam);
/// The centre of the dynamic bodies (the follow camera's target).
Eigen::Vector3f dynamicCentroid(Scene& scene);
/// The HUD's figures: timings per frame, counts, the scenario's messages.
render::HudStats hudStats(Scene& scene, double fps, const RunTimings& perFrame, double time_s);
/// A window (or an offscreen context) for the scene; notes "render" as a subsystem.
Result<std::unique_ptr<render::Renderer>> makeRenderer(Scene& scene, int w, int h, bool offscreen, bool hud);

}  // namespace tumble::app
