// Micro-benchmark for the terrain's targets on a 4097^2 map: tree build time,
// bytes per sample (heights + tree), ray casts per second on random rays.
// Not a test: prints one line per figure. Build with `cmake --build build
// --target benchmarks`, run build/bin/tumble_bench_terrain.
#include <chrono>
#include <cstdio>

#include "terrain/generators.h"
#include "terrain/terrain.h"

using namespace tumble;
using namespace tumble::terrain;

namespace {
double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

int main() {
  auto t0 = std::chrono::steady_clock::now();
  HeightMap map = generatePlasma(4097, 4097, {12345, 0.5});
  std::printf("plasma 4097^2 generation: %.3f s\n", secondsSince(t0));

  HeightTree tree;
  t0 = std::chrono::steady_clock::now();
  tree.build(map);
  std::printf("tree build 4097^2 (8x8-block leaves): %.4f s, %zu nodes, %d levels\n", secondsSince(t0),
              tree.nodeCount(), tree.levelCount());

  TerrainDesc desc;
  desc.heightScale_m = 0.003;  // ~200 m relief over 4 km: realistic slopes
  auto terrain = Terrain::create(std::move(map), desc);
  const TerrainMemory mem = terrain->memory();
  const double samples = 4097.0 * 4097.0;
  std::printf("memory: heights %zu B, tree %zu B, bytes_per_sample %.4f\n", mem.heights, mem.tree,
              double(mem.heights + mem.tree) / samples);

  const Aabb box = terrain->bounds();
  struct Kind {
    const char* name;
    int kind;
  };
  for (Kind k : {Kind{"steep (camera/picking, 30-90 deg down)", 0}, Kind{"grazing (line of sight, ~horizontal)", 1},
                 Kind{"short downward probes (wheels, 2 m)", 2}}) {
    Rng rng(7);
    const int kRays = k.kind == 1 ? 100000 : 1000000;
    int hits = 0;
    t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < kRays; ++r) {
      const Real x = Real(box.min.x() + rng.unit() * (box.max.x() - box.min.x()));
      const Real z = Real(box.min.z() + rng.unit() * (box.max.z() - box.min.z()));
      Vec3 o, d;
      Real maxT = 1e5f;
      if (k.kind == 0) {
        o = Vec3(x, box.max.y() + 50, z);
        d = Vec3(Real(rng.symmetric()), -Real(0.6 + rng.unit()), Real(rng.symmetric()));
      } else if (k.kind == 1) {
        o = Vec3(x, terrain->heightAt(x, z) + 2, z);
        d = Vec3(Real(rng.symmetric()), Real(0.02 * rng.symmetric()), Real(rng.symmetric()));
      } else {
        o = Vec3(x, terrain->heightAt(x, z) + 1, z);
        d = Vec3(0, -1, 0);
        maxT = 2;
      }
      if (terrain->rayCast(o, d, maxT)) ++hits;
    }
    const double s = secondsSince(t0);
    std::printf("ray casts, %s: %.0f rays/s (%d of %d hit)\n", k.name, kRays / s, hits, kRays);
  }
  return 0;
}
