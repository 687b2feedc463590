// Hulls and compounds in the world: resting, stacking, edges, the height
// field, rays and shape queries, compared with analytic answers.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "grid_field.h"
#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/internal/manifold.h"
#include "physics_fixture.h"

namespace tumble::physics::test {
namespace {

std::vector<Vec3> boxPoints(const Vec3& h) {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i) p.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  return p;
}

Shape hullBox(const Vec3& h) { return makeHullShape(boxPoints(h)).value(); }

/// Lowest point of a body's shape along world y (m).
Real lowestY(const Body& b) {
  Vec3 lo, hi;
  b.shape.bounds(b.position_m, b.orientation, &lo, &hi);
  return lo.y();
}

/// An eight-sided prism (a short "puck") of radius r and half height hh, axis y.
Shape puck(Real r, Real hh, int sides = 8) {
  std::vector<Vec3> p;
  for (int i = 0; i < sides; ++i) {
    const Real a = 2 * kPi * Real(i) / Real(sides);
    p.emplace_back(r * std::cos(a), -hh, r * std::sin(a));
    p.emplace_back(r * std::cos(a), hh, r * std::sin(a));
  }
  return makeHullShape(p).value();
}

// Contact reduction of a face's points to four: points a body so far out
// that its corners overflow give no distance that compares. The snapshot
// fuzzer reached this through collideHullPlane and read c[-1]; now the
// deepest point alone is kept, and finite points still give four.
TEST(ContactReduction, NonFinitePointsKeepTheDeepestAloneAndFinitePointsKeepFour) {
  const Real inf = std::numeric_limits<Real>::infinity();
  ContactCandidate c[6];
  for (int i = 0; i < 6; ++i) c[i] = {Vec3(inf, Real(i), -inf), Real(-0.01 * i), std::uint32_t(i)};
  ASSERT_EQ(reduceToFourCandidates(c, 6, Vec3::UnitY()), 1);
  EXPECT_EQ(c[0].id, 5u);  // the deepest
  ContactCandidate f[6];
  for (int i = 0; i < 6; ++i)
    f[i] = {Vec3(std::cos(Real(i)), 0, std::sin(Real(i))), Real(-0.001 * i), std::uint32_t(i)};
  EXPECT_EQ(reduceToFourCandidates(f, 6, Vec3::UnitY()), 4);
}

TEST(Hull, RestsOnThePlaneABoxAndAnotherHull) {
  World w;
  addGround(w);
  BodyDef base;
  base.type = BodyType::Static;
  base.shape = Shape::box(Vec3(2, Real(0.5), 2));
  base.position_m = Vec3(0, Real(0.5), 0);
  w.createBody(base).value();
  const Vec3 h(Real(0.4), Real(0.25), Real(0.3));
  const BodyId onPlane = addBody(w, hullBox(h), Vec3(5, 1, 0));
  const BodyId onBox = addBody(w, hullBox(h), Vec3(0, 2, 0));
  const BodyId onHull = addBody(w, puck(Real(0.3), Real(0.1)), Vec3(0, 3, 0));
  simulate(w, 4);
  for (BodyId id : {onPlane, onBox, onHull}) EXPECT_LT(w.body(id).linearVelocity_mps.norm(), Real(0.02));
  EXPECT_NEAR(lowestY(w.body(onPlane)), 0, 0.01);
  EXPECT_NEAR(lowestY(w.body(onBox)), 1, 0.01);
  EXPECT_NEAR(lowestY(w.body(onHull)), lowestY(w.body(onBox)) + 2 * h.y(), 0.01);
  EXPECT_LT(w.errorStats().penetrationMax_m, 0.02);
}

TEST(Hull, StackOfFiveHullBoxesStands) {
  World w;
  addGround(w);
  const Vec3 h = Vec3::Constant(Real(0.5));
  std::vector<BodyId> ids;
  for (int i = 0; i < 5; ++i) ids.push_back(addBody(w, hullBox(h), Vec3(0, Real(0.5) + Real(1.01) * i, 0)));
  simulate(w, 5);
  for (int i = 0; i < 5; ++i) {
    const Body& b = w.body(ids[i]);
    EXPECT_NEAR(b.position_m.y(), Real(0.5) + i, 0.02) << "box " << i;
    EXPECT_LT(std::hypot(b.position_m.x(), b.position_m.z()), 0.01) << "box " << i;
  }
}

TEST(Hull, SlidesDownAnInclineAtGTimesSinMinusMuCos) {
  // A hull block on a 30 degree ramp (static box) with mu = 0.2:
  // a = g (sin - mu cos), from rest: x = a t^2 / 2.
  World w;
  const Real theta = kPi / 6, mu = Real(0.2);
  const Quat tilt(Eigen::AngleAxis<Real>(theta, Vec3::UnitZ()));
  BodyDef ramp;
  ramp.type = BodyType::Static;
  ramp.shape = Shape::box(Vec3(20, Real(0.5), 2));
  ramp.orientation = tilt;
  ramp.friction = mu;
  w.createBody(ramp).value();
  const Vec3 h(Real(0.3), Real(0.2), Real(0.3));
  const Vec3 up = tilt * Vec3::UnitY();
  BodyDef d;
  d.shape = hullBox(h);
  d.mass_kg = 2;
  d.friction = mu;
  d.orientation = tilt;
  d.position_m = up * (Real(0.5) + h.y());
  const BodyId id = w.createBody(d).value();
  simulate(w, Real(0.5));  // settle onto the ramp
  const Vec3 x0 = w.body(id).position_m, v0 = w.body(id).linearVelocity_mps;
  const Real t = 1;
  simulate(w, t);
  const Vec3 downhill = tilt * Vec3(-1, 0, 0);
  const Real a = kStandardGravity * (std::sin(theta) - mu * std::cos(theta));
  const Real expected = v0.dot(downhill) * t + a * t * t / 2;
  EXPECT_NEAR((w.body(id).position_m - x0).dot(downhill), expected, 0.03 * expected + 0.01);
}

TEST(Hull, EdgeOnEdgeContactHasTheEdgeNormal) {
  // Two hull cubes turned 45 degrees about crossed axes touch edge to edge:
  // the upper one, dropped onto the lower (static) one, rests with its
  // centre sqrt(2) h above the contact edge: 2 sqrt(2) h above the lower centre.
  World w;
  const Real h = Real(0.5);
  BodyDef lower;
  lower.type = BodyType::Static;
  lower.shape = hullBox(Vec3::Constant(h));
  lower.orientation = Quat(Eigen::AngleAxis<Real>(kPi / 4, Vec3::UnitZ()));
  w.createBody(lower).value();
  BodyDef upper;
  upper.shape = hullBox(Vec3::Constant(h));
  upper.orientation = Quat(Eigen::AngleAxis<Real>(kPi / 4, Vec3::UnitX()));
  upper.position_m = Vec3(0, 2 * std::sqrt(Real(2)) * h + Real(0.05), 0);
  upper.mass_kg = 1;
  w.settings().gravity_mps2 = Vec3(0, -1, 0);  // slow, so it settles before it can slide off
  const BodyId id = w.createBody(upper).value();
  for (int i = 0; i < 30; ++i) w.step(Real(1.0 / 60.0));
  EXPECT_NEAR(w.body(id).position_m.y(), 2 * std::sqrt(Real(2)) * h, 0.01);
  EXPECT_GT(w.contactPointCount(), 0);
}

TEST(Hull, SphereAndCapsuleRestOnAHull) {
  World w;
  BodyDef base;
  base.type = BodyType::Static;
  base.shape = puck(2, Real(0.5), 12);
  w.createBody(base).value();
  const BodyId ball = addBody(w, Shape::sphere(Real(0.3)), Vec3(Real(0.5), 2, 0));
  BodyDef cap;
  cap.shape = Shape::capsule(Real(0.2), Real(0.5));
  cap.orientation = Quat(Eigen::AngleAxis<Real>(kPi / 2, Vec3::UnitZ()));
  cap.position_m = Vec3(-Real(0.5), 2, Real(0.8));
  cap.mass_kg = 1;
  const BodyId capsule = w.createBody(cap).value();
  simulate(w, 3);
  EXPECT_NEAR(w.body(ball).position_m.y(), Real(0.5) + Real(0.3), 0.01);
  EXPECT_NEAR(w.body(capsule).position_m.y(), Real(0.5) + Real(0.2), 0.01);
  EXPECT_LT(w.body(ball).linearVelocity_mps.norm(), 0.02);
}

TEST(Hull, RestsOnATiltedHeightFieldWithoutSliding) {
  // A 10 degree slope, friction 0.6 (> tan 10 deg): the hull block stays.
  const Real slope = std::tan(Real(10) * kPi / 180);
  GridField field(21, 21, 1, -10, -10, [&](Real x, Real) { return slope * x; });
  World w;
  w.setHeightField(&field);
  const Quat tilt(Eigen::AngleAxis<Real>(std::atan(slope), Vec3::UnitZ()));
  BodyDef d;
  d.shape = hullBox(Vec3(Real(0.4), Real(0.2), Real(0.3)));
  d.orientation = tilt;
  d.position_m = Vec3(0, Real(0.25) / std::cos(std::atan(slope)), Real(0.5));
  d.mass_kg = 1;
  const BodyId id = w.createBody(d).value();
  simulate(w, 1);
  const Vec3 p = w.body(id).position_m;
  simulate(w, 2);
  EXPECT_LT((w.body(id).position_m - p).norm(), 0.01);
  // Its centre sits h / cos above the surface.
  const Real surface = slope * w.body(id).position_m.x();
  EXPECT_NEAR(w.body(id).position_m.y() - surface, Real(0.2) / std::cos(std::atan(slope)), 0.01);
}

TEST(Hull, APeakOfTheHeightFieldUnderItsFaceHoldsItUp) {
  // Flat ground with one grid vertex raised 0.15 m under the middle of a
  // wide hull block: none of the block's corners is near the peak, so only
  // the terrain-vertex-against-lowest-face contact keeps the peak out.
  GridField field(11, 11, 1, -5, -5, [](Real x, Real z) { return x == 0 && z == 0 ? Real(0.15) : Real(0); });
  World w;
  w.setHeightField(&field);
  BodyDef d;
  d.shape = hullBox(Vec3(Real(0.9), Real(0.2), Real(0.9)));
  d.position_m = Vec3(Real(0.05), Real(0.6), Real(0.05));
  d.mass_kg = 5;
  const BodyId id = w.createBody(d).value();
  // Once settled, the block rides on the peak: without the peak contact its
  // centre would sink to about 0.2 m (corners on the nearly flat ground).
  // The peak may sit inside by the method's tolerance: terrain vertices
  // count only where they reach 1 cm deeper than every corner
  // (kPeakTolerance_m, as for boxes: a box here settles identically), plus
  // the 5 mm slop.
  simulate(w, 2);
  Real deepest = 1;  // signed distance of the peak from the hull (m), smallest seen
  for (int i = 0; i < 60; ++i) {
    w.step(Real(1.0 / 60.0));
    const Body& b = w.body(id);
    const Vec3 local = b.orientation.conjugate() * (Vec3(0, Real(0.15), 0) - b.position_m);
    Real outside = -1;
    for (const HullFace& f : b.shape.hull->faces) outside = std::max(outside, f.normal.dot(local) - f.offset_m);
    deepest = std::min(deepest, outside);
  }
  EXPECT_GT(deepest, -0.02) << "the peak went into the block";
  EXPECT_GT(w.body(id).position_m.y(), 0.3);
  EXPECT_LT(w.body(id).linearVelocity_mps.norm(), 0.05);
}

TEST(Compound, THandleFallsAndRestsOnItsBar) {
  World w;
  addGround(w);
  ShapeFrame frame;
  auto shape = makeCompoundShape({{Shape::box(Vec3(1, Real(0.1), Real(0.1))), Vec3::Zero(), Quat::Identity()},
                                  {Shape::capsule(Real(0.1), Real(0.4)), Vec3(0, 0, Real(0.6)),
                                   Quat(Eigen::AngleAxis<Real>(kPi / 2, Vec3::UnitX()))}},
                                 &frame);
  ASSERT_TRUE(shape.ok()) << shape.error();
  BodyDef d;
  d.shape = shape.value();
  d.position_m = Vec3(0, 1, 0) + frame.centre_m;
  d.orientation = frame.rotation;
  d.mass_kg = 3;
  const BodyId id = w.createBody(d).value();
  simulate(w, 3);
  const Body& b = w.body(id);
  EXPECT_LT(b.linearVelocity_mps.norm(), 0.02);
  EXPECT_NEAR(lowestY(b), 0, 0.01);
  // Lying flat, the centre of mass is 0.1 m up (both children are 0.1 thick).
  EXPECT_NEAR(b.position_m.y(), 0.1, 0.01);
}

TEST(Compound, RollsOnAHeightFieldChildByChild) {
  // A dumbbell (two spheres on a thin capsule) rolls down a 5 degree slope:
  // with the bar clear of the ground it rolls like its two wheels, so it
  // accelerates at g sin / (1 + I / (m r^2)).
  const Real slope = std::tan(Real(5) * kPi / 180);
  GridField field(41, 21, 1, -20, -10, [&](Real x, Real) { return -slope * x; });
  World w;
  w.setHeightField(&field);
  const Real r = Real(0.3);
  auto shape = makeCompoundShape({{Shape::sphere(r), Vec3(0, 0, -1), Quat::Identity()},
                                  {Shape::sphere(r), Vec3(0, 0, 1), Quat::Identity()},
                                  {Shape::capsule(Real(0.05), Real(0.7)), Vec3::Zero(),
                                   Quat(Eigen::AngleAxis<Real>(kPi / 2, Vec3::UnitX()))}});
  ASSERT_TRUE(shape.ok()) << shape.error();
  BodyDef d;
  d.shape = shape.value();
  d.position_m = Vec3(0, r / std::cos(std::atan(slope)) + Real(0.01), 0);
  d.density_kgpm3 = 1000;
  const BodyId id = w.createBody(d).value();
  simulate(w, Real(0.2));
  const Body& b0 = w.body(id);
  const Real x0 = b0.position_m.x(), v0 = b0.linearVelocity_mps.x();
  const Real t = 1;
  simulate(w, t);
  const Body& b = w.body(id);
  const Real iAxis = b.inertiaLocal_kgm2.minCoeff() < b.inertiaLocal_kgm2.maxCoeff()
                         ? (b.orientation.conjugate() * Vec3::UnitZ()).cwiseAbs().dot(b.inertiaLocal_kgm2)
                         : b.inertiaLocal_kgm2.x();
  const Real theta = std::atan(slope);
  const Real a = kStandardGravity * std::sin(theta) / (1 + iAxis / (b.mass_kg * r * r));
  const Real along = (b.position_m.x() - x0) / std::cos(theta);
  const Real expected = (v0 / std::cos(theta)) * t + a * t * t / 2;
  EXPECT_GT(expected, Real(0.3));  // it really rolls (a = 0.6 m/s^2 here)
  EXPECT_NEAR(along, expected, 0.03 * expected);
}

TEST(Hull, RayHitsTheFaceAtTheAnalyticDistance) {
  World w;
  BodyDef d;
  d.type = BodyType::Static;
  d.shape = puck(1, Real(0.5), 6);  // a hexagonal prism: flat faces at y = +-0.5
  d.position_m = Vec3(0, 2, 0);
  w.createBody(d).value();
  RayHit hit;
  ASSERT_TRUE(w.rayCast(Vec3(Real(0.2), 10, Real(0.1)), Vec3(0, -1, 0), 20, &hit));
  EXPECT_NEAR(hit.distance_m, 10 - Real(2.5), 1e-4);
  EXPECT_NEAR(hit.normal.y(), 1, 1e-4);
  // Along x the hexagon's vertex is at r = 1 (vertex 0 of the prism).
  ASSERT_TRUE(w.rayCast(Vec3(10, 2, 0), Vec3(-1, 0, 0), 20, &hit));
  EXPECT_NEAR(hit.distance_m, 9, 1e-4);
  EXPECT_FALSE(w.rayCast(Vec3(0, 10, Real(1.2)), Vec3(0, -1, 0), 20, &hit));
}

TEST(Query, SphereCastStopsAtTheAnalyticDistance) {
  World w;
  addGround(w);
  BodyDef box;
  box.type = BodyType::Static;
  box.shape = Shape::box(Vec3(1, 1, 1));
  box.position_m = Vec3(5, 1, 0);
  const BodyId boxId = w.createBody(box).value();
  ShapeCastHit hit;
  // Straight down onto the plane: centre travels 3 - r.
  ASSERT_TRUE(w.shapeCast(Shape::sphere(Real(0.5)), Vec3(0, 3, 0), Quat::Identity(), Vec3(0, -1, 0), 10, &hit));
  EXPECT_NEAR(hit.distance_m, Real(2.5), 2e-3);
  EXPECT_NEAR(hit.normal.y(), 1, 1e-3);
  EXPECT_NEAR(hit.point_m.y(), 0, 2e-3);
  // Sideways into the box's face at x = 4: travels 4 - 0.5 from x = 0.
  ASSERT_TRUE(w.shapeCast(Shape::sphere(Real(0.5)), Vec3(0, 1, 0), Quat::Identity(), Vec3(2, 0, 0), 10, &hit));
  EXPECT_EQ(hit.body, boxId);
  EXPECT_NEAR(hit.distance_m, Real(3.5), 2e-3);
  EXPECT_NEAR(hit.normal.x(), -1, 1e-3);
  // Grazing the box's top edge (y = 2) from above at height 2 + r + 1 mm: passes.
  EXPECT_FALSE(w.shapeCast(Shape::sphere(Real(0.5)), Vec3(0, Real(2.51), 0), Quat::Identity(), Vec3(1, 0, 0), 10,
                           &hit, BodyId{}) &&
               hit.body == boxId);
  // Too short a cast: no hit.
  EXPECT_FALSE(w.shapeCast(Shape::sphere(Real(0.5)), Vec3(0, 3, 0), Quat::Identity(), Vec3(0, -1, 0), 2, &hit));
  // Ignoring the plane, a box cast down beside the box finds nothing else.
  const BodyId ground = w.idOf(0);
  EXPECT_FALSE(w.shapeCast(Shape::box(Vec3::Constant(Real(0.3))), Vec3(0, 3, 0), Quat::Identity(), Vec3(0, -1, 0), 10,
                           &hit, ground));
}

TEST(Query, BoxAndSphereCastsHitTheHeightFieldOnASlope) {
  // Slope y = 0.5 x; casting down at x = 2 (surface y = 1).
  GridField field(21, 21, 1, -10, -10, [](Real x, Real) { return Real(0.5) * x; });
  World w;
  w.setHeightField(&field);
  ShapeCastHit hit;
  const Real r = Real(0.25);
  ASSERT_TRUE(w.shapeCast(Shape::sphere(r), Vec3(2, 5, Real(0.3)), Quat::Identity(), Vec3(0, -1, 0), 10, &hit));
  // A sphere touches the plane when its centre is r / cos(theta) above it.
  const Real cosT = 1 / std::sqrt(Real(1.25));
  EXPECT_NEAR(hit.distance_m, 5 - 1 - r / cosT, 3e-3);
  EXPECT_TRUE(hit.body.isNull());
  EXPECT_NEAR(hit.normal.dot(Vec3(-Real(0.5), 1, 0).normalized()), 1, 1e-3);
  // An axis-aligned box (half 0.2) first touches with its lower corner at x = 2 + 0.2 (uphill side).
  ASSERT_TRUE(w.shapeCast(Shape::box(Vec3::Constant(Real(0.2))), Vec3(2, 5, Real(0.3)), Quat::Identity(),
                          Vec3(0, -1, 0), 10, &hit));
  EXPECT_NEAR(hit.distance_m, 5 - Real(0.2) - Real(0.5) * Real(2.2), 3e-3);
}

TEST(Query, HullCastOntoHullAndOverlap) {
  World w;
  BodyDef d;
  d.type = BodyType::Static;
  d.shape = hullBox(Vec3(1, Real(0.5), 1));
  const BodyId base = w.createBody(d).value();
  const BodyId ball = addBody(w, Shape::sphere(Real(0.5)), Vec3(4, 0, 0));
  ShapeCastHit hit;
  ASSERT_TRUE(w.shapeCast(puck(Real(0.3), Real(0.2)), Vec3(0, 3, 0), Quat::Identity(), Vec3(0, -1, 0), 10, &hit));
  EXPECT_EQ(hit.body, base);
  EXPECT_NEAR(hit.distance_m, 3 - Real(0.5) - Real(0.2), 2e-3);
  // Overlap: a box straddling both bodies finds both; one beside them, none.
  auto both = w.overlapShape(Shape::box(Vec3(Real(2.5), Real(0.2), Real(0.2))), Vec3(2, 0, 0), Quat::Identity());
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[0], base);
  EXPECT_EQ(both[1], ball);
  EXPECT_TRUE(w.overlapShape(Shape::sphere(Real(0.4)), Vec3(2, 0, 2), Quat::Identity()).empty());
  // A rotated box reaching the sphere only with its corner.
  const Quat q(Eigen::AngleAxis<Real>(kPi / 4, Vec3::UnitY()));
  EXPECT_EQ(w.overlapShape(Shape::box(Vec3::Constant(Real(0.5))), Vec3(Real(2.9), 0, 0), q).size(), 1u);
  EXPECT_TRUE(w.overlapShape(Shape::box(Vec3::Constant(Real(0.5))), Vec3(Real(2.7), 0, 0), Quat::Identity()).empty());
  // Bad queries find nothing rather than failing.
  EXPECT_TRUE(w.overlapShape(Shape::sphere(-1), Vec3::Zero(), Quat::Identity()).empty());
  EXPECT_FALSE(w.shapeCast(Shape::sphere(1), Vec3::Zero(), Quat::Identity(), Vec3::Zero(), 1, &hit));
}

}  // namespace
}  // namespace tumble::physics::test
