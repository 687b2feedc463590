// Render cost per quality preset: one frame of base:drive (terrain, the
// trees and rocks, the car with its wheels, the generated sky and clouds,
// sun shadows) drawn offscreen at 1280x720 with each preset's renderer
// settings, the same frame under a storm sky (rain, denser fog), and on
// medium and high with the terrain's surface blending off and on.
// The time is the wall time of Renderer::drawFrame, as the play report's
// frame_ms.render_p50 measures it; on Mesa llvmpipe that is the
// rasteriser's work (the resolve of the multisampled scene waits for it).
//
//   cmake --build build --target tumble_bench_render && build/bin/tumble_bench_render
#include <benchmark/benchmark.h>

#include <cstdlib>

#include "app/fixed_step.h"
#include "app/player_settings.h"
#include "app/scene.h"
#include "bench_renderer.h"
#include "render/renderer.h"
#include "vehicle/vehicle_system.h"

namespace {

using namespace tumble;

void BM_DriveFrame(benchmark::State& state) {
  const auto level = static_cast<app::QualityLevel>(state.range(0));
  const bool storm = state.range(1) != 0;
  app::SceneOptions options;
  options.scenarioRef = "base:drive";
  options.sets = {{"autopilot", "1"}};
  auto scene = app::Scene::create(options);
  if (!scene) {
    state.SkipWithError(scene.error().c_str());
    return;
  }
  (*scene)->start();
  app::RunTimings timings;
  for (int i = 0; i < 180; ++i) app::stepScene(**scene, app::StepTime{i * (*scene)->dt_s(), i}, timings);
  (*scene)->savePreviousState();
  render::FrameSnapshot frame;
  (*scene)->snapshot(frame, 1.0);
  if (storm) {  // the same frame under a storm: dark cover, dense fog, rain, lightning
    frame.sky.weather = render::Weather::Storm;
    frame.sky.cloudCover = 1;
  }

  auto renderer = bench::offscreenRenderer(state, level);
  if (!renderer) return;
  // Third argument: the terrain's surface blending forced off (0) or on
  // (1); -1 keeps the preset's. Its cost is the ratio of the two in one run.
  const int blend = int(state.range(2));
  if (blend >= 0) {
    render::RenderQuality quality = renderer->quality();
    quality.terrainBlend = blend != 0;
    renderer->setQuality(quality);
  }
  // Behind and above the car, looking along its way.
  render::Camera& camera = renderer->camera();
  const vehicle::VehicleSystem* vehicles = (*scene)->vehiclesIfAny();
  if (vehicles)
    vehicles->forEach([&](vehicle::VehicleId id) {
      const physics::Body& b = (*scene)->world().body(vehicles->chassis(id));
      camera.target = b.position_m.cast<float>() + Eigen::Vector3f(0, 1, 0);
      const Vec3 forward = b.orientation * Vec3::UnitZ();
      camera.yaw_rad = float(std::atan2(-forward.x(), -forward.z()));
    });
  camera.pitch_rad = 0.25f;
  camera.distance_m = 7;
  render::Controls controls;
  // The first frame uploads the sky cube and terrain chunks: not timed.
  if (const Status s = renderer->drawFrame(frame, render::HudStats{}, controls); !s) {
    state.SkipWithError(s.error().c_str());
    return;
  }
  for (auto _ : state) {
    const Status s = renderer->drawFrame(frame, render::HudStats{}, controls);
    if (!s) state.SkipWithError(s.error().c_str());
  }
  state.SetLabel(std::string(app::qualityName(level)) + (storm ? ", storm" : "") +
                (blend < 0 ? "" : blend ? ", blend on" : ", blend off"));
}
BENCHMARK(BM_DriveFrame)
    ->ArgsProduct({{0, 1, 2}, {0, 1}, {-1}})
    ->ArgsProduct({{1, 2}, {0}, {0, 1}})
    ->ArgNames({"preset", "storm", "blend"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
