// Input costs: a Lua input.value call (the per-step read every vehicle
// controller makes), compared in the same run with a plain Lua function
// call, and the C++ side: one fixed step's snapshot and one key event with
// the base mod's bindings.
//
//   build/bin/tumble_bench_input
//
// Lua numbers are per call: each benchmark iteration is one on_update that
// makes kCallsPerUpdate calls, so the loop and the callback cost divide out.
#include <SDL.h>
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>

#include "app/scene.h"
#include "input/input_system.h"
#include "physics/world.h"
#include "script/mod_bindings.h"
#include "script/scenario_host.h"

namespace {

namespace fs = std::filesystem;
using namespace tumble;

constexpr int kCallsPerUpdate = 1000;

input::BindingSet baseBindings() {
  script::ModInfo base;
  base.name = "base";
  base.dir = std::string(TUMBLE_SOURCE_DIR) + "/mods/base";
  return script::loadModBindings(base).set;
}

// A scenario whose on_update runs `body` kCallsPerUpdate times.
void runLuaLoop(benchmark::State& state, const std::string& body) {
  const fs::path dir = fs::temp_directory_path() / "tumble_bench_input" / "m";
  fs::create_directories(dir / "scenarios");
  std::ofstream(dir / "mod.lua") << "return {name = \"m\", version = \"1.0.0\", api = 1}\n";
  std::ofstream(dir / "scenarios" / "s.lua")
      << "local v = 0\nlocal function f(name) return 0 end\nreturn {on_update = function()\n  for i = 1, "
      << kCallsPerUpdate << " do " << body << " end\nend}\n";
  app::SceneOptions options;
  options.scenarioRef = "m:s";
  options.modDirs = {dir.parent_path().string()};
  options.bindings = baseBindings();
  auto scene = app::Scene::create(options);
  if (!scene) {
    state.SkipWithError(scene.error().c_str());
    return;
  }
  input::InputSystem& in = scene.value()->input();
  script::ScenarioHost& host = scene.value()->host();
  in.inject(in.find("throttle"), 0.7);
  scene.value()->start();
  std::int64_t step = 0;
  for (auto _ : state) {
    in.step();
    host.update(double(step) / 60, 1.0 / 60, step);
    ++step;
  }
  if (!host.errors().empty()) state.SkipWithError(host.errors()[0].summary().c_str());
  state.SetItemsProcessed(state.iterations() * kCallsPerUpdate);
}

void BM_LuaInputValue(benchmark::State& state) { runLuaLoop(state, "v = input.value(\"throttle\")"); }
BENCHMARK(BM_LuaInputValue);

// The same loop calling a plain Lua function: the floor any call pays.
void BM_LuaPlainCall(benchmark::State& state) { runLuaLoop(state, "v = f(\"throttle\")"); }
BENCHMARK(BM_LuaPlainCall);

void BM_InputStep(benchmark::State& state) {
  input::InputSystem in(baseBindings());
  for (const char* c : {"vehicle", "interact"}) (void)in.setContextEnabled(c, true);
  for (auto _ : state) {
    in.step();
    benchmark::DoNotOptimize(in.value(0));
  }
}
BENCHMARK(BM_InputStep);

void BM_InputKeyEvent(benchmark::State& state) {
  input::InputSystem in(baseBindings());
  for (const char* c : {"vehicle", "interact"}) (void)in.setContextEnabled(c, true);
  SDL_Event e{};
  e.key.keysym.scancode = SDL_SCANCODE_W;
  bool down = false;
  for (auto _ : state) {
    down = !down;
    e.type = down ? SDL_KEYDOWN : SDL_KEYUP;
    benchmark::DoNotOptimize(in.handleEvent(e));
  }
}
BENCHMARK(BM_InputKeyEvent);

}  // namespace

BENCHMARK_MAIN();
