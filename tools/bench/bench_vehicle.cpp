// Vehicles at scale: the base:convoy scene (N vehicles on generated hills,
// each driven by a Lua autopilot from scripts/tumble/drive.lua) stepped at
// 60 Hz with the default 8 substeps.
//
//   build/bin/tumble_bench_vehicle
//
// Counters per fixed step: ms_step (everything), ms_physics (World::step
// with the wheel model in its substeps), ms_script (the scenario's
// on_update: the Lua controllers, plus the vehicles' per-step C++
// bookkeeping), us_lua_per_vehicle = (script time with autopilots - script
// time with the cars parked) / N, i.e. what one Lua controller costs.
// Compare ratios within one run: the machine is shared.
#include <benchmark/benchmark.h>

#include <chrono>

#include "app/scene.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Times {
  double total = 0, physics = 0, script = 0;
  int steps = 0;
};

Times runConvoy(benchmark::State* state, int count, bool autopilot, int warmup, int steps) {
  tumble::app::SceneOptions o;
  o.scenarioRef = "base:convoy";
  // Every car on autopilot, or every car parked (the baseline without Lua per car).
  o.sets = {{"count", std::to_string(count)}, {autopilot ? "autopilot" : "parked", "1"}};
  auto created = tumble::app::Scene::create(o);
  if (!created) {
    if (state) state->SkipWithError(created.error().c_str());
    return {};
  }
  tumble::app::Scene& scene = *created.value();
  scene.host().start();
  scene.registerStaticObjects();
  const double dt = o.dt_s;
  Times t;
  std::int64_t step = 0;
  auto one = [&](bool measure) {
    const double time = double(step) * dt;
    const auto t0 = Clock::now();
    scene.host().update(time, dt, step);
    const auto t1 = Clock::now();
    scene.world().step(tumble::Real(dt));
    const auto t2 = Clock::now();
    scene.host().afterStep(time + dt, step);
    const auto t3 = Clock::now();
    ++step;
    if (!measure) return;
    t.script += std::chrono::duration<double>(t1 - t0).count();
    t.physics += std::chrono::duration<double>(t2 - t1).count();
    t.total += std::chrono::duration<double>(t3 - t0).count();
    ++t.steps;
  };
  for (int i = 0; i < warmup; ++i) one(false);  // cars under way, settled on their springs
  if (state) {
    for (auto _ : *state) one(true);
  } else {
    for (int i = 0; i < steps; ++i) one(true);
  }
  return t;
}

void BM_Convoy(benchmark::State& state) {
  const int count = int(state.range(0));
  const Times with = runConvoy(&state, count, true, 120, 0);
  const Times parked = runConvoy(nullptr, count, false, 120, with.steps);
  if (with.steps == 0 || parked.steps == 0) return;
  const double n = double(with.steps);
  state.counters["ms_step"] = with.total / n * 1e3;
  state.counters["ms_physics"] = with.physics / n * 1e3;
  state.counters["ms_script"] = with.script / n * 1e3;
  state.counters["us_lua_per_vehicle"] = (with.script / n - parked.script / double(parked.steps)) / count * 1e6;
  state.counters["ms_step_parked"] = parked.total / double(parked.steps) * 1e3;
}
BENCHMARK(BM_Convoy)->Arg(1)->Arg(10)->Arg(50)->Iterations(300)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
