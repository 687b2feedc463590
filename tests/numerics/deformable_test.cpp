// Mass-spring deformables (physics/deformable.h): a hanging rope's stretch
// against static equilibrium, k/m = 1e6 stable at dt = 1/60, energy that
// never grows without wind, cloth that stays above the ground and on a box,
// wind that pushes a flag downwind, pins carried by a body, and refused
// definitions.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "physics/convex_hull.h"
#include "physics/deformable.h"
#include "physics/mesh_shape.h"
#include "physics/world.h"

namespace tumble::physics {
namespace {

constexpr Real kDt = Real(1.0 / 60.0);
constexpr double kG = 9.81;

// Rope of N segments and N + 1 particles of mass m, pinned at the top. The
// spring j below particle j carries the N - j particles under it, so it
// stretches (N - j) m g / k; in total m g / k * N (N + 1) / 2.
TEST(Deformable, HangingRopeStretchMatchesStaticEquilibrium) {
  RopeDef def;
  def.segments = 20;
  def.mass_kg = 2.1;  // m = 0.1 kg per particle
  def.start_m = Vec3(0, 10, 0);
  def.end_m = Vec3(0, 6, 0);
  def.material.stiffness_Npm = 500;
  def.material.bendStiffness_Npm = 0;  // bend springs along a straight rope would share the load
  def.material.damping_Nspm = 20;  // settles the slow longitudinal mode within the 10 s
  auto rope = Deformable::rope(def);
  ASSERT_TRUE(rope) << rope.error();
  DeformableEnvironment env;
  for (int i = 0; i < 600; ++i) (*rope)->step(kDt, env);
  const double m = 0.1, N = 20;
  const double expected = m * kG / 500 * N * (N + 1) / 2;  // 0.412 m
  const double stretch = (*rope)->structuralLength() - (*rope)->structuralRestLength();
  EXPECT_NEAR(stretch, expected, 0.005 * expected);
  // Hanging straight down from the pin.
  EXPECT_NEAR((*rope)->position(20).x(), 0, 1e-6);
  EXPECT_NEAR((*rope)->position(20).y(), 6 - expected, 0.005 * expected);
}

// k/m = 1e6 with one substep of 1/60 s: omega h = 16.7, where every
// explicit method explodes. Backward Euler damps the stiff mode.
TEST(Deformable, StiffRopeIsStableAtSixtyHertz) {
  RopeDef def;
  def.segments = 10;
  def.mass_kg = 1.1;  // 0.1 kg per particle
  def.start_m = Vec3(0, 5, 0);
  def.end_m = Vec3(3, 5, 0);
  def.material.stiffness_Npm = 1e5;  // k / m = 1e6
  def.material.damping_Nspm = 0;
  def.material.airDrag_Nspm = 0;
  def.material.substeps = 1;
  auto rope = Deformable::rope(def);
  ASSERT_TRUE(rope);
  DeformableEnvironment env;
  const double e0 = (*rope)->energy(env.gravity_mps2);
  double eMax = e0;
  for (int i = 0; i < 300; ++i) {
    (*rope)->step(kDt, env);
    eMax = std::max(eMax, (*rope)->energy(env.gravity_mps2));
  }
  EXPECT_EQ((*rope)->stats().nanEvents, 0);
  EXPECT_EQ((*rope)->stats().cgFailures, 0);
  EXPECT_LE(eMax, e0 + 1e-9 * std::abs(e0));
  // Inextensible to within the static stretch (10 particles of 0.1 kg on 1e5 N/m).
  EXPECT_LT((*rope)->structuralLength() - (*rope)->structuralRestLength(), 1e-3);
  // It swung down: the free end is below the pin by about the rope's length.
  EXPECT_LT((*rope)->position(10).y(), 5 - 2.5);
}

TEST(Deformable, EnergyNeverGrowsWithoutWind) {
  ClothDef def;
  def.columns = 12;
  def.rows = 10;
  def.pins = ClothPins::TopCorners;
  def.origin_m = Vec3(0, 3, 0);
  def.edgeU_m = Vec3(2, 0, 0);
  def.edgeV_m = Vec3(0, 0, 1.5);  // horizontal: it falls and swings
  def.material.stiffness_Npm = 5000;
  auto cloth = Deformable::cloth(def);
  ASSERT_TRUE(cloth);
  DeformableEnvironment env;
  double previous = (*cloth)->energy(env.gravity_mps2);
  const double scale = std::abs(previous) + 1;
  double worstGain = 0;
  for (int i = 0; i < 240; ++i) {
    (*cloth)->step(kDt, env);
    const double e = (*cloth)->energy(env.gravity_mps2);
    worstGain = std::max(worstGain, (e - previous) / scale);
    previous = e;
  }
  EXPECT_LE(worstGain, 1e-9) << "backward Euler only removes energy";
  EXPECT_EQ((*cloth)->stats().nanEvents, 0);
}

// A 4 m x 1 m cloth dropped from 2 m over a floor plane and a 1 m table
// (x in [1.5, 2.5], y in [0, 1], z in [-0.5, 0.5]) whose shape the test
// gives: half of it lands on the floor, half on the table. Checks that no
// particle sinks into the floor or enters the table, and where it rests.
// Only four particles span the 1 m top, so a 1 % compression between the
// two caught at its edges arches the middle by up to sqrt(L^2 - (0.99 L)^2)
// ~ 4 cm (L = 0.27 m): a discretisation effect, bounded here.
void dropClothOnTable(const Shape& tableShape, const Vec3& tablePosition_m) {
  World world;
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  ASSERT_TRUE(world.createBody(ground));
  BodyDef table;
  table.type = BodyType::Static;
  table.shape = tableShape;
  table.position_m = tablePosition_m;
  ASSERT_TRUE(world.createBody(table));
  ClothDef def;
  def.columns = 16;
  def.rows = 8;
  def.pins = ClothPins::None;
  def.origin_m = Vec3(-1, 2, -0.5);
  def.edgeU_m = Vec3(4, 0, 0);  // half over the floor, half over the table
  def.edgeV_m = Vec3(0, 0, 1);
  def.material.stiffness_Npm = 2000;
  auto cloth = Deformable::cloth(def);
  ASSERT_TRUE(cloth);
  DeformableEnvironment env;
  env.world = &world;
  const double r = def.material.radius_m;
  double lowest = 1e9, insideTable = 0;
  for (int i = 0; i < 180; ++i) {
    (*cloth)->step(kDt, env);
    lowest = std::min(lowest, (*cloth)->lowestPoint());
    for (int p = 0; p < (*cloth)->particleCount(); ++p) {
      // Penetration of the particle's sphere into the table's 1 m cube.
      const Eigen::Vector3d x = ((*cloth)->position(p) - Vec3(2, Real(0.5), 0)).cast<double>();
      const Eigen::Vector3d outside = (x.cwiseAbs() - Eigen::Vector3d::Constant(0.5)).cwiseMax(0.0);
      const double gap = outside.norm() > 0 ? outside.norm() : -(0.5 - x.cwiseAbs().maxCoeff());
      insideTable = std::max(insideTable, r - gap);
    }
  }
  EXPECT_GT(lowest, -1e-3) << "no particle sinks into the ground";
  EXPECT_LT(insideTable, 1e-3) << "no particle inside the table";
  // At rest: the part over the floor lies on it (y = radius), the part
  // over the table is held up by its top (y >= 1 + radius).
  EXPECT_NEAR((*cloth)->position(4 * 16 + 0).y(), r, 2e-3);
  EXPECT_GT((*cloth)->position(4 * 16 + 12).y(), 1 + r - 1e-3);
  EXPECT_LT((*cloth)->position(4 * 16 + 12).y(), 1 + r + 0.06);
  EXPECT_LT((*cloth)->velocity(4 * 16 + 0).norm(), 0.01);
}

TEST(Deformable, ClothStaysAboveTheGroundAndOutOfABox) {
  dropClothOnTable(Shape::box(Vec3(Real(0.5), Real(0.5), Real(0.5))), Vec3(2, Real(0.5), 0));
}

// The same table as a static triangle mesh (a closed box model, origin at
// its foot): the particles rest on its top face and never enter it.
TEST(Deformable, ClothLiesOnAMeshTable) {
  std::array<Vec3, 8> corners;
  for (int i = 0; i < 8; ++i) corners[i] = Vec3((i & 1) ? 0.5f : -0.5f, (i & 2) ? 1.0f : 0.0f, (i & 4) ? 0.5f : -0.5f);
  const ConvexHull hull = computeConvexHull(corners).value();
  MeshTreeInput tree;
  tree.nodes.resize(1);
  tree.nodes[0].vertices_m = hull.vertices_m;
  for (const auto& t : hull.triangles) tree.nodes[0].triangles.push_back({t[0], t[1], t[2]});
  dropClothOnTable(makeMeshShape(tree).value(), Vec3(2, 0, 0));
}

// A smooth height field y = 0.5 sin x, enough for the particles (they ask
// only surfaceAt); the rest answers "nothing here".
class SineField final : public HeightField {
 public:
  static Real height(Real x) { return Real(0.5) * std::sin(x); }
  void visitTriangles(const Vec3&, const Vec3&, TriangleVisitor, void*) const override {}
  bool surfaceAt(Real x, Real, Real* h, Vec3* n) const override {
    *h = height(x);
    *n = Vec3(-Real(0.5) * std::cos(x), 1, 0).normalized();
    return true;
  }
  Real frictionAt(Real, Real) const override { return Real(0.6); }
  bool rayCast(const Vec3&, const Vec3&, Real, HeightFieldHit*) const override { return false; }
  void bounds(Vec3* lo, Vec3* hi) const override {
    *lo = Vec3(-100, Real(-0.5), -100);
    *hi = Vec3(100, Real(0.5), 100);
  }
};

TEST(Deformable, RopeRestsOnTerrainWithoutSinking) {
  SineField field;
  RopeDef def;
  def.start_m = Vec3(-3, 2, 0);
  def.end_m = Vec3(3, 2, 0);
  def.segments = 30;
  def.pinStart = false;
  auto rope = Deformable::rope(def);
  ASSERT_TRUE(rope);
  DeformableEnvironment env;
  env.heightField = &field;
  double worst = 0;  // deepest particle below the surface (m)
  for (int i = 0; i < 240; ++i) {
    (*rope)->step(kDt, env);
    for (int p = 0; p < (*rope)->particleCount(); ++p) {
      const Vec3 x = (*rope)->position(p);
      worst = std::max(worst, double(SineField::height(x.x()) - (x.y() - def.material.radius_m)));
    }
  }
  // Pushed out along the normal from the vertical gap: on a slope the
  // particle can sit up to r (1 - cos) lower, 0.1 mm on this 27 degree one.
  EXPECT_LT(worst, 1e-3);
  double speed = 0;
  for (int p = 0; p < (*rope)->particleCount(); ++p) speed = std::max(speed, double((*rope)->velocity(p).norm()));
  EXPECT_LT(speed, 0.05) << "at rest in the hollows after 4 s";
}

TEST(Deformable, WindPushesAFlagDownwind) {
  ClothDef def;
  def.columns = 10;
  def.rows = 8;
  def.origin_m = Vec3(0, 3, 0);
  def.edgeU_m = Vec3(0, -1, 0);  // pinned along the pole (the "top" row is vertical)
  def.edgeV_m = Vec3(1.5, 0, 0);
  def.pins = ClothPins::TopEdge;
  auto flag = Deformable::cloth(def);
  ASSERT_TRUE(flag);
  (*flag)->setWind(Vec3(0, 0, 8));
  DeformableEnvironment env;
  for (int i = 0; i < 180; ++i) (*flag)->step(kDt, env);
  double meanZ = 0;
  for (int i = 0; i < (*flag)->particleCount(); ++i) meanZ += (*flag)->position(i).z();
  meanZ /= (*flag)->particleCount();
  EXPECT_GT(meanZ, 0.2) << "blown downwind (+z)";
  EXPECT_EQ((*flag)->stats().nanEvents, 0);
}

TEST(Deformable, PinToABodyFollowsIt) {
  World world(WorldSettings{});
  BodyDef hook;
  hook.type = BodyType::Kinematic;
  hook.shape = Shape::sphere(Real(0.1));
  hook.position_m = Vec3(0, 5, 0);
  hook.linearVelocity_mps = Vec3(1, 0, 0);
  BodyId body = world.createBody(hook).value();
  RopeDef def;
  def.start_m = Vec3(0, 5, 0);
  def.end_m = Vec3(0, 3, 0);
  def.segments = 8;
  def.pinStart = false;
  auto rope = Deformable::rope(def);
  ASSERT_TRUE(rope);
  ASSERT_TRUE((*rope)->pinToBody(0, world, body));
  EXPECT_FALSE((*rope)->pinToBody(99, world, body));
  DeformableEnvironment env;
  env.world = &world;
  for (int i = 0; i < 60; ++i) {
    world.step(kDt);
    (*rope)->step(kDt, env);
  }
  EXPECT_NEAR((*rope)->position(0).x(), world.body(body).position_m.x(), 1e-5);
  EXPECT_NEAR((*rope)->position(0).x(), 1.0, 1e-3);
}

TEST(Deformable, BadDefinitionsNameTheField) {
  RopeDef rope;
  rope.material.stiffness_Npm = 0;
  auto r = Deformable::rope(rope);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find("stiffness"), std::string::npos) << r.error();
  ClothDef cloth;
  cloth.columns = 1;
  auto c = Deformable::cloth(cloth);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().find("columns"), std::string::npos) << c.error();
  cloth.columns = 4;
  cloth.edgeV_m = cloth.edgeU_m;
  EXPECT_FALSE(Deformable::cloth(cloth));
}

}  // namespace
}  // namespace tumble::physics
