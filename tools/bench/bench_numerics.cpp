// Numerics lab benchmarks: what a Lua ODE derivative costs against the same
// system in C++, what the world's integrator strategies cost against the
// default, and what a cloth step costs.
//
//   build/bin/tumble_bench_numerics
//
// Compare ratios within one run (the machine is shared). Counter
// `derivatives` is derivative evaluations per second (1e9 / it = ns each).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>

#include "numerics/integrator.h"
#include "numerics/systems.h"
#include "physics/deformable.h"
#include "physics/world.h"
#include "script/mods.h"
#include "app/scene.h"
#include "script/scenario_host.h"

namespace {

using namespace tumble;

constexpr int kStepsPerUpdate = 1000;

// The pendulum theta'' = -(g/L) sin theta in C++, classical RK4.
void BM_OdeRk4Cpp(benchmark::State& state) {
  numerics::Pendulum pendulum(9.81 / 2);
  numerics::Integrator rk4(numerics::Method::Rk4, 2);
  Eigen::VectorXd y(2);
  y << 1.0, 0.0;
  double t = 0;
  for (auto _ : state) {
    for (int i = 0; i < kStepsPerUpdate; ++i, t += 1e-3) rk4.step(pendulum, t, y, 1e-3);
    benchmark::DoNotOptimize(y.data());
  }
  state.counters["derivatives"] =
      benchmark::Counter(double(state.iterations()) * kStepsPerUpdate * 4, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_OdeRk4Cpp)->Unit(benchmark::kMicrosecond);

// The same pendulum as ode.system{...} in a scenario's on_update: each
// update steps it kStepsPerUpdate times with RK4 (4 Lua derivative calls
// per step). The scenario lives in a temporary mod.
void BM_OdeRk4Lua(benchmark::State& state) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "tumble_bench_numerics";
  fs::create_directories(dir / "benchode" / "scenarios");
  std::ofstream(dir / "benchode" / "mod.lua") << "return {name = \"benchode\", version = \"0.1.0\", api = 1}\n";
  std::ofstream(dir / "benchode" / "scenarios" / "pendulum.lua")
      << "local sys\n"
         "return {\n"
         "  on_start = function(ctx)\n"
         "    sys = ode.system{state = {1, 0}, method = \"rk4\",\n"
         "      derivative = function(t, y) return {y[2], -9.81 / 2 * math.sin(y[1])} end}\n"
         "  end,\n"
         "  on_update = function(ctx, dt) sys:step(1, "
      << kStepsPerUpdate << ") end,\n}\n";
  app::SceneOptions options;
  options.scenarioRef = "benchode:pendulum";
  options.modDirs = {dir.string()};
  options.limits.instructionsPerCall = 1'000'000'000;
  auto scene = app::Scene::create(options);
  if (!scene) {
    state.SkipWithError(scene.error().c_str());
    return;
  }
  script::ScenarioHost& host = scene.value()->host();
  scene.value()->start();
  std::int64_t step = 0;
  for (auto _ : state) {
    host.update(double(step) / 60, 1.0 / 60, step);
    ++step;
  }
  if (!host.errors().empty()) state.SkipWithError(host.errors().front().message.c_str());
  state.counters["derivatives"] =
      benchmark::Counter(double(state.iterations()) * kStepsPerUpdate * 4, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_OdeRk4Lua)->Unit(benchmark::kMicrosecond);

// 100 free boxes falling (no contacts) for each integrator strategy: the
// cost of routing translation through numerics against the default loop.
void BM_WorldIntegrator(benchmark::State& state) {
  const auto method = physics::bodyIntegrators()[std::size_t(state.range(0))];
  physics::World world;
  world.settings().integrator = method.method;
  for (int i = 0; i < 100; ++i) {
    physics::BodyDef d;
    d.shape = physics::Shape::box(Vec3(Real(0.2), Real(0.2), Real(0.2)));
    d.position_m = Vec3(Real(i % 10), Real(1000), Real(i / 10));
    d.allowSleep = false;
    (void)world.createBody(d);
  }
  for (auto _ : state) world.step(Real(1.0 / 60));
  state.SetLabel(method.name);
}
BENCHMARK(BM_WorldIntegrator)->DenseRange(0, 7)->Unit(benchmark::kMicrosecond);

// A 24 x 24 cloth pinned at two corners, falling and swinging: one World
// step's worth of implicit substeps (2).
void BM_ClothStep(benchmark::State& state) {
  physics::ClothDef def;
  def.columns = int(state.range(0));
  def.rows = int(state.range(0));
  def.pins = physics::ClothPins::TopCorners;
  def.edgeV_m = Vec3(0, 0, 2);
  auto cloth = physics::Deformable::cloth(def);
  physics::DeformableEnvironment env;
  for (auto _ : state) (*cloth)->step(Real(1.0 / 60), env);
  state.counters["cg_iterations_max"] = (*cloth)->stats().cgIterationsMax;
}
BENCHMARK(BM_ClothStep)->Arg(12)->Arg(24)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
