// World basics: handles, validation, integration, determinism, faults.
#include "physics_fixture.h"

namespace tumble::physics::test {

TEST(World, StaleHandlesAreDetected) {
  World w;
  BodyId a = addBody(w, Shape::sphere(1), Vec3(0, 5, 0));
  EXPECT_TRUE(w.isValid(a));
  EXPECT_TRUE(w.destroyBody(a));
  EXPECT_FALSE(w.isValid(a));
  EXPECT_FALSE(w.destroyBody(a));
  BodyId b = addBody(w, Shape::sphere(1), Vec3(0, 5, 0));
  EXPECT_EQ(a.index, b.index) << "slot is reused";
  EXPECT_FALSE(w.isValid(a)) << "old handle to a reused slot must stay invalid";
  EXPECT_TRUE(w.isValid(b));
  EXPECT_FALSE(w.isValid(BodyId{}));
}

TEST(World, BadDefinitionsAreRefusedWithTheField) {
  World w;
  BodyDef d;
  d.shape = Shape::box(Vec3(1, 0, 1));
  auto r = w.createBody(d);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("half_extents"), std::string::npos) << r.error();
  d.shape = Shape::sphere(1);
  d.mass_kg = -1;
  r = w.createBody(d);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("mass"), std::string::npos);
  d.mass_kg = 1;
  d.position_m = Vec3(std::nanf(""), 0, 0);
  r = w.createBody(d);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("position"), std::string::npos);
  d.position_m = Vec3::Zero();
  d.restitution = 2;
  EXPECT_FALSE(w.createBody(d).ok());
  EXPECT_EQ(w.bodyCount(), 0);
}

TEST(World, FreeFallMatchesSemiImplicitEuler) {
  // Semi-implicit Euler with step h gives y_n = y0 - g h^2 n (n+1) / 2,
  // i.e. the exact parabola plus g h t / 2. Check both: the exact discrete
  // answer to round-off and the continuous one within the O(h) bound.
  World w;
  w.settings().substeps = 1;
  BodyId b = addBody(w, Shape::sphere(Real(0.5)), Vec3(0, 100, 0));
  const Real h = Real(1.0 / 60.0);
  const int n = 120;
  for (int i = 0; i < n; ++i) w.step(h);
  double g = kStandardGravity, t = n * h;
  double discrete = 100 - g * h * h * n * (n + 1) / 2;
  double exact = 100 - g * t * t / 2;
  EXPECT_NEAR(w.body(b).position_m.y(), discrete, 1e-3);
  EXPECT_NEAR(w.body(b).position_m.y(), exact, g * h * t / 2 + 1e-3);
  EXPECT_NEAR(w.body(b).linearVelocity_mps.y(), -g * t, 1e-3);
}

TEST(World, SameInputsGiveTheSameHash) {
  auto run = [] {
    World w;
    addGround(w);
    for (int i = 0; i < 10; ++i) {
      BodyDef d;
      d.shape = i % 2 ? Shape::box(Vec3(Real(0.4), Real(0.3), Real(0.5))) : Shape::sphere(Real(0.4));
      d.position_m = Vec3(Real(0.3) * i, 1 + Real(0.9) * i, Real(0.1) * i);
      d.orientation = Quat(Eigen::AngleAxis<Real>(Real(0.3) * i, Vec3(1, 1, 0).normalized()));
      w.createBody(d).value();
    }
    simulate(w, 3);
    return w.stateHash();
  };
  std::uint64_t a = run(), b = run();
  EXPECT_EQ(a, b);
}

TEST(World, NonFiniteBodyIsFrozenAndDoesNotSpread) {
  World w;
  addGround(w);
  BodyId bad = addBody(w, Shape::box(Vec3::Constant(Real(0.5))), Vec3(0, Real(0.5), 0));
  BodyId good = addBody(w, Shape::box(Vec3::Constant(Real(0.5))), Vec3(0, Real(1.5), 0));
  simulate(w, Real(0.5));
  w.setLinearVelocity(bad, Vec3(std::numeric_limits<Real>::quiet_NaN(), 0, 0));
  simulate(w, 2);
  EXPECT_EQ(w.errorStats().nanEvents, 1);
  EXPECT_TRUE(w.body(bad).frozen);
  EXPECT_TRUE(w.body(bad).position_m.allFinite());
  const Body& g = w.body(good);
  EXPECT_TRUE(g.position_m.allFinite() && g.linearVelocity_mps.allFinite());
  EXPECT_NEAR(g.position_m.y(), 1.5, 0.02) << "the box on top still rests on the frozen one";
}

TEST(World, RayCastHitsShapesAtTheirAnalyticDistance) {
  World w;
  addGround(w);
  BodyId s = addBody(w, Shape::sphere(1), Vec3(10, 5, 0));
  BodyId b = addBody(w, Shape::box(Vec3(1, 2, 1)), Vec3(0, 5, 10));
  BodyId c = addBody(w, Shape::capsule(Real(0.5), 1), Vec3(-10, 5, 0));
  RayHit hit;
  ASSERT_TRUE(w.rayCast(Vec3(0, 5, 0), Vec3(1, 0, 0), 100, &hit));
  EXPECT_EQ(hit.body, s);
  EXPECT_NEAR(hit.distance_m, 9, 1e-4);
  EXPECT_NEAR(hit.normal.x(), -1, 1e-4);
  ASSERT_TRUE(w.rayCast(Vec3(0, 5, 0), Vec3(0, 0, 3), 100, &hit));
  EXPECT_EQ(hit.body, b);
  EXPECT_NEAR(hit.distance_m, 9, 1e-4);
  ASSERT_TRUE(w.rayCast(Vec3(0, 5, 0), Vec3(-1, 0, 0), 100, &hit));
  EXPECT_EQ(hit.body, c);
  EXPECT_NEAR(hit.distance_m, Real(9.5), 1e-4);
  ASSERT_TRUE(w.rayCast(Vec3(-10, 20, 0), Vec3(0, -1, 0), 100, &hit));
  EXPECT_EQ(hit.body, c);
  EXPECT_NEAR(hit.distance_m, 20 - Real(6.5), 1e-4) << "hits the top cap";
  ASSERT_TRUE(w.rayCast(Vec3(3, 7, 3), Vec3(0, -1, 0), 100, &hit));
  EXPECT_NEAR(hit.distance_m, 7, 1e-4) << "ground plane";
  EXPECT_FALSE(w.rayCast(Vec3(0, 5, 0), Vec3(0, 0, -1), 100, nullptr));
  auto all = w.rayCastAll(Vec3(20, 5, 0), Vec3(-1, 0, 0), 100);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].body, s);
  EXPECT_EQ(all[1].body, c);
}

TEST(World, RestingBodiesFallAsleepAndAnImpulseWakesThem) {
  World w;
  addGround(w);
  BodyId b = addBody(w, Shape::box(Vec3::Constant(Real(0.5))), Vec3(0, Real(0.6), 0));
  simulate(w, 3);
  EXPECT_FALSE(w.body(b).awake);
  w.applyImpulse(b, Vec3(0, 5, 0), w.body(b).position_m);
  EXPECT_TRUE(w.body(b).awake);
  w.step(Real(1.0 / 60));
  EXPECT_GT(w.body(b).position_m.y(), 0.5);
}

TEST(World, ABodyHittingASleeperWakesItAndPassesItsMomentum) {
  // Equal boxes, restitution 1, no gravity: the moving one stops and the
  // struck one leaves at its speed, even though the struck one was asleep
  // (it must be woken before the speculative contact acts, or it would act
  // as a wall).
  World w;
  w.settings().gravity_mps2 = Vec3::Zero();
  w.settings().restitutionThreshold_mps = Real(0.1);
  BodyId sleeper = addBody(w, Shape::box(Vec3::Constant(Real(0.5))), Vec3(5, 0, 0), 1, 0, 1);
  simulate(w, 1);
  ASSERT_FALSE(w.body(sleeper).awake) << "the target must be asleep before the hit";
  BodyId striker = addBody(w, Shape::box(Vec3::Constant(Real(0.5))), Vec3(0, 0, 0), 1, 0, 1);
  w.setLinearVelocity(striker, Vec3(3, 0, 0));
  simulate(w, 2);
  EXPECT_NEAR(w.body(sleeper).linearVelocity_mps.x(), 3, 0.06);
  EXPECT_NEAR(w.body(striker).linearVelocity_mps.x(), 0, 0.06);
}

}  // namespace tumble::physics::test
