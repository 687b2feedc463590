// The two joint solvers, lagrange and impulse, side by side: one World
// step of a hanging chain of 10, 100 and 1000 links (ball joints, links not
// colliding with their neighbours, nudged sideways so the solver has work),
// and of 10 rag-dolls dropped on a plane. Counter joint_error_m: the largest
// anchor separation over the timed steps (5 s simulated each, so both
// solvers see the same motion). Compare ratios within one run:
//   build/bin/tumble_bench_joints
// Counter solve_ms (Lagrange solver): its own share of the step (assembly,
// factorizations, solves in the 8 substeps; JointSolveStats::solveMs).
// Measured 2026-11-22 (see README, "Joints"): the Lagrange solver solves in
// the World's substeps and kept 4 um / 48 um / 21 um on 10 / 100 / 1000
// links where the impulse solver keeps 0.3 mm / 5 mm / 6.6 cm; the Lagrange
// solve time grows linearly with links. Since the Lagrange rows have a 1 %
// compliance (JointSettings::compliance, for piles of rag-dolls): relative
// to each row's own links, 43 um / 7.7 mm / 13 cm, solve 0.08 / 0.82 /
// 8.6 ms (12 um / 55 um / 21 um, 6.9 ms at 1000 links with compliance 0);
// relative to the whole system along the row where no contact touches
// (now): 12 um / 49 um / 1.1 mm, solve 0.10 / 1.0 / 11.1 ms (one more
// numeric factorization per substep).
#include <benchmark/benchmark.h>

#include "physics/joints/joint_system.h"
#include "physics/joints/ragdoll.h"
#include "physics/world.h"

namespace {

using namespace tumble;
using namespace tumble::physics;

constexpr Real kDt = Real(1.0 / 60.0);

JointSolverKind kindOf(const benchmark::State& state) {
  return state.range(0) == 0 ? JointSolverKind::Lagrange : JointSolverKind::Impulse;
}

void BM_HangingChain(benchmark::State& state) {
  WorldSettings ws;
  ws.enableSleep = false;
  World world(ws);
  JointSettings js;
  js.solver = kindOf(state);
  JointSystem joints(world, js);
  const int n = int(state.range(1));
  const Real L = Real(0.25);
  std::vector<BodyId> links;
  for (int i = 0; i < n; ++i) {
    BodyDef d;
    d.shape = Shape::box(Vec3(Real(0.05), L / 2, Real(0.05)));
    d.position_m = Vec3(0, -L * (Real(i) + Real(0.5)), 0);
    d.mass_kg = Real(0.5);
    links.push_back(world.createBody(d).value());
    const BodyId parent = i == 0 ? BodyId{} : links[i - 1];
    (void)joints.createJoint(makeJointDef(world, JointType::Ball, links[i], parent, Vec3(0, -L * Real(i), 0))).value();
    if (i > 0) world.disableCollision(links[i], links[i - 1]);
  }
  world.applyImpulse(links.back(), Vec3(Real(0.05), 0, 0), world.body(links.back()).position_m);
  for (int i = 0; i < 30; ++i) joints.step(kDt);  // warm start
  joints.resetErrorStats();
  double solveMs = 0;
  for (auto _ : state) {
    joints.step(kDt);
    solveMs += joints.lastSolve().solveMs;
  }
  state.counters["joint_error_m"] = joints.maxAnchorError_m();
  state.counters["solve_ms"] = solveMs / double(state.iterations());
  state.SetLabel(jointSolverName(js.solver));
}
BENCHMARK(BM_HangingChain)
    ->ArgsProduct({{0, 1}, {10, 100, 1000}})
    ->ArgNames({"impulse", "links"})
    ->Iterations(300)  // 5 s simulated each: the same motion for both solvers
    ->Unit(benchmark::kMillisecond);

void BM_RagdollDrop(benchmark::State& state) {
  World world;
  world.settings().enableSleep = false;  // time the solver, not an idle world
  JointSettings js;
  js.solver = kindOf(state);
  js.projectPositions = false;  // as the scenario host
  JointSystem joints(world, js);
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  (void)world.createBody(ground).value();
  for (int k = 0; k < 10; ++k)
    (void)buildRagdoll(world, joints, defaultHuman(), Vec3(Real(k % 5) * 2, Real(0.3 + 0.4 * (k / 5)), 0),
                       Quat(Eigen::AngleAxis<Real>(kPi / 2, Vec3::UnitX())))
        .value();
  for (auto _ : state) joints.step(kDt);
  state.counters["joint_error_m"] = joints.maxAnchorError_m();
  state.SetLabel(jointSolverName(js.solver));
}
BENCHMARK(BM_RagdollDrop)->Arg(0)->Arg(1)->ArgName("impulse")->Iterations(300)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
