// Rag-doll piles under the impulse joint solver (joints solved with the contacts): the
// Tumble half of `tools/tumble compare ragdolls_100`, timed by CPU time so
// that the figure holds on a shared machine (the compare tool times wall
// clock and divides by Bullet's in the same run).
//
//   cmake --build build --target tumble_bench_ragdolls
//   build/bin/tumble_bench_ragdolls --benchmark_repetitions=3
//
// BM_Ragdolls100: 100 default humans (11 parts, 10 joints) lying in a 10 x 10
// grid 2.5 m apart, dropped from 0.5-1.4 m onto a static ground box, as
// tumble_compare's ragdolls_100 lays them out; default WorldSettings (8
// substeps x (4 solve + 2 relax) sweeps). Arg sleep=0 keeps every body awake
// (the compare tool's setting: it times the solver, not an idle world);
// sleep=1 is what a player gets (settled dolls fall asleep island by
// island). rolling=0 gives the parts no rolling resistance, as the compare
// tool builds them (sleep:0/rolling:0 is its Tumble half); rolling=1 keeps
// spawn_ragdoll's 0.2. One iteration is one World step; 300 steps = 5 s simulated, the
// same motion in every repetition. Counters: joint_error_m (largest anchor
// separation after any step), contacts (contact points in the last step),
// asleep (bodies asleep at the end), fastest_mps (the fastest part at the
// end: how still a settled pile is).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "physics/joints/joint_system.h"
#include "physics/joints/ragdoll.h"
#include "physics/world.h"

namespace {

using namespace tumble;
using namespace tumble::physics;

constexpr Real kDt = Real(1.0 / 60.0);

struct Pile {
  std::unique_ptr<World> world;
  std::unique_ptr<JointSystem> joints;
  std::vector<BodyId> parts;
};

Pile makePile(bool sleep, bool rolling) {
  Pile p;
  WorldSettings ws;
  ws.enableSleep = sleep;
  p.world = std::make_unique<World>(ws);
  JointSettings js;
  js.solver = JointSolverKind::Impulse;
  js.projectPositions = false;  // as the scenario host
  p.joints = std::make_unique<JointSystem>(*p.world, js);
  BodyDef ground;  // Bullet's benchmark ground: 500 x 100 x 500 m, top at y = 0
  ground.type = BodyType::Static;
  ground.shape = Shape::box(Vec3(250, 50, 250));
  ground.position_m = Vec3(0, -50, 0);
  ground.friction = Real(0.6);
  (void)p.world->createBody(ground).value();
  RagdollDesc desc = defaultHuman(Real(1.75), Real(75));
  if (!rolling) desc.rollingResistance = 0;  // as tumble_compare builds its parts
  const Quat lying(Eigen::AngleAxis<Real>(kPi / 2, Vec3::UnitX()));
  for (int k = 0; k < 100; ++k) {
    const Vec3 origin(Real((k % 10 - 4.5) * 2.5), Real(0.5 + 0.3 * (k % 4)), Real((k / 10 - 4.5) * 2.5 - 0.9));
    const Ragdoll doll = buildRagdoll(*p.world, *p.joints, desc, origin, lying).value();
    p.parts.insert(p.parts.end(), doll.bodies.begin(), doll.bodies.end());
  }
  return p;
}

void BM_Ragdolls100(benchmark::State& state) {
  Pile p = makePile(state.range(0) != 0, state.range(1) != 0);
  double jointError = 0;
  for (auto _ : state) {
    p.joints->beforeWorldStep();  // as the scenario host and the compare tool do
    p.world->step(kDt);
    jointError = std::max(jointError, double(p.joints->anchorError_m()));
  }
  int asleep = 0;
  double fastest = 0;
  for (BodyId id : p.parts) {
    const Body& b = p.world->body(id);
    asleep += b.awake ? 0 : 1;
    fastest = std::max(fastest, double(b.linearVelocity_mps.norm()));
  }
  state.counters["fastest_mps"] = fastest;
  state.counters["joint_error_m"] = jointError;
  state.counters["contacts"] = double(p.world->contactPointCount());
  state.counters["asleep"] = asleep;
}
BENCHMARK(BM_Ragdolls100)
    ->Args({0, 0})  // tumble_compare's ragdolls_100
    ->Args({0, 1})  // spawn_ragdoll's parts (rolling resistance 0.2), kept awake
    ->Args({1, 1})  // what a player gets
    ->ArgNames({"sleep", "rolling"})
    ->Iterations(300)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
