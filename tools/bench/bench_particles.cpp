// Particle update cost (target: 100 000 particles updated in < 1 ms
// on one core). Run: build/bin/tumble_bench_particles
//
// BM_ParticleUpdate: one emitter holding N live particles (lifetimes long
// enough that none die and rate 0, so only the update runs: gravity, drag,
// position, age, spin and the death check). BM_ParticleSteadyState: ten
// emitters spawning and killing at a steady 100 000 particles, the cost a
// real scene pays per step (spawning included).
#include <benchmark/benchmark.h>

#include "particles/particle_system.h"

namespace {

using namespace tumble::particles;

void BM_ParticleUpdate(benchmark::State& state) {
  const int n = int(state.range(0));
  EmitterDef d;
  d.rate_per_s = 0;
  d.lifetimeMin_s = d.lifetimeMax_s = 1e6f;
  d.maxCount = n;
  d.shape = EmitterShape::Sphere;
  d.spread_rad = 3.14f;
  d.speedMin_mps = 1;
  d.speedMax_mps = 4;
  d.gravityScale = 1;
  d.drag_per_s = 0.5f;
  d.spinMax_radps = 2;
  ParticleSystem ps(1);
  EmitterId id = ps.create(d, Eigen::Vector3f::Zero());
  ps.burst(id, n);
  ps.step(1.0f / 60);
  for (auto _ : state) {
    ps.step(1.0f / 60);
    benchmark::ClobberMemory();
  }
  state.counters["particles"] = ps.count(id);
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_ParticleUpdate)->Arg(10'000)->Arg(100'000)->Unit(benchmark::kMicrosecond);

void BM_ParticleSteadyState(benchmark::State& state) {
  // 10 emitters x 5000/s x 2 s mean life = 100 000 live particles.
  EmitterDef d;
  d.rate_per_s = 5000;
  d.lifetimeMin_s = 1;
  d.lifetimeMax_s = 3;
  d.maxCount = 20'000;
  d.shape = EmitterShape::Cone;
  d.spread_rad = 0.3f;
  d.speedMin_mps = 1;
  d.speedMax_mps = 4;
  d.gravityScale = 0.3f;
  d.drag_per_s = 0.5f;
  ParticleSystem ps(1);
  for (int i = 0; i < 10; ++i) ps.create(d, Eigen::Vector3f(float(i), 0, 0));
  for (int i = 0; i < 300; ++i) ps.step(1.0f / 60);
  for (auto _ : state) {
    ps.step(1.0f / 60);
    benchmark::ClobberMemory();
  }
  state.counters["particles"] = ps.particleCount();
}
BENCHMARK(BM_ParticleSteadyState)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
