// Static triangle meshes (ShapeType::Mesh): contacts, seams, one-sided
// faces, rays and the object tree's early-outs, each against an analytic
// answer or the same scene on a plane.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/mesh_shape.h"
#include "physics_fixture.h"

namespace tumble::physics::test {
namespace {

constexpr Real kDt = Real(1.0 / 60);

/// A closed box [lo, hi] added to a node, faces wound outwards.
void addBox(MeshTreeNodeInput& node, const Vec3& lo, const Vec3& hi) {
  std::array<Vec3, 8> corners;
  for (int i = 0; i < 8; ++i)
    corners[i] = Vec3((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  const ConvexHull hull = computeConvexHull(corners).value();
  const std::uint32_t base = std::uint32_t(node.vertices_m.size());
  node.vertices_m.insert(node.vertices_m.end(), hull.vertices_m.begin(), hull.vertices_m.end());
  for (const auto& t : hull.triangles) node.triangles.push_back({base + t[0], base + t[1], base + t[2]});
}

/// A flat floor at height y of nx * nz square cells (two triangles each, facing +Y).
void addFloor(MeshTreeNodeInput& node, Real x0, Real z0, int nx, int nz, Real cell, Real y) {
  const std::uint32_t base = std::uint32_t(node.vertices_m.size());
  for (int j = 0; j <= nz; ++j)
    for (int i = 0; i <= nx; ++i) node.vertices_m.emplace_back(x0 + i * cell, y, z0 + j * cell);
  auto at = [&](int i, int j) { return base + std::uint32_t(j * (nx + 1) + i); };
  for (int j = 0; j < nz; ++j)
    for (int i = 0; i < nx; ++i) {
      node.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j)});
      node.triangles.push_back({at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)});
    }
}

BodyId addMesh(World& w, const MeshTreeInput& tree, const Vec3& p = Vec3::Zero(), const Quat& q = Quat::Identity(),
               const Vec3& scale = Vec3::Ones(), Real friction = Real(0.6)) {
  BodyDef d;
  d.type = BodyType::Static;
  d.shape = makeMeshShape(tree, scale).value();
  d.position_m = p;
  d.orientation = q;
  d.friction = friction;
  return w.createBody(d).value();
}

MeshTreeInput floorTree(int cells, Real cell) {
  MeshTreeInput tree;
  tree.nodes.resize(1);
  addFloor(tree.nodes[0], -cells * cell / 2, -cells * cell / 2, cells, cells, cell, 0);
  return tree;
}

/// A tree model: the root holds nothing, a trunk (0.4 m square, 3 m tall)
/// and a canopy (3 m wide, from 2.5 m to 4.5 m) are its children.
MeshTreeInput treeModel() {
  MeshTreeInput tree;
  tree.nodes.resize(3);
  tree.nodes[0].name = "tree";
  tree.nodes[1].parent = 0;
  tree.nodes[1].name = "trunk";
  addBox(tree.nodes[1], Vec3(Real(-0.2), 0, Real(-0.2)), Vec3(Real(0.2), 3, Real(0.2)));
  tree.nodes[2].parent = 0;
  tree.nodes[2].name = "canopy";
  addBox(tree.nodes[2], Vec3(Real(-1.5), Real(2.5), Real(-1.5)), Vec3(Real(1.5), Real(4.5), Real(1.5)));
  return tree;
}

TEST(MeshShape, SphereDroppedOnAMeshFloorRestsAtItsRadius) {
  World w;
  addMesh(w, floorTree(20, Real(0.5)));
  const Real r = Real(0.3);
  BodyId ball = addBody(w, Shape::sphere(r), Vec3(Real(0.13), 1, Real(0.27)));
  simulate(w, 2);
  const Body& b = w.body(ball);
  EXPECT_NEAR(b.position_m.y(), r, Real(0.005));  // within the solver's slop
  EXPECT_LT(b.linearVelocity_mps.norm(), Real(0.01));
  EXPECT_NEAR(b.position_m.x(), Real(0.13), Real(1e-3));
}

// A box sliding across a floor of 0.25 m triangles with friction mu must
// move exactly as the same box on a plane: no seam bumps (|v_y| ~ 0), the
// same height and the stopping distance v0^2 / (2 mu g) both give.
TEST(MeshShape, BoxSlidesAcrossSeamsAsOnAPlane) {
  const Real mu = Real(0.5), v0 = 5;
  const Vec3 dir = Vec3(1, 0, Real(0.37)).normalized();  // crosses the cells' diagonals too
  World onMesh, onPlane;
  addMesh(onMesh, floorTree(80, Real(0.25)), Vec3::Zero(), Quat::Identity(), Vec3::Ones(), mu);
  addGround(onPlane, mu);
  const Shape box = Shape::box(Vec3(Real(0.4), Real(0.25), Real(0.4)));
  BodyId a = addBody(onMesh, box, Vec3(-5, Real(0.25), -3), 1, mu);
  BodyId b = addBody(onPlane, box, Vec3(-5, Real(0.25), -3), 1, mu);
  onMesh.setLinearVelocity(a, dir * v0);
  onPlane.setLinearVelocity(b, dir * v0);
  Real maxVy = 0, maxDy = 0, maxDv = 0;
  for (int i = 0; i < 180; ++i) {
    onMesh.step(kDt);
    onPlane.step(kDt);
    const Body& m = onMesh.body(a);
    const Body& p = onPlane.body(b);
    maxVy = std::max(maxVy, std::abs(m.linearVelocity_mps.y()));
    maxDy = std::max(maxDy, std::abs(m.position_m.y() - p.position_m.y()));
    maxDv = std::max(maxDv, (m.linearVelocity_mps - p.linearVelocity_mps).norm());
  }
  const Real dist = (onMesh.body(a).position_m - Vec3(-5, Real(0.25), -3)).dot(dir);
  const Real expected = v0 * v0 / (2 * mu * kStandardGravity);
  std::printf("mesh slide: %.4f m (plane %.4f, analytic %.4f), max |v_y| %.2e, max height gap %.2e, max dv %.2e\n",
              dist, (onPlane.body(b).position_m - Vec3(-5, Real(0.25), -3)).dot(dir), expected, maxVy, maxDy, maxDv);
  EXPECT_NEAR(dist, expected, Real(0.03) * expected);
  EXPECT_LT(maxVy, Real(1e-2));
  EXPECT_LT(maxDy, Real(2e-3));
  EXPECT_LT(maxDv, Real(0.05));
  // Stopped on the seams, it keeps its corner contacts (stable ids) and sleeps as on the plane.
  EXPECT_EQ(onMesh.body(a).awake, onPlane.body(b).awake);
  EXPECT_FALSE(onMesh.body(a).awake);
}

// A ball rolling across the seams with rolling resistance C_rr slows at
// (5/7) C_rr g, smoothly: its speed never rises.
TEST(MeshShape, SphereRollsAcrossSeamsWithoutBumping) {
  World w;
  addMesh(w, floorTree(60, Real(0.3)));
  const Real crr = Real(0.05), r = Real(0.3), v0 = 3;
  const Vec3 dir = Vec3(1, 0, Real(0.61)).normalized();
  BodyDef d;
  d.shape = Shape::sphere(r);
  d.position_m = Vec3(-6, r, -4);
  d.rollingResistance = crr;
  d.linearVelocity_mps = dir * v0;
  d.angularVelocity_radps = Vec3::UnitY().cross(dir) * (v0 / r);
  BodyId ball = w.createBody(d).value();
  Real maxVy = 0, prevSpeed = v0, maxRise = 0;
  const Real T = 2;
  for (int i = 0; i < int(T * 60); ++i) {
    w.step(kDt);
    const Vec3 v = w.body(ball).linearVelocity_mps;
    maxVy = std::max(maxVy, std::abs(v.y()));
    maxRise = std::max(maxRise, v.norm() - prevSpeed);
    prevSpeed = v.norm();
  }
  const Real decel = (v0 - prevSpeed) / T, expected = Real(5.0 / 7.0) * crr * kStandardGravity;
  EXPECT_NEAR(decel, expected, Real(0.05) * expected);
  EXPECT_LT(maxVy, Real(1e-2));
  EXPECT_LT(maxRise, Real(1e-4));
}

// The tree's covering box spans the canopy; a ball rolling under the canopy
// beside the trunk passes (the old single box around the model stopped it),
// one rolling at the trunk stops there, 0.2 + r from its axis.
TEST(MeshShape, BallUnderTheCanopyPassesAndOneAtTheTrunkStops) {
  World w;
  addGround(w, 0);
  addMesh(w, treeModel(), Vec3(0, 0, 5));
  const Real r = Real(0.3);
  BodyId past = addBody(w, Shape::sphere(r), Vec3(1, r, 0), 1, 0);
  BodyId hit = addBody(w, Shape::sphere(r), Vec3(0, r, 0), 1, 0);
  w.setLinearVelocity(past, Vec3(0, 0, 4));
  w.setLinearVelocity(hit, Vec3(0, 0, 4));
  simulate(w, 3);
  EXPECT_GT(w.body(past).position_m.z(), 10);  // rolled on under the canopy (4 m/s for 3 s from z = 0)
  EXPECT_LT(w.body(hit).position_m.z(), 5 - Real(0.2) - r + Real(0.01));
  EXPECT_GT(w.body(hit).position_m.z(), 5 - Real(0.2) - r - Real(0.02));
}

// 0.1 m sphere at 80 m/s (1.3 m per step) at a 0.1 m thick mesh wall: it
// must end on the near side.
TEST(MeshShape, FastSphereDoesNotTunnelThroughAMeshWall) {
  for (Real speed : {Real(20), Real(80), Real(200)}) {
    World w;
    w.settings().gravity_mps2 = Vec3::Zero();
    MeshTreeInput tree;
    tree.nodes.resize(1);
    addBox(tree.nodes[0], Vec3(-2, -2, Real(-0.05)), Vec3(2, 2, Real(0.05)));
    addMesh(w, tree, Vec3(0, 0, 10));
    BodyId ball = addBody(w, Shape::sphere(Real(0.1)), Vec3(Real(0.3), Real(0.2), 0));
    w.setLinearVelocity(ball, Vec3(0, 0, speed));
    simulate(w, 1);
    EXPECT_LT(w.body(ball).position_m.z(), 10 - Real(0.05)) << "speed " << speed;
  }
  // A tumbling 0.2 m box at 80 m/s likewise.
  World w;
  w.settings().gravity_mps2 = Vec3::Zero();
  MeshTreeInput tree;
  tree.nodes.resize(1);
  addBox(tree.nodes[0], Vec3(-2, -2, Real(-0.05)), Vec3(2, 2, Real(0.05)));
  addMesh(w, tree, Vec3(0, 0, 10));
  BodyId box = addBody(w, Shape::box(Vec3::Constant(Real(0.1))), Vec3(Real(-0.4), Real(0.3), 0));
  w.setLinearVelocity(box, Vec3(0, 0, 80));
  w.setAngularVelocity(box, Vec3(3, 7, 1));
  simulate(w, 1);
  EXPECT_LT(w.body(box).position_m.z(), 10 - Real(0.05));
}

// A single triangle, scaled by (2, 1, 3), rotated and placed: a ray hits it
// where the plane through the three transformed vertices says, with that
// plane's normal; a ray from behind passes (one-sided).
TEST(MeshShape, RayHitsARotatedScaledMeshWhereTheTriangleIs) {
  World w;
  MeshTreeInput tree;
  tree.nodes.resize(1);
  tree.nodes[0].vertices_m = {Vec3(-1, 0, -1), Vec3(0, 0, 1), Vec3(1, 0, -1)};
  tree.nodes[0].triangles = {{0, 1, 2}};
  const Vec3 scale(2, 1, 3), p(1, 2, 3);
  const Quat q(Eigen::AngleAxis<Real>(Real(0.4), Vec3(1, 0, Real(0.5)).normalized()));
  BodyId body = addMesh(w, tree, p, q, scale);
  Vec3 v[3];
  for (int i = 0; i < 3; ++i) v[i] = p + q * tree.nodes[0].vertices_m[i].cwiseProduct(scale);
  const Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
  const Vec3 target = (v[0] + v[1] + v[2]) / 3 + (v[1] - v[0]) * Real(0.1);
  const Vec3 origin = target + n * 4 + Vec3(Real(0.3), 0, Real(-0.2));
  const Vec3 dir = (target - origin).normalized();
  RayHit hit;
  ASSERT_TRUE(w.rayCast(origin, dir, 10, &hit));
  EXPECT_EQ(hit.body, body);
  EXPECT_NEAR(hit.distance_m, (target - origin).norm(), Real(1e-4));
  EXPECT_LT((hit.point_m - target).norm(), Real(1e-4));
  EXPECT_GT(hit.normal.dot(n), Real(0.9999));
  EXPECT_TRUE(w.rayCastBody(body, origin, dir, 10, &hit));
  EXPECT_FALSE(w.rayCast(target - n * 4, n, 10, &hit)) << "back faces do not stop rays";
  EXPECT_FALSE(w.rayCast(origin, -dir, 10, &hit));
}

// Ten models of 5 parts each (12 triangles per part, 2 m apart); a ball
// resting on one part of one model: the broad phase pairs it with that
// model only, and there the tree reads that part's triangles only, while
// the brute force reads all 60 of the model.
TEST(MeshShape, TheTreeTestsOnlyTheReachedNodesTriangles) {
  MeshTreeInput tree;
  tree.nodes.resize(6);
  for (int k = 1; k <= 5; ++k) {
    tree.nodes[k].parent = 0;
    addBox(tree.nodes[k], Vec3(Real(2 * k), 0, 0), Vec3(Real(2 * k + 1), 1, 1));
  }
  for (bool useTree : {true, false}) {
    World w;
    w.settings().meshTree = useTree;
    for (int m = 0; m < 10; ++m) addMesh(w, tree, Vec3(0, 0, Real(5 * m)));
    addBody(w, Shape::sphere(Real(0.3)), Vec3(Real(6.5), Real(1.3), Real(10.5)));  // on part 3 of model 2
    w.step(kDt);
    const MeshStats& s = w.meshStats();
    EXPECT_EQ(s.pairs, 1u);
    if (useTree) {
      EXPECT_EQ(s.nodesVisited, 6u);
      EXPECT_EQ(s.subtreesSkipped, 4u);
      EXPECT_EQ(s.trianglesTested, 12u);
    } else {
      EXPECT_EQ(s.trianglesTested, 60u);
    }
    EXPECT_GE(s.exactTests, 1u);
  }
}

TEST(MeshShape, RefusesBadInputWithAClearMessage) {
  MeshTreeInput tree;
  EXPECT_FALSE(makeMeshShape(tree).ok());
  tree.nodes.resize(2);
  tree.nodes[1].parent = 0;
  tree.nodes[1].name = "roof";
  EXPECT_NE(makeMeshShape(tree).error().find("no triangles"), std::string::npos);
  tree.nodes[1].vertices_m = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, std::nan(""), 1)};
  tree.nodes[1].triangles = {{0, 1, 2}};
  const std::string e = makeMeshShape(tree).error();
  EXPECT_NE(e.find("'roof'"), std::string::npos) << e;
  EXPECT_NE(e.find("vertex 3"), std::string::npos) << e;
  tree.nodes[1].vertices_m[2] = Vec3(0, 0, 1);
  tree.nodes[1].triangles = {{0, 1, 7}};
  EXPECT_NE(makeMeshShape(tree).error().find("does not exist"), std::string::npos);
  tree.nodes[1].triangles = {{0, 2, 1}};
  Shape s = makeMeshShape(tree).value();
  World w;
  BodyDef d;
  d.shape = s;
  auto body = w.createBody(d);  // dynamic by default
  ASSERT_FALSE(body.ok());
  EXPECT_NE(body.error().find("static"), std::string::npos) << body.error();
  d.type = BodyType::Kinematic;
  EXPECT_FALSE(w.createBody(d).ok());
  d.type = BodyType::Static;
  EXPECT_TRUE(w.createBody(d).ok());
}

// A box resting on a rock-like mesh box (its top edges are real creases)
// settles flat on the top face and sleeps.
TEST(MeshShape, BoxRestsOnAMeshBlock) {
  World w;
  MeshTreeInput tree;
  tree.nodes.resize(1);
  addBox(tree.nodes[0], Vec3(-1, 0, -1), Vec3(1, 1, 1));
  addMesh(w, tree);
  BodyId box = addBody(w, Shape::box(Vec3(Real(0.3), Real(0.2), Real(0.3))), Vec3(Real(0.5), Real(1.5), 0));
  simulate(w, 2);
  EXPECT_NEAR(w.body(box).position_m.y(), Real(1.2), Real(0.006));
  EXPECT_FALSE(w.body(box).awake);
}

// Every kind of moving shape rests on a mesh block's top face at the height
// its own geometry says: capsule lying down (radius), hull (its lowest
// vertex) and compound (its lowest child).
TEST(MeshShape, CapsuleHullAndCompoundRestOnAMeshBlock) {
  World w;
  MeshTreeInput tree;
  tree.nodes.resize(1);
  addBox(tree.nodes[0], Vec3(-4, 0, -4), Vec3(4, 1, 4));
  addMesh(w, tree);
  BodyDef cap;
  cap.shape = Shape::capsule(Real(0.2), Real(0.4));
  cap.position_m = Vec3(-2, Real(1.6), 0);
  cap.orientation = Quat(Eigen::AngleAxis<Real>(Real(kPi / 2), Vec3::UnitZ()));  // lying along x
  BodyId capsule = w.createBody(cap).value();
  std::vector<Vec3> prism;  // a six-sided prism 0.5 m tall
  for (int i = 0; i < 6; ++i)
    for (Real y : {Real(-0.25), Real(0.25)})
      prism.emplace_back(Real(0.3) * std::cos(i * kPi / 3), y, Real(0.3) * std::sin(i * kPi / 3));
  BodyId hull = addBody(w, makeHullShape(prism).value(), Vec3(0, Real(1.8), 0));
  CompoundChild left{Shape::box(Vec3(Real(0.1), Real(0.3), Real(0.1))), Vec3(Real(-0.3), 0, 0)};
  CompoundChild right{Shape::box(Vec3(Real(0.1), Real(0.3), Real(0.1))), Vec3(Real(0.3), 0, 0)};
  BodyId compound = addBody(w, makeCompoundShape({left, right}).value(), Vec3(2, Real(1.8), 0));
  simulate(w, 3);
  EXPECT_NEAR(w.body(capsule).position_m.y(), Real(1.2), Real(0.006));
  EXPECT_NEAR(w.body(hull).position_m.y(), Real(1.25), Real(0.006));
  EXPECT_NEAR(w.body(compound).position_m.y(), Real(1.3), Real(0.006));
  for (BodyId id : {capsule, hull, compound}) EXPECT_FALSE(w.body(id).awake);
}

// A box on a floor of 5 cm triangles (its bottom covers ~250 of them) gets
// a bounded contact set: one normal, at most four points.
TEST(MeshShape, ManyTrianglesUnderABoxGiveOneFourPointManifold) {
  World w;
  addMesh(w, floorTree(80, Real(0.05)));
  BodyDef d;
  d.shape = Shape::box(Vec3(Real(0.4), Real(0.2), Real(0.4)));
  d.position_m = Vec3(Real(0.01), Real(0.25), Real(0.02));
  d.allowSleep = false;  // a sleeping body has no contacts to count
  BodyId box = w.createBody(d).value();
  simulate(w, 1);
  EXPECT_LE(w.contactPointCount(), 4);
  EXPECT_GE(w.contactPointCount(), 3);
  EXPECT_NEAR(w.body(box).position_m.y(), Real(0.2), Real(0.006));
}

// Queries see the mesh: an overlap touching the block's top finds it, one
// above does not, and a sphere cast down stops where it touches the top.
TEST(MeshShape, OverlapAndShapeCastFindTheMesh) {
  World w;
  MeshTreeInput tree;
  tree.nodes.resize(1);
  addBox(tree.nodes[0], Vec3(-1, 0, -1), Vec3(1, 1, 1));
  BodyId block = addMesh(w, tree);
  const Shape ball = Shape::sphere(Real(0.3));
  auto found = w.overlapShape(ball, Vec3(Real(0.2), Real(1.25), 0), Quat::Identity());
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0], block);
  EXPECT_TRUE(w.overlapShape(ball, Vec3(Real(0.2), Real(1.4), 0), Quat::Identity()).empty());
  ShapeCastHit hit;
  ASSERT_TRUE(w.shapeCast(ball, Vec3(Real(0.2), 3, Real(0.1)), Quat::Identity(), Vec3(0, -1, 0), 5, &hit));
  EXPECT_EQ(hit.body, block);
  EXPECT_NEAR(hit.distance_m, 3 - 1 - Real(0.3), World::kQueryTolerance_m + Real(1e-3));
  EXPECT_LE(hit.distance_m, 3 - 1 - Real(0.3) + Real(1e-4));  // conservative: never later than the touch
}

}  // namespace
}  // namespace tumble::physics::test
