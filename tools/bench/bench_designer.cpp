// The scenario designer at scale (runtime/app/design_document.h), on a
// 4097 x 4097 map at 1 m spacing: one brush dab of radius 20 m (heights,
// the collision tree's boxes refitted over the dab, the undo tiles it
// touches), one paint dab of radius 20 m, and saving the whole map as a mod
// (16-bit height PNG, five layer PNGs, scenario, design file). Targets:
// a dab <= 2 ms, a save <= 1 s.
//
//   cmake --build build --target tumble_bench_designer
//   build/bin/tumble_bench_designer
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <memory>

#include "app/design_document.h"
#include "terrain/png_io.h"

namespace {

using namespace tumble;
using namespace tumble::app;

DesignDocument& bigMap() {
  static std::unique_ptr<DesignDocument> doc = [] {
    NewMapOptions o;
    o.generator = "plasma";
    o.size_samples = 4097;
    o.seed = 9;
    o.minHeight_m = 0;
    o.maxHeight_m = 200;
    auto d = DesignDocument::create(o);
    return std::make_unique<DesignDocument>(std::move(d.value()));
  }();
  return *doc;
}

// Dabs along a line through the map, one stroke per benchmark run; the
// stroke's end (the undo step) is measured apart in BM_StrokeEnd.
void BM_BrushDab(benchmark::State& state) {
  DesignDocument& d = bigMap();
  Brush b;
  b.kind = BrushKind(state.range(0));
  b.radius_m = 20;
  b.strength_m_per_s = 2;
  b.falloff = 0.5;
  b.flattenHeight_m = 100;
  double x = -1500;
  d.beginStroke();
  for (auto _ : state) {
    benchmark::DoNotOptimize(d.dab(b, x, 300, 1.0 / 60));
    x += 2;  // a dab every 2 m: the mouse dragged at 120 m/s, 60 dabs a second
    if (x > 1500) x = -1500;
  }
  d.endStroke();  // after the timed loop
}
BENCHMARK(BM_BrushDab)->DenseRange(0, 4)->ArgName("kind(raise,lower,smooth,flatten,noise)")->Unit(benchmark::kMicrosecond);

void BM_PaintDab(benchmark::State& state) {
  DesignDocument& d = bigMap();
  const Surface& mud = *findSurface("mud");
  const Surface& rock = *findSurface("rock");
  double x = -1500;
  int k = 0;
  d.beginStroke();
  for (auto _ : state) {
    benchmark::DoNotOptimize(d.paint(++k % 2 ? mud : rock, x, -300, 20));
    x += 2;
    if (x > 1500) x = -1500;
  }
  d.endStroke();
}
BENCHMARK(BM_PaintDab)->Unit(benchmark::kMicrosecond);

// A stroke of 60 dabs (one second of dragging, 120 m) and its end: the
// undo step kept from the tiles it touched.
void BM_StrokeOf60Dabs(benchmark::State& state) {
  DesignDocument& d = bigMap();
  Brush b;
  b.radius_m = 20;
  double z = -1500;
  for (auto _ : state) {
    d.beginStroke();
    for (int k = 0; k < 60; ++k) d.dab(b, -60 + 2 * k, z, 1.0 / 60);
    d.endStroke();
    z += 50;
    if (z > 1500) z = -1500;
  }
  state.counters["undo_MiB"] = double(d.undoBytes()) / (1 << 20);
}
BENCHMARK(BM_StrokeOf60Dabs)->Unit(benchmark::kMillisecond);

void BM_Save(benchmark::State& state) {
  DesignDocument& d = bigMap();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("tumble_bench_designer_" + std::to_string(::getpid()));
  for (auto _ : state) {
    Status st = d.saveAsMod(dir.string(), "bench", "big");
    if (!st) state.SkipWithError(st.error().c_str());
  }
  std::uintmax_t bytes = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir / "bench"))
    if (e.is_regular_file() && e.path().string().find("/backup/") == std::string::npos) bytes += e.file_size();
  state.counters["MB_written"] = double(bytes) / 1e6;
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}
BENCHMARK(BM_Save)->Iterations(3)->MeasureProcessCPUTime()->Unit(benchmark::kMillisecond);

// The save's longest part alone: the 16-bit height PNG, encoded as the save
// does it (on its own thread there, beside the five layers).
void BM_EncodeHeights(benchmark::State& state) {
  const terrain::HeightMap& h = bigMap().terrain().heights();
  for (auto _ : state) {
    auto png = terrain::encodePngGrey16(h.samples().data(), h.width(), h.height(), {1, 2, true});
    benchmark::DoNotOptimize(png);
  }
}
BENCHMARK(BM_EncodeHeights)->Iterations(3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
