// Rag-doll description and builder: the default human's anthropometry, the
// collision-filter pairs, and a drop on the ground.
#include <gtest/gtest.h>

#include <cstdio>

#include "physics/joints/ragdoll.h"

namespace tumble::physics {
namespace {

TEST(Ragdoll, DefaultHumanHasElevenPartsWithWintersMasses) {
  const Real H = Real(1.8), M = 80;
  RagdollDesc d = defaultHuman(H, M);
  ASSERT_TRUE(validateRagdoll(d).ok());
  EXPECT_EQ(d.parts.size(), 11u);
  EXPECT_EQ(d.joints.size(), 10u);
  double mass = 0, top = 0, bottom = 1e9;
  for (const RagdollPart& p : d.parts) {
    mass += p.mass_kg;
    const double reach = p.shape == RagdollShape::Box ? p.halfExtents_m.y() : p.halfHeight_m + p.radius_m;
    top = std::max(top, double(p.position_m.y()) + reach);
    bottom = std::min(bottom, double(p.position_m.y()) - reach);
  }
  EXPECT_NEAR(mass, M, 1e-3);
  EXPECT_NEAR(top, H, 1e-4);  // top of the head at the body height
  EXPECT_GE(bottom, 0);
  EXPECT_LT(bottom, 0.01 * H);
  // Every joint is filtered, nothing else.
  ASSERT_EQ(d.noCollide.size(), d.joints.size());
  for (std::size_t k = 0; k < d.joints.size(); ++k) {
    EXPECT_EQ(d.noCollide[k].first, d.joints[k].partA);
    EXPECT_EQ(d.noCollide[k].second, d.joints[k].partB);
  }
}

TEST(Ragdoll, BadDescriptionsNameTheField) {
  RagdollDesc d = defaultHuman();
  d.parts[3].mass_kg = -1;
  auto s = validateRagdoll(d);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("upper_arm_l"), std::string::npos) << s.error();
  EXPECT_NE(s.error().find("mass"), std::string::npos) << s.error();
  d = defaultHuman();
  d.joints[0].partB = 42;
  s = validateRagdoll(d);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("waist"), std::string::npos) << s.error();
}

struct DropResult {
  double errorMax_m, errorEnd_m, fastest_mps;
  double asleepAt_s;  ///< first time every part was asleep (-1: never)
  bool asleepAtEnd;
};

/// The default human dropped face-first on the ground, 5 s at 60 Hz.
DropResult dropRagdoll(const JointSettings& settings, const char* label) {
  World world;
  JointSystem joints(world, settings);
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  (void)world.createBody(ground).value();
  // Tilted forward a little so it falls over rather than standing.
  const Quat tilt(Eigen::AngleAxis<Real>(Real(0.3), Vec3::UnitX()));
  Ragdoll r = buildRagdoll(world, joints, defaultHuman(), Vec3(0, Real(0.3), 0), tilt).value();
  EXPECT_EQ(r.bodies.size(), 11u);
  EXPECT_EQ(r.joints.size(), 10u);
  EXPECT_EQ(r.noCollide.size(), 10u);
  EXPECT_EQ(joints.connectedPairs().size(), 10u);
  auto allAsleep = [&] {
    for (BodyId b : r.bodies)
      if (world.body(b).awake) return false;
    return true;
  };
  double asleepAt = -1;
  for (int i = 0; i < 5 * 60; ++i) {
    joints.step(Real(1.0 / 60.0));
    if (asleepAt < 0 && allAsleep()) asleepAt = (i + 1) / 60.0;
  }
  DropResult out{joints.maxAnchorError_m(), joints.anchorError_m(), 0, asleepAt, allAsleep()};
  for (BodyId b : r.bodies) out.fastest_mps = std::max<double>(out.fastest_mps, world.body(b).linearVelocity_mps.norm());
  std::printf("[ragdoll drop] %s: anchor error max %.2e m, at 5 s %.2e m, fastest part %.4f m/s, asleep at %.2f s "
              "(%s at 5 s), solve %.3f ms (%d rows)\n",
              label, out.errorMax_m, out.errorEnd_m, out.fastest_mps, out.asleepAt_s,
              out.asleepAtEnd ? "asleep" : "awake", joints.lastSolve().solveMs, joints.lastSolve().rows);
  return out;
}

// Formulation A with the World's separate contact solver: the rag-doll
// stays in one piece; with the velocity-only projection it comes to rest.
// Not yet checked (needs World changes, see the report): asleep within 5 s
// (World::applyForce wakes the body every step) and joints within 1 cm on
// the ground (contact forces are not in Q: joints stretch by ~g / k_s).
TEST(Ragdoll, DroppedOnTheGroundStaysInOnePiece) {
  const DropResult d = dropRagdoll(JointSettings{}, "defaults (velocity + position projection)");
  EXPECT_LT(d.errorMax_m, 0.1);
  EXPECT_LT(d.errorEnd_m, 0.05);
}

TEST(Ragdoll, DroppedOnTheGroundComesToRestWithVelocityProjection) {
  JointSettings s;
  s.projectPositions = false;
  const DropResult d = dropRagdoll(s, "velocity projection only");
  EXPECT_LT(d.errorEnd_m, 0.05);
  EXPECT_LT(d.fastest_mps, 0.01);
  // Issue 4: asleep within 5 s of the drop.
  EXPECT_GE(d.asleepAt_s, 0) << "never fell asleep";
  EXPECT_LE(d.asleepAt_s, 5);
}

// Formulation A with many contacts between jointed bodies of different
// dolls: 10 rag-dolls dropped crosswise in a pile (as base:ragdoll_pile
// --set count=10) for 8 s. The joints stay together and nothing becomes
// non-finite (an earlier variant of A that re-projected the joints between
// the contact sweeps blew up here at 0.9 s; the version before the substep
// solve opened them by 27 cm).
TEST(Ragdoll, TenPiledUnderFormulationAStayTogether) {
  World world;
  JointSettings s;
  s.projectPositions = false;  // as the scenario host
  JointSystem joints(world, s);
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  (void)world.createBody(ground).value();
  for (int i = 1; i <= 10; ++i) {
    const Vec3 axis = i % 2 == 0 ? Vec3::UnitZ() : Vec3::UnitX();  // crossed alternately
    ASSERT_TRUE(buildRagdoll(world, joints, defaultHuman(Real(1.8), 75), Vec3(0, Real(0.3 + 0.5 * (i - 1)), Real(-0.9)),
                             Quat(Eigen::AngleAxis<Real>(kPi / 2, axis)))
                    .ok());
  }
  for (int i = 0; i < 8 * 60; ++i) joints.step(Real(1.0 / 60.0));
  std::printf("[pile of 10, A] anchor error max %.3f m, nan events %d\n", joints.maxAnchorError_m(),
              world.errorStats().nanEvents);
  EXPECT_EQ(world.errorStats().nanEvents, 0);
  EXPECT_LT(joints.maxAnchorError_m(), 0.25);
}

TEST(CollisionFilter, DisabledPairsPassThroughEachOtherAndOthersStillCollide) {
  World w;
  w.settings().gravity_mps2 = Vec3::Zero();
  auto box = [&](const Vec3& p, const Vec3& v) {
    BodyDef d;
    d.shape = Shape::box(Vec3::Constant(Real(0.5)));
    d.position_m = p;
    d.linearVelocity_mps = v;
    d.mass_kg = 1;
    return w.createBody(d).value();
  };
  // Two boxes flying at each other with the pair disabled pass through...
  BodyId a = box(Vec3(-2, 0, 0), Vec3(2, 0, 0));
  BodyId b = box(Vec3(2, 0, 0), Vec3(-2, 0, 0));
  w.disableCollision(a, b);
  EXPECT_TRUE(w.collisionDisabled(b, a)) << "order does not matter";
  // ...while a third box, not filtered, is hit by the first one at x = 3
  // (unhindered, a would reach x = 4 in 3 s).
  BodyId c = box(Vec3(4, 0, 0), Vec3::Zero());
  for (int i = 0; i < 180; ++i) w.step(Real(1.0 / 60));
  EXPECT_GT(w.body(a).position_m.x(), 1.5) << "a passed through b";
  EXPECT_LT(w.body(b).position_m.x(), -1.5) << "b passed through a";
  EXPECT_LT(w.body(a).position_m.x(), w.body(c).position_m.x() - Real(0.9)) << "a did not pass through c";
  EXPECT_GT(w.body(c).linearVelocity_mps.x(), Real(0.5)) << "c was hit and moves";
  // Enabling the pair again makes them collide.
  w.enableCollision(a, b);
  EXPECT_FALSE(w.collisionDisabled(a, b));
  // A destroyed body's filter entries go with it: a new body in the same
  // slot collides normally.
  w.disableCollision(a, c);
  w.destroyBody(c);
  BodyId d = box(Vec3(20, 0, 0), Vec3::Zero());
  EXPECT_FALSE(w.collisionDisabled(a, d));
}

}  // namespace
}  // namespace tumble::physics
