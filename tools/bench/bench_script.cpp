// Lua scripting costs: one Lua -> C++ binding call, the
// per-frame cost of 100 bodies each driven from Lua in on_update, and one
// hot-reload scan of a mod folder.
//
//   build/bin/tumble_bench_script
//
// Binding calls are timed in a Lua loop of kCalls calls inside one
// on_update; BM_LuaCall_EmptyLuaFunction is the same loop calling an empty
// Lua function, so (binding - empty) is what crossing into C++ adds. The
// counter ns_per_call is seconds per call (printed with an n suffix: ns).
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "app/fixed_step.h"
#include "app/scene.h"
#include "core/file_watch.h"
#include "physics/world.h"
#include "script/mods.h"
#include "script/scenario_host.h"

namespace tumble {
namespace {

namespace fs = std::filesystem;
constexpr int kCalls = 10000;

// A throw-away mod with one scenario, loaded in a scene of its own.
std::unique_ptr<app::Scene> loadScenario(const std::string& source) {
  fs::path dir = fs::temp_directory_path() / ("tumble_bench_script_" + std::to_string(::getpid())) / "bench";
  fs::create_directories(dir / "scenarios");
  std::ofstream(dir / "mod.lua") << "return {name = \"bench\", version = \"1.0.0\", api = 1}\n";
  std::ofstream(dir / "scenarios" / "s.lua") << source;
  app::SceneOptions options;
  options.scenarioRef = "bench:s";
  options.modDirs = {dir.parent_path().string()};
  auto scene = app::Scene::create(options);
  return scene ? std::move(scene.value()) : nullptr;
}

// on_update calls `call` kCalls times; `setup` runs in on_start.
void callLoop(benchmark::State& state, const std::string& setup, const std::string& call) {
  const std::string source = "local ball, f\nreturn {\n  on_start = function(ctx)\n" + setup +
                             "\n  end,\n  on_update = function(ctx, dt)\n    for i = 1, " + std::to_string(kCalls) +
                             " do " + call + " end\n  end,\n}\n";
  auto scene = loadScenario(source);
  if (!scene) {
    state.SkipWithError("scenario did not load");
    return;
  }
  scene->start();
  script::ScenarioHost* host = &scene->host();
  std::int64_t step = 0;
  for (auto _ : state) host->update(double(step) / 60, 1.0 / 60, step), ++step;
  if (!host->errors().empty()) state.SkipWithError(host->errors().front().summary().c_str());
  state.counters["ns_per_call"] =
      benchmark::Counter(kCalls, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_LuaCall_EmptyLuaFunction(benchmark::State& state) { callLoop(state, "f = function() end", "f()"); }
// A trivial binding: no argument, returns one integer.
void BM_LuaCall_WorldBodyCount(benchmark::State& state) { callLoop(state, "", "world.body_count()"); }
// body:position(): checks the handle, reads the body, returns a new {x, y, z} table.
void BM_LuaCall_BodyPosition(benchmark::State& state) {
  callLoop(state, "ball = world.sphere{radius = 0.5, position = {0, 5, 0}}", "ball:position()");
}
// body:apply_force(f): parses a vector argument, no allocation.
void BM_LuaCall_BodyApplyForce(benchmark::State& state) {
  callLoop(state, "ball = world.sphere{radius = 0.5, position = {0, 5, 0}}", "ball:apply_force{0, 1, 0}");
}
// tune.number read every call, as the docs suggest doing in on_update.
void BM_LuaCall_TuneNumber(benchmark::State& state) {
  callLoop(state, "", "tune.number(\"speed\", 2, {min = 0, max = 10, unit = \"m/s\"})");
}
// tune.get: the live value of a declared tunable, without the declaration.
void BM_LuaCall_TuneGet(benchmark::State& state) {
  callLoop(state, "tune.number(\"speed\", 2, {min = 0, max = 10})", "tune.get(\"speed\")");
}

// 100 bodies on a plane, each steered from Lua every step: read position
// and velocity, push towards its own target with a damped spring.
const char* kEntities = R"(
local bodies, targets = {}, {}
return {
  on_start = function(ctx)
    world.plane{}
    for i = 1, 100 do
      local x, z = (i - 1) % 10 * 2.0, (i - 1) // 10 * 2.0
      bodies[i] = world.sphere{radius = 0.4, position = {x, 0.4, z}, mass = 1}
      targets[i] = {x = x + 1, z = z + 1}
    end
  end,
  on_update = function(ctx, dt)
    for i = 1, #bodies do
      local b, t = bodies[i], targets[i]
      local p, v = b:position(), b:velocity()
      b:apply_force{(t.x - p.x) * 20 - v.x * 4, 0, (t.z - p.z) * 20 - v.z * 4}
    end
  end,
}
)";

// The script part of a frame: on_update for the 100 entities.
void BM_Entities100_ScriptPerFrame(benchmark::State& state) {
  auto scene = loadScenario(kEntities);
  if (!scene) return state.SkipWithError("scenario did not load");
  scene->start();
  script::ScenarioHost* host = &scene->host();
  std::int64_t step = 0;
  for (auto _ : state) {
    host->update(double(step) / 60, 1.0 / 60, step);
    state.PauseTiming();  // physics is not what this measures, but it keeps the state realistic
    scene->world().step(Real(1.0 / 60));
    state.ResumeTiming();
    ++step;
  }
  if (!host->errors().empty()) state.SkipWithError(host->errors().front().summary().c_str());
}

// A whole fixed step (script + physics), for scale.
void BM_Entities100_WholeStep(benchmark::State& state) {
  auto scene = loadScenario(kEntities);
  if (!scene) return state.SkipWithError("scenario did not load");
  scene->start();
  std::int64_t step = 0;
  app::RunTimings timings;
  for (auto _ : state) {
    app::stepScene(*scene, app::StepTime{double(step) / 60, step}, timings);
    timings.stepMs.clear();
    ++step;
  }
}

// Hot reload's cost while playing: one scan of mods/base for saved .lua
// files (done 4 times a second, not every frame).
void BM_HotReload_PollModsBase(benchmark::State& state) {
  FileWatch watch({TUMBLE_SOURCE_DIR "/mods/base"}, {".lua"});
  for (auto _ : state) benchmark::DoNotOptimize(watch.poll());
  state.counters["files"] = double(watch.fileCount());
}

BENCHMARK(BM_LuaCall_EmptyLuaFunction);
BENCHMARK(BM_LuaCall_WorldBodyCount);
BENCHMARK(BM_LuaCall_BodyPosition);
BENCHMARK(BM_LuaCall_BodyApplyForce);
BENCHMARK(BM_LuaCall_TuneNumber);
BENCHMARK(BM_LuaCall_TuneGet);
BENCHMARK(BM_Entities100_ScriptPerFrame)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Entities100_WholeStep)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_HotReload_PollModsBase)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace tumble

BENCHMARK_MAIN();
