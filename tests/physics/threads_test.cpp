// WorldSettings::threads: the contact passes shared between threads give the
// sequential result bit for bit ("Threads" in runtime/physics/contact_solver.cpp),
// and the worker pool under it runs every job on every thread once.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <vector>

#include "physics/compound_shape.h"
#include "physics/internal/worker_pool.h"
#include "physics_fixture.h"

namespace tumble::physics::test {
namespace {

TEST(WorkerPool, EveryThreadRunsEveryJobOnceAndRunReturnsWhenAllHaveFinished) {
  for (int threads : {1, 2, 3, 4}) {
    WorkerPool pool(threads);
    ASSERT_EQ(pool.threads(), threads);
    // Each job, thread t writes slot t after some work of its own; when run
    // returns, the caller must see every slot of this job. A run that
    // returned early, a thread that ran a job twice or missed one, or two
    // threads given one index would leave a slot of another job.
    std::vector<long> slot(static_cast<std::size_t>(threads), -1);
    std::atomic<int> ran{0};
    int wrong = 0;
    for (int job = 0; job < 500; ++job) {
      pool.run([&](int t) {
        ran.fetch_add(1);
        volatile double work = 0;
        for (int i = 0; i < 200 * (t + 1); ++i) work = work + 1;
        slot[std::size_t(t)] = job * 10 + long(work > 0);
      });
      for (int t = 0; t < threads; ++t) wrong += slot[std::size_t(t)] != job * 10 + 1;
    }
    EXPECT_EQ(ran.load(), 500 * threads) << threads << " threads";
    EXPECT_EQ(wrong, 0) << threads << " threads";
  }
}

struct Dropped {
  BodyId id;
  Real startHeight_m = 0;
};

/// A scene with every kind of contact row: a pyramid of boxes on a static
/// box, spheres that bounce (restitution, solved in the sequential order),
/// capsules and cylinders (rim contacts), a compound rolling on an
/// off-centre sphere, a kinematic paddle sweeping through, and sleep on.
std::vector<Dropped> buildMixedScene(World& w) {
  std::vector<Dropped> spheres;
  BodyDef floor;
  floor.type = BodyType::Static;
  floor.shape = Shape::box(Vec3(12, Real(0.5), 12));
  floor.position_m = Vec3(0, Real(-0.5), 0);
  floor.friction = Real(0.6);
  w.createBody(floor).value();
  const int layers = 7;
  for (int layer = 0; layer < layers; ++layer) {
    const int side = layers - layer;
    for (int i = 0; i < side; ++i)
      for (int k = 0; k < side; ++k) {
        const Real x = (Real(i) - Real(side - 1) / 2) * Real(1.02);
        const Real z = (Real(k) - Real(side - 1) / 2) * Real(1.02);
        addBody(w, Shape::box(Vec3::Constant(Real(0.5))), Vec3(x, Real(0.5) + Real(layer), z));
      }
  }
  for (int i = 0; i < 12; ++i) {
    const Real a = Real(i) * Real(0.52);
    spheres.push_back({addBody(w, Shape::sphere(Real(0.3)), Vec3(6 + std::cos(a), Real(1 + i), std::sin(a)), 1,
                               Real(0.4), Real(0.7)),
                       Real(1 + i)});
    addBody(w, Shape::capsule(Real(0.2), Real(0.4)), Vec3(-6 + std::sin(a), Real(1 + i), std::cos(a)));
    addBody(w, Shape::cylinder(Real(0.3), Real(0.2)), Vec3(std::cos(a), Real(1 + i), 6 + std::sin(a)));
  }
  CompoundChild ball, bar;
  ball.shape = Shape::sphere(Real(0.4));
  ball.position_m = Vec3(0, Real(-0.2), 0);
  bar.shape = Shape::box(Vec3(Real(0.6), Real(0.1), Real(0.1)));
  bar.position_m = Vec3(0, Real(0.3), 0);
  BodyDef weeble;
  weeble.shape = makeCompoundShape({ball, bar}).value();
  weeble.position_m = Vec3(0, 1, -6);
  weeble.angularVelocity_radps = Vec3(0, 0, 3);
  w.createBody(weeble).value();
  BodyDef paddle;
  paddle.type = BodyType::Kinematic;
  paddle.shape = Shape::box(Vec3(Real(0.2), Real(1), 3));
  paddle.position_m = Vec3(-9, 1, 0);
  paddle.linearVelocity_mps = Vec3(2, 0, 0);
  w.createBody(paddle).value();
  return spheres;
}

// 90 steps: the test runs beside other tests under ctest, where threads
// that spin for each other are slow (README, "Two cores").
TEST(Threads, TwoAndThreeThreadsGiveTheOneThreadStateBitForBit) {
  WorldSettings settings;
  World one(settings);
  const std::vector<Dropped> spheres = buildMixedScene(one);
  std::vector<std::unique_ptr<World>> shared;
  for (int threads : {2, 3}) {
    WorldSettings s = settings;
    s.threads = threads;
    shared.push_back(std::make_unique<World>(s));
    buildMixedScene(*shared.back());
  }
  for (int step = 0; step < 90; ++step) {
    one.step(Real(1.0 / 60.0));
    for (auto& w : shared) {
      w->step(Real(1.0 / 60.0));
      ASSERT_EQ(w->stateHash(), one.stateHash()) << w->settings().threads << " threads, step " << step;
    }
  }
  // The threads took part: the steps with at least 128 manifolds (the
  // pile falls asleep after about half a second, and what is left awake
  // has fewer; 33 of the 90 steps on this code).
  for (auto& w : shared) EXPECT_GT(w->stepsOnThreads(), 20u) << w->settings().threads << " threads";
  EXPECT_EQ(one.stepsOnThreads(), 0u);
  // And the world stepped: every sphere fell from its start (1 to 12 m up)
  // onto the floor or onto the others (a radius of 0.3 m: the lowest ends
  // 0.7 m below its start), nothing went non-finite.
  for (const Dropped& d : spheres) EXPECT_LT(one.body(d.id).position_m.y(), d.startHeight_m - Real(0.5));
  EXPECT_EQ(one.errorStats().nanEvents, 0);
}

}  // namespace
}  // namespace tumble::physics::test
