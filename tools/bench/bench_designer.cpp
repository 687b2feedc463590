// The scenario designer at scale (runtime/app/design_document.h), on a
// 4097 x 4097 map at 1 m spacing: one brush dab of radius 20 m (heights,
// the collision tree's boxes refitted over the dab, the undo tiles it
// touches), one paint dab of radius 20 m, and saving the whole map as a mod
// (16-bit height PNG, five layer PNGs, scenario, design file). Targets:
// a dab <= 2 ms, a save <= 1 s. BM_DabOnScreen adds what the renderer then
// does (offscreen, Mesa): the chunks the dab touched rebuilt with their
// normals and uploaded, and the block materials under it.
//
//   cmake --build build --target tumble_bench_designer
//   build/bin/tumble_bench_designer
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <memory>

#include <cstdlib>

#include "app/design_document.h"
#include "core/process_stats.h"
#include "app/player_settings.h"
#include "bench_renderer.h"
#include "render/renderer.h"
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

// A dab as the player sees it: the document's dab, then the frame that
// shows it, the terrain brought up to date by the renderer. The time
// reported is the renderer's terrain update in that frame (TerrainStats::
// updateTime_ms: dropping the touched chunks, rebuilding and uploading the
// ones in view with their normals, the block materials under the dab);
// the dab itself is BM_BrushDab, the whole frame is the frame_ms counter.
// The eye looks at the brush from 80 m, as in the designer; dabs walk back
// and forth across 60 m in front of it.
void BM_DabOnScreen(benchmark::State& state) {
  const auto level = static_cast<app::QualityLevel>(state.range(0));
  DesignDocument& d = bigMap();
  auto renderer = bench::offscreenRenderer(state, level);
  if (!renderer) return;
  render::Camera& camera = renderer->camera();
  camera.target = {0, float(d.groundHeight_m(0, 300)), 300};
  camera.yaw_rad = 0.6f;
  camera.pitch_rad = 0.5f;
  camera.distance_m = 80;
  render::TerrainSurface surface;
  d.fillSurface(surface);
  surface.revision = 1;
  d.takeChangedSamples();
  render::FrameSnapshot frame;
  frame.terrain = &surface;
  render::Controls controls;
  // The first frame builds every chunk in view: not timed.
  if (const Status s = renderer->drawFrame(frame, render::HudStats{}, controls); !s) {
    state.SkipWithError(s.error().c_str());
    return;
  }
  Brush b;
  b.radius_m = 20;
  b.strength_m_per_s = 2;
  double x = -30, step = 2, frames_ms = 0, invalidated = 0, uploaded = 0;
  d.beginStroke();
  for (auto _ : state) {
    const SampleRect r = d.dab(b, x, 300, 1.0 / 60);
    d.takeChangedSamples();
    // Pointers and sizes; then the changed rectangle since the revision the
    // renderer drew, as the designer hands it over (DesignerMode::fillSurface).
    const std::uint64_t shown = surface.revision;
    d.fillSurface(surface);
    surface.revision = shown + 1;
    surface.dirtySinceRevision = shown;
    surface.dirtyI0 = r.i0;
    surface.dirtyJ0 = r.j0;
    surface.dirtyI1 = r.i1;
    surface.dirtyJ1 = r.j1;
    const Stopwatch frameClock;
    if (const Status s = renderer->drawFrame(frame, render::HudStats{}, controls); !s) {
      state.SkipWithError(s.error().c_str());
      break;
    }
    frames_ms += 1000.0 * frameClock.seconds();
    const render::TerrainStats& t = renderer->terrainStats();
    state.SetIterationTime(t.updateTime_ms / 1000.0);
    invalidated += t.chunksInvalidated;
    uploaded += t.chunksUploaded;
    x += step;
    if (x > 30 || x < -30) step = -step;
  }
  d.endStroke();
  const double n = double(std::max<std::int64_t>(1, state.iterations()));
  state.counters["frame_ms"] = frames_ms / n;
  state.counters["chunks_invalidated"] = invalidated / n;
  state.counters["chunks_uploaded"] = uploaded / n;
  state.SetLabel(app::qualityName(level));
}
// A fixed count: the timed part is a small share of each frame, so a minimum
// time would take thousands of software-rendered frames.
BENCHMARK(BM_DabOnScreen)->DenseRange(0, 2)->ArgName("preset")->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(60);

}  // namespace

BENCHMARK_MAIN();
