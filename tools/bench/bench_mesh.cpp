// Static mesh collision: bodies among many static models with collision =
// "mesh", stepped with the object tree (covering and tight boxes skip the
// parts a body is not near) and with the brute force (every triangle's box
// of each model a body's box overlaps). Same scene, same steps; compare the
// two times within one run. Counters per step: triangles whose box was read,
// exact shape-triangle tests, subtrees skipped by a covering box.
//
//   cmake --build build --target tumble_bench_mesh && build/bin/tumble_bench_mesh
//
// Scenes: "scenery" is a 8 x 8 grid of the base mod's tree, rock and
// building models (1 to 3 nodes, 24 to 320 triangles; 3 to 5 m) with 128
// spheres, boxes and capsules dropped among them; "jeeps" is a 4 x 4 grid
// of the 3DS jeep (its parts are nodes, about 2000 triangles) scaled to 4 m
// long, with 64 bodies; "tiled ground" is one model of a 100 x 100 m bumpy
// ground (a track or a town square) made of 10 x 10 tiles, each a node of
// 200 triangles (20 000 in all), with 64 bodies resting and rolling on it.
#include <benchmark/benchmark.h>

#include <string>

#include "app/scene_models.h"
#include "physics/mesh_shape.h"
#include "physics/world.h"

namespace {

using namespace tumble;
using physics::BodyDef;
using physics::BodyType;
using physics::Shape;

struct Placed {
  std::string file;
  Real size_m;  ///< the model is scaled so that its longest side is this long
};

/// Builds the world: a plane, a grid of static models 6 m apart and bodies
/// dropped over them, then lets them fall for one second (warm).
void dropBodies(physics::World& w, int bodies, Real spread_m) {
  for (int i = 0; i < bodies; ++i) {
    BodyDef d;
    switch (i % 3) {
      case 0: d.shape = Shape::sphere(Real(0.3)); break;
      case 1: d.shape = Shape::box(Vec3(Real(0.3), Real(0.2), Real(0.25))); break;
      default: d.shape = Shape::capsule(Real(0.2), Real(0.3)); break;
    }
    const Real x = spread_m * Real(std::sin(1.7 * i)) / 2, z = spread_m * Real(std::cos(2.3 * i)) / 2;
    d.position_m = Vec3(x, 2 + Real(i % 7), z);
    d.linearVelocity_mps = Vec3(Real(std::cos(0.9 * i)), 0, Real(std::sin(0.9 * i)));
    d.allowSleep = false;  // keep every body in the narrow phase, step after step
    (void)w.createBody(d);
  }
  for (int s = 0; s < 60; ++s) w.step(Real(1.0 / 60));
}

bool buildScene(physics::World& w, const std::vector<Placed>& kinds, int side, int bodies, std::string* error) {
  app::ModelCache cache;
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  (void)w.createBody(ground);
  std::vector<Shape> shapes;
  for (const Placed& k : kinds) {
    auto tree = cache.meshTree(k.file);
    if (!tree) return *error = tree.error(), false;
    Vec3 lo = Vec3::Constant(1e30f), hi = -lo;
    for (const auto& node : tree->nodes)
      for (const Vec3& v : node.vertices_m) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    auto shape = physics::makeMeshShape(*tree, Vec3::Constant(k.size_m / (hi - lo).maxCoeff()));
    if (!shape) return *error = shape.error(), false;
    shapes.push_back(*shape);
  }
  const Real spacing = 6;
  for (int i = 0; i < side * side; ++i) {
    BodyDef d;
    d.type = BodyType::Static;
    d.shape = shapes[std::size_t(i) % shapes.size()];
    d.position_m = Vec3(spacing * Real(i % side - side / 2), 0, spacing * Real(i / side - side / 2));
    d.orientation = Quat(Eigen::AngleAxis<Real>(Real(0.7 * i), Vec3::UnitY()));
    (void)w.createBody(d);
  }
  dropBodies(w, bodies, spacing * Real(side));
  return true;
}

/// Steps the built world and reports the mesh counters per step.
void measure(benchmark::State& state, physics::World& w) {
  w.resetMeshStats();
  std::int64_t steps = 0;
  for (auto _ : state) {
    w.step(Real(1.0 / 60));
    ++steps;
  }
  const physics::MeshStats& s = w.meshStats();
  const double n = double(std::max<std::int64_t>(steps, 1));
  state.counters["pairs/step"] = double(s.pairs) / n;
  state.counters["tri_boxes/step"] = double(s.trianglesTested) / n;
  state.counters["exact/step"] = double(s.exactTests) / n;
  state.counters["skipped_subtrees/step"] = double(s.subtreesSkipped) / n;
  state.SetLabel(state.range(0) ? "tree" : "brute force");
}

void run(benchmark::State& state, const std::vector<Placed>& kinds, int side, int bodies) {
  physics::World w;
  w.settings().meshTree = state.range(0) != 0;
  std::string error;
  if (!buildScene(w, kinds, side, bodies, &error)) {
    state.SkipWithError(error.c_str());
    return;
  }
  measure(state, w);
}

const std::string kModels = std::string(TUMBLE_SOURCE_DIR) + "/mods/base/assets/models/";

void BM_MeshScenery(benchmark::State& state) {
  run(state,
      {{kModels + "tree.obj", 4}, {kModels + "rock.obj", 3}, {kModels + "building.obj", 5}},
      8, 128);
}
BENCHMARK(BM_MeshScenery)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);

void BM_MeshJeeps(benchmark::State& state) {
  run(state, {{std::string(TUMBLE_SHARED_DIR) + "/assets/third_party/models/jeep1.3ds", 4}}, 4, 64);
}
BENCHMARK(BM_MeshJeeps)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);

void BM_MeshTiledGround(benchmark::State& state) {
  physics::MeshTreeInput tree;
  tree.nodes.resize(1);  // the root holds no triangles; the tiles are its children
  constexpr int kTiles = 10, kCells = 10;
  constexpr Real kTile_m = 10, kCell_m = kTile_m / kCells;
  auto height = [](Real x, Real z) { return Real(0.4) * std::sin(Real(0.3) * x) * std::cos(Real(0.23) * z); };
  for (int tz = 0; tz < kTiles; ++tz)
    for (int tx = 0; tx < kTiles; ++tx) {
      physics::MeshTreeNodeInput node;
      node.parent = 0;
      const Real x0 = kTile_m * Real(tx - kTiles / 2), z0 = kTile_m * Real(tz - kTiles / 2);
      for (int j = 0; j <= kCells; ++j)
        for (int i = 0; i <= kCells; ++i) {
          const Real x = x0 + Real(i) * kCell_m, z = z0 + Real(j) * kCell_m;
          node.vertices_m.emplace_back(x, height(x, z), z);
        }
      auto at = [](int i, int j) { return std::uint32_t(j * (kCells + 1) + i); };
      for (int j = 0; j < kCells; ++j)
        for (int i = 0; i < kCells; ++i) {
          node.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j)});
          node.triangles.push_back({at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)});
        }
      tree.nodes.push_back(std::move(node));
    }
  physics::World w;
  w.settings().meshTree = state.range(0) != 0;
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = physics::makeMeshShape(tree).value();
  (void)w.createBody(ground);
  dropBodies(w, 64, 80);
  measure(state, w);
}
BENCHMARK(BM_MeshTiledGround)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
