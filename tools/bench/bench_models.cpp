// Models: loading the 3DS jeep with assimp, building the mesh pass's draw
// list (tree culling + material sort) for many instances, and mass
// properties of a shipped closed mesh.
//
//   build/bin/tumble_bench_models
#include <benchmark/benchmark.h>

#include <string>

#include "physics/mass_properties.h"
#include "render/internal/camera_math.h"
#include "render/internal/mesh_draw_list.h"
#include "render/model.h"

namespace {

using namespace tumble;

std::shared_ptr<const render::Model> load(const std::string& path) {
  auto model = render::loadModel(path);
  return model.ok() ? *model : nullptr;
}

void BM_LoadJeep3ds(benchmark::State& state) {
  const std::string path = std::string(TUMBLE_SHARED_DIR) + "/assets/third_party/models/jeep1.3ds";
  for (auto _ : state) {
    auto model = load(path);
    if (!model) state.SkipWithError("jeep1.3ds did not load");
    benchmark::DoNotOptimize(model);
  }
}
BENCHMARK(BM_LoadJeep3ds)->Unit(benchmark::kMillisecond);

// N jeeps on a grid around the camera, about half of them outside the view.
void BM_DrawList(benchmark::State& state) {
  auto jeep = load(std::string(TUMBLE_SHARED_DIR) + "/assets/third_party/models/jeep1.3ds");
  auto hatchback = load(std::string(TUMBLE_SOURCE_DIR) + "/mods/base/assets/models/hatchback.obj");
  if (!jeep || !hatchback) {
    state.SkipWithError("models did not load");
    return;
  }
  std::vector<render::ModelInstance> instances;
  const int n = int(state.range(0));
  const int side = int(std::ceil(std::sqrt(double(n))));
  for (int i = 0; i < n; ++i) {
    render::ModelInstance inst;
    inst.model = i % 2 ? jeep : hatchback;
    inst.scale = Eigen::Vector3f::Constant(i % 2 ? 0.25f : 1.0f);
    inst.position = {8.0f * float(i % side - side / 2), 0, 8.0f * float(i / side - side / 2)};
    instances.push_back(inst);
  }
  render::Camera camera;
  camera.target = {0, 1, 0};
  camera.distance_m = 30;
  const Eigen::Matrix4f vp = render::makeFrameView(camera, 16.0f / 9.0f).viewProjection;
  std::vector<render::MeshDraw> draws;
  render::MeshStats stats;
  for (auto _ : state) {
    render::buildMeshDrawList(instances, vp, draws, stats);
    benchmark::DoNotOptimize(draws.data());
  }
  state.counters["draws"] = stats.drawCalls;
  state.counters["culled_nodes"] = stats.nodesCulled;
  state.counters["material_switches"] = stats.materialSwitches;
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_DrawList)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_MassPropertiesOfTruck(benchmark::State& state) {
  auto truck = load(std::string(TUMBLE_SOURCE_DIR) + "/mods/base/assets/models/truck.obj");
  if (!truck) {
    state.SkipWithError("truck.obj did not load");
    return;
  }
  const render::FlatMesh flat = render::flattenModel(*truck);
  std::vector<Vec3> v;
  for (const auto& p : flat.positions) v.push_back(p.cast<Real>());
  for (auto _ : state) {
    auto props = physics::massPropertiesOfMesh(v, flat.triangles, 800);
    benchmark::DoNotOptimize(props);
  }
  state.counters["triangles"] = double(flat.triangles.size());
}
BENCHMARK(BM_MassPropertiesOfTruck)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
