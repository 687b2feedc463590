// Shapes: what hulls and compounds cost next to boxes, hull construction,
// and shape casts. Compare ratios within one run (shared machine):
//   build/bin/tumble_bench_shapes
// BM_Pile/<kind>: 64 bodies dropped in a 4 x 4 x 4 block onto the ground,
// stepped for 2 s (sleep off); kind 0 boxes, 1 the same boxes as hulls,
// 2 T-handle compounds (a box and a capsule), 3 16-sided prisms (hulls),
// 4 cylinders of the prisms' size (the exact shape against its hull).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/world.h"

namespace tumble::physics {
namespace {

std::vector<Vec3> boxPoints(const Vec3& h) {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i) p.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  return p;
}

Shape pileShape(int kind) {
  const Vec3 h = Vec3::Constant(Real(0.4));
  switch (kind) {
    case 1: return makeHullShape(boxPoints(h)).value();
    case 2:
      return makeCompoundShape({{Shape::box(Vec3(Real(0.4), Real(0.08), Real(0.08))), Vec3::Zero(), Quat::Identity()},
                                {Shape::capsule(Real(0.06), Real(0.2)), Vec3(0, 0, Real(0.3)),
                                 Quat(Eigen::AngleAxis<Real>(kPi / 2, Vec3::UnitX()))}})
          .value();
    case 3: {
      std::vector<Vec3> p;
      for (int i = 0; i < 16; ++i) {
        const Real a = 2 * kPi * Real(i) / 16;
        p.emplace_back(Real(0.4) * std::cos(a), Real(-0.3), Real(0.4) * std::sin(a));
        p.emplace_back(Real(0.4) * std::cos(a), Real(0.3), Real(0.4) * std::sin(a));
      }
      return makeHullShape(p).value();
    }
    case 4: return Shape::cylinder(Real(0.4), Real(0.3));
    default: return Shape::box(h);
  }
}

void BM_Pile(benchmark::State& state) {
  const int kind = int(state.range(0));
  const Shape shape = pileShape(kind);
  for (auto _ : state) {
    state.PauseTiming();
    WorldSettings ws;
    ws.enableSleep = false;
    World w(ws);
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape = Shape::plane();
    w.createBody(ground).value();
    for (int i = 0; i < 64; ++i) {
      BodyDef d;
      d.shape = shape;
      d.position_m = Vec3(Real(i % 4), Real(0.5) + Real(i / 16) * Real(0.9), Real((i / 4) % 4));
      d.mass_kg = 1;
      w.createBody(d).value();
    }
    state.ResumeTiming();
    for (int s = 0; s < 120; ++s) w.step(Real(1.0 / 60.0));
  }
  const char* const labels[] = {"boxes", "box hulls", "T compounds", "16-gon prisms", "cylinders"};
  state.SetLabel(labels[kind]);
}
BENCHMARK(BM_Pile)->DenseRange(0, 4)->Unit(benchmark::kMillisecond);

void BM_HullBuild(benchmark::State& state) {
  // Points on a sphere: every point is a hull vertex (the worst case).
  const int n = int(state.range(0));
  std::vector<Vec3> p;
  const Real golden = kPi * (3 - std::sqrt(Real(5)));
  for (int i = 0; i < n; ++i) {
    const Real y = 1 - 2 * (Real(i) + Real(0.5)) / Real(n), r = std::sqrt(1 - y * y);
    p.emplace_back(r * std::cos(golden * Real(i)), y, r * std::sin(golden * Real(i)));
  }
  for (auto _ : state) benchmark::DoNotOptimize(makeHullShape(p));
}
BENCHMARK(BM_HullBuild)->Arg(16)->Arg(64)->Arg(256)->Unit(benchmark::kMicrosecond);

void BM_ShapeCast(benchmark::State& state) {
  // A wheel-sized sphere cast down into a field of 100 boxes on the ground.
  World w;
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  w.createBody(ground).value();
  for (int i = 0; i < 100; ++i) {
    BodyDef d;
    d.type = BodyType::Static;
    d.shape = Shape::box(Vec3::Constant(Real(0.5)));
    d.position_m = Vec3(Real(i % 10) * 2, Real(0.5), Real(i / 10) * 2);
    w.createBody(d).value();
  }
  const Shape wheel = Shape::sphere(Real(0.35));
  int k = 0;
  for (auto _ : state) {
    ShapeCastHit hit;
    const Vec3 from(Real(k % 19), 3, Real((k / 19) % 19));
    benchmark::DoNotOptimize(w.shapeCast(wheel, from, Quat::Identity(), Vec3(0, -1, 0), 5, &hit));
    ++k;
  }
}
BENCHMARK(BM_ShapeCast)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace tumble::physics

BENCHMARK_MAIN();
