// World::saveState / restoreState with bodies whose shape data is stored
// whole (convex hulls, compounds and static triangle meshes): a body a
// script made after the world
// was set up comes back in a world that never had it, and the run goes on
// bit for bit; damaged shape bytes are refused or give a state the next
// step runs from, never a crash or a read outside an array (the sanitizer
// build checks the last).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/mesh_shape.h"
#include "physics/world.h"

namespace tumble::physics {
namespace {

BodyId addBody(World& w, const Shape& s, const Vec3& p, const Vec3& spin = Vec3::Zero()) {
  BodyDef d;
  d.shape = s;
  d.position_m = p;
  d.angularVelocity_radps = spin;
  d.mass_kg = 2;
  d.allowSleep = false;
  return w.createBody(d).value();
}

/// The world as its set-up made it: a ground plane and a box.
std::vector<BodyId> setUp(World& w) {
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  (void)w.createBody(ground).value();
  return {addBody(w, Shape::box(Vec3(Real(0.5), Real(0.5), Real(0.5))), Vec3(0, Real(0.5), 0))};
}

/// What was made later: a static slope (a triangle mesh of two triangles,
/// as a model placed by a script), a wedge (hull) falling onto it and a
/// hammer (a box and a hull pyramid).
std::vector<BodyId> makeLater(World& w) {
  MeshTreeInput slope;
  slope.nodes.push_back({-1,
                         {{1, Real(0.3), -1}, {3, Real(0.9), -1}, {3, Real(0.9), 2}, {1, Real(0.3), 2}},
                         {{0, 2, 1}, {0, 3, 2}},
                         "slope"});
  BodyDef ramp;
  ramp.type = BodyType::Static;
  ramp.shape = makeMeshShape(slope).value();
  const BodyId slopeBody = w.createBody(ramp).value();
  const std::vector<Vec3> wedge = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 0}, {0, 1, 1}};
  const BodyId wedgeBody = addBody(w, makeHullShape(wedge).value(), Vec3(2, 2, 0), Vec3(1, 2, 3));
  const std::vector<Vec3> pyramid = {{Real(-0.3), 0, Real(-0.2)}, {Real(0.3), 0, Real(-0.2)},
                                     {Real(-0.3), 0, Real(0.2)},  {Real(0.3), 0, Real(0.2)}, {0, Real(0.4), 0}};
  CompoundChild handle{Shape::box(Vec3(Real(0.1), Real(0.6), Real(0.1))), Vec3::Zero(), Quat::Identity()};
  CompoundChild head{makeHullShape(pyramid).value(), Vec3(0, Real(0.6), 0), Quat::Identity()};
  return {wedgeBody, addBody(w, makeCompoundShape({handle, head}).value(), Vec3(Real(-1.5), 3, Real(0.5)), Vec3(0, 2, 5)),
          slopeBody};
}

std::string poses(const World& w, const std::vector<BodyId>& ids) {
  std::string s;
  for (BodyId id : ids) {
    const Body& b = w.body(id);
    s.append(reinterpret_cast<const char*>(&b.position_m), sizeof b.position_m);
    s.append(reinterpret_cast<const char*>(&b.orientation), sizeof b.orientation);
  }
  return s;
}

TEST(WorldState, HullsCompoundsAndMeshesMadeLaterComeBackInAWorldThatNeverHadThem) {
  World a;
  std::vector<BodyId> ids = setUp(a);
  const std::vector<BodyId> later = makeLater(a);
  ids.insert(ids.end(), later.begin(), later.end());
  for (int i = 0; i < 40; ++i) a.step(Real(1.0 / 60));  // falling, spinning, the wedge landing
  const std::string bytes = a.saveState();
  World b;
  setUp(b);  // as a loaded run's set-up makes it: no wedge, no hammer
  ASSERT_EQ(b.bodyCount(), 2);
  const Status st = b.restoreState(bytes);
  ASSERT_TRUE(st) << st.error();
  ASSERT_EQ(b.bodyCount(), 5);
  ASSERT_TRUE(b.isValid(later[0]) && b.isValid(later[1]) && b.isValid(later[2]));
  EXPECT_EQ(b.body(later[0]).shape.type, ShapeType::Hull);
  EXPECT_EQ(b.body(later[1]).shape.type, ShapeType::Compound);
  ASSERT_EQ(b.body(later[2]).shape.type, ShapeType::Mesh);
  EXPECT_EQ(b.body(later[2]).shape.mesh->triangles.size(), 2u);
  EXPECT_EQ(poses(b, ids), poses(a, ids));
  for (int i = 0; i < 80; ++i) {
    a.step(Real(1.0 / 60));
    b.step(Real(1.0 / 60));
  }
  EXPECT_EQ(poses(b, ids), poses(a, ids)) << "the run from the restored world ends elsewhere";
  EXPECT_LT(a.body(later[1]).position_m.y(), Real(1)) << "the hammer fell";
  EXPECT_GT(a.body(later[0]).position_m.x(), Real(1.2)) << "the wedge rests on the slope, not beside it";
  EXPECT_GT(a.body(later[0]).position_m.y(), Real(0.3)) << "the wedge rests on the slope, not on the ground";
  EXPECT_TRUE(a.body(later[1]).position_m.allFinite());
}

// Every cut is refused; single changed bytes anywhere (most of the state is
// the hull, compound and mesh data) are refused or restored and stepped.
TEST(WorldState, DamagedShapeBytesAreRefusedOrRunNeverCrash) {
  World a;
  setUp(a);
  makeLater(a);
  for (int i = 0; i < 40; ++i) a.step(Real(1.0 / 60));
  const std::string bytes = a.saveState();
  std::mt19937 rng(11);
  int refused = 0, accepted = 0;
  auto attempt = [&](const std::string& damaged) {
    World b;
    setUp(b);
    if (b.restoreState(damaged)) {
      ++accepted;
      for (int i = 0; i < 3; ++i) b.step(Real(1.0 / 60));
    } else {
      ++refused;
    }
  };
  for (int k = 0; k < 64; ++k) attempt(bytes.substr(0, bytes.size() * std::size_t(k) / 64));
  EXPECT_EQ(refused, 64);
  for (int k = 0; k < 3000; ++k) {
    std::string damaged = bytes;
    const std::size_t at = std::uniform_int_distribution<std::size_t>(0, damaged.size() - 1)(rng);
    damaged[at] = char(std::uniform_int_distribution<int>(0, 255)(rng));
    attempt(damaged);
  }
  std::printf("[world state] %zu bytes: %d refused, %d accepted and stepped\n", bytes.size(), refused - 64,
              accepted);
  EXPECT_GT(refused - 64, 0);
}

}  // namespace
}  // namespace tumble::physics
