// How the step cost and the memory grow with the number of bodies: square
// 3-D pyramids of touching unit cubes (half 0.5 m, 1 kg, friction 0.6) on a
// static ground box, every body awake (no sleep: the solver is timed, not an
// idle world), default WorldSettings (8 substeps x (4 solve + 2 relax)).
//
//   cmake --build build --target tumble_bench_scaling
//   build/bin/tumble_bench_scaling
//
// Bases 14, 22, 36 and 57 give 1015, 3795, 16206 and 63365 boxes (about
// 1k, 4k, 16k and 64k). One iteration is one World step, after two warm-up
// steps that build the contact set. Counters:
//   bodies, contacts          (contact points in the last step)
//   us_per_body               CPU time per step / bodies, microseconds
//   bytes_per_body            resident memory the world added (bodies,
//                             broad phase, contacts after the warm-up
//                             steps) / bodies, from /proc/self/statm
//   drift_m                   largest horizontal displacement of a box at
//                             the end: the pile stands (mm) or slumps (m)
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <vector>

#include "physics/world.h"

namespace {

using namespace tumble;
using namespace tumble::physics;

constexpr Real kDt = Real(1.0 / 60.0);

/// Resident set size of this process now, bytes.
double residentBytes() {
  long pages = 0, resident = 0;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return double(resident) * double(sysconf(_SC_PAGESIZE));
}

struct Pile {
  std::unique_ptr<World> world;
  std::vector<BodyId> boxes;
  std::vector<Vec3> start;
};

Pile makePile(int base) {
  Pile p;
  WorldSettings ws;
  ws.enableSleep = false;
  p.world = std::make_unique<World>(ws);
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::box(Vec3(Real(base + 10), Real(0.5), Real(base + 10)));
  ground.position_m = Vec3(0, Real(-0.5), 0);
  ground.friction = Real(0.6);
  (void)p.world->createBody(ground).value();
  for (int layer = 0; layer < base; ++layer) {
    const int n = base - layer;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        BodyDef b;
        b.shape = Shape::box(Vec3::Constant(Real(0.5)));
        b.mass_kg = 1;
        b.friction = Real(0.6);
        b.position_m = Vec3(Real(i - (n - 1) * 0.5), Real(0.5 + layer), Real(j - (n - 1) * 0.5));
        p.boxes.push_back(p.world->createBody(b).value());
        p.start.push_back(b.position_m);
      }
  }
  return p;
}

void BM_PyramidPile(benchmark::State& state) {
  const int base = int(state.range(0));
  const double before = residentBytes();
  Pile p = makePile(base);
  for (int i = 0; i < 2; ++i) p.world->step(kDt);
  const double added = residentBytes() - before;
  const std::clock_t c0 = std::clock();
  for (auto _ : state) p.world->step(kDt);
  const double cpuPerStep_s = double(std::clock() - c0) / CLOCKS_PER_SEC / double(state.iterations());
  double drift = 0;
  for (std::size_t i = 0; i < p.boxes.size(); ++i) {
    const Vec3 d = p.world->body(p.boxes[i]).position_m - p.start[i];
    drift = std::max(drift, double(std::hypot(d.x(), d.z())));
  }
  const double n = double(p.boxes.size());
  state.counters["bodies"] = n;
  state.counters["contacts"] = double(p.world->contactPointCount());
  state.counters["us_per_body"] = cpuPerStep_s * 1e6 / n;
  state.counters["bytes_per_body"] = added / n;
  state.counters["drift_m"] = drift;
}
BENCHMARK(BM_PyramidPile)->ArgName("base")->Arg(14)->Arg(22)->Arg(36)->Arg(57)->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()->Iterations(10);

}  // namespace

BENCHMARK_MAIN();
