// Bodies on a height field, compared with analytic answers. The field here
// is a synthetic grid of triangles built in the test (same split as the
// terrain module: each cell cut along its (i, j)-(i+1, j+1) diagonal), so
// physics is tested without the terrain module.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "physics/height_field.h"
#include "physics/world.h"
#include "grid_field.h"
#include "physics_fixture.h"

namespace tumble::physics::test {
namespace {

BodyDef dynamicDef(const Shape& s, const Vec3& p, Real friction = Real(0.6)) {
  BodyDef d;
  d.shape = s;
  d.position_m = p;
  d.mass_kg = 1;
  d.friction = friction;
  return d;
}

// A sphere rolling without slipping down a slope of angle theta accelerates
// at a = g sin(theta) / (1 + I / (m r^2)) = 5/7 g sin(theta). The slope is
// 0.5 m triangles, so a 0.5 m ball crosses a seam every few centimetres.
TEST(HeightField, SphereRollsDownSlopeAtFiveSeventhsGSinTheta) {
  const Real theta = Real(20 * kPi / 180), r = Real(0.5);
  GridField field(161, 21, Real(0.5), -10, -5, [&](Real x, Real) { return -std::tan(theta) * x; });
  World w;
  w.setHeightField(&field);
  const Vec3 n(std::sin(theta), std::cos(theta), 0);
  BodyId ball = w.createBody(dynamicDef(Shape::sphere(r), n * r + Vec3(0, 0, Real(0.13)))).value();
  const Real T = 2;
  Real maxNormalSpeed = 0;
  for (int i = 0; i < int(T * 60); ++i) {
    w.step(Real(1.0 / 60));
    maxNormalSpeed = std::max(maxNormalSpeed, std::abs(w.body(ball).linearVelocity_mps.dot(n)));
  }
  const Vec3 down(std::cos(theta), -std::sin(theta), 0);
  const Real a = w.body(ball).linearVelocity_mps.dot(down) / T;
  const Real expected = Real(5.0 / 7.0) * kStandardGravity * std::sin(theta);
  std::printf("slope: a = %.4f m/s^2, expected %.4f (%.2f%%), max |v.n| = %.2e m/s\n", a, expected,
              100 * (a / expected - 1), maxNormalSpeed);
  EXPECT_NEAR(a, expected, Real(0.02) * expected);
  EXPECT_LT(maxNormalSpeed, Real(0.01));  // never bumps at a seam
}

// A box sliding on flat ground made of many triangles: no seam ever lifts
// it (max |v_y| tiny) and it stops after v0^2 / (2 mu g), mu = sqrt(0.5 * 0.5).
TEST(HeightField, BoxSlidesOverSeamsWithoutBumpingAndStopsAsFrictionPredicts) {
  GridField field(81, 81, Real(0.5), -20, -20, [](Real, Real) { return Real(0); },
                  [](Real, Real) { return Real(0.5); });
  World w;
  w.setHeightField(&field);
  const Vec3 dir = Vec3(1, 0, Real(0.37)).normalized();  // crosses the diagonals too
  const Real v0 = 5, mu = Real(0.5);
  BodyDef d = dynamicDef(Shape::box(Vec3(Real(0.4), Real(0.25), Real(0.4))), Vec3(-5, Real(0.25), -3), mu);
  d.linearVelocity_mps = dir * v0;
  BodyId box = w.createBody(d).value();
  const Vec3 start = w.body(box).position_m;
  Real maxVy = 0;
  for (int i = 0; i < 240; ++i) {
    w.step(Real(1.0 / 60));
    maxVy = std::max(maxVy, std::abs(w.body(box).linearVelocity_mps.y()));
  }
  const Real dist = (w.body(box).position_m - start).dot(dir);
  const Real expected = v0 * v0 / (2 * mu * kStandardGravity);
  std::printf("box slide: %.4f m, expected %.4f (%.2f%%), max |v_y| = %.2e m/s, final y = %.5f\n", dist,
              expected, 100 * (dist / expected - 1), maxVy, w.body(box).position_m.y());
  EXPECT_NEAR(dist, expected, Real(0.03) * expected);
  EXPECT_LT(maxVy, Real(1e-2));
  EXPECT_NEAR(w.body(box).position_m.y(), Real(0.25), Real(0.01));
}

// A ball rolling across seams on flat ground with rolling resistance C_rr
// decelerates at (5/7) C_rr g, smoothly: the speed never rises and |v_y| stays ~0.
TEST(HeightField, SphereRollsAcrossSeamsWithoutBumping) {
  GridField field(121, 61, Real(0.5), -10, -15, [](Real, Real) { return Real(0); });
  World w;
  w.setHeightField(&field);
  const Real crr = Real(0.05), r = Real(0.3), v0 = 3;
  const Vec3 dir = Vec3(1, 0, Real(0.61)).normalized();
  BodyDef d = dynamicDef(Shape::sphere(r), Vec3(-5, r, -10));
  d.rollingResistance = crr;
  d.linearVelocity_mps = dir * v0;
  d.angularVelocity_radps = Vec3::UnitY().cross(dir) * (v0 / r);  // rolling: v = w x (r up)
  BodyId ball = w.createBody(d).value();
  Real maxVy = 0, prevSpeed = v0, maxRise = 0;
  const Real T = 3;
  for (int i = 0; i < int(T * 60); ++i) {
    w.step(Real(1.0 / 60));
    const Vec3 v = w.body(ball).linearVelocity_mps;
    maxVy = std::max(maxVy, std::abs(v.y()));
    const Real speed = v.norm();
    maxRise = std::max(maxRise, speed - prevSpeed);
    prevSpeed = speed;
  }
  const Real decel = (v0 - prevSpeed) / T, expected = Real(5.0 / 7.0) * crr * kStandardGravity;
  std::printf("rolling: decel %.4f m/s^2, expected %.4f (%.2f%%), max |v_y| %.2e, max speed rise %.2e\n", decel,
              expected, 100 * (decel / expected - 1), maxVy, maxRise);
  EXPECT_NEAR(decel, expected, Real(0.05) * expected);
  EXPECT_LT(maxVy, Real(1e-2));
  EXPECT_LT(maxRise, Real(1e-4));
}

// Friction from the field's friction function ("drag map"): mud (0.9) in one
// lane, ice-like (0.1) in the other; each block stops after v0^2 / (2 mu g)
// with mu = sqrt(body 1.0 * field).
TEST(HeightField, FrictionFunctionSetsStoppingDistance) {
  GridField field(81, 41, Real(0.5), -10, -10, [](Real, Real) { return Real(0); },
                  [](Real, Real z) { return z > 0 ? Real(0.9) : Real(0.1); });
  World w;
  w.setHeightField(&field);
  const Real v0 = 4;
  BodyId blocks[2];
  const Real lanes[2] = {5, -5}, fieldMu[2] = {Real(0.9), Real(0.1)};
  for (int k = 0; k < 2; ++k) {
    BodyDef d = dynamicDef(Shape::box(Vec3(Real(0.3), Real(0.2), Real(0.3))), Vec3(-8, Real(0.2), lanes[k]), 1);
    d.linearVelocity_mps = Vec3(v0, 0, 0);
    blocks[k] = w.createBody(d).value();
  }
  simulate(w, 5);
  for (int k = 0; k < 2; ++k) {
    const Real mu = std::sqrt(fieldMu[k]);
    const Real expected = v0 * v0 / (2 * mu * kStandardGravity);
    const Real dist = w.body(blocks[k]).position_m.x() + 8;
    std::printf("field mu %.1f: slid %.4f m, expected %.4f (%.2f%%)\n", fieldMu[k], dist, expected,
                100 * (dist / expected - 1));
    EXPECT_NEAR(dist, expected, Real(0.03) * expected);
  }
}

// A sphere and a box fired down at 300 m/s neither pass through the field
// nor end up under it (speculative contacts plus the swept check).
TEST(HeightField, FastBodiesDoNotTunnel) {
  GridField field(81, 81, 1, -40, -40, [](Real x, Real z) { return Real(0.05) * std::sin(x) * std::cos(z); });
  World w;
  w.setHeightField(&field);
  BodyDef s = dynamicDef(Shape::sphere(Real(0.25)), Vec3(Real(0.3), 40, Real(0.7)));
  s.linearVelocity_mps = Vec3(0, -300, 0);
  BodyDef b = dynamicDef(Shape::box(Vec3::Constant(Real(0.2))), Vec3(Real(-3.3), 40, Real(2.1)));
  b.linearVelocity_mps = Vec3(4, -300, -2);
  BodyId ids[2] = {w.createBody(s).value(), w.createBody(b).value()};
  Real lowest[2] = {1e9, 1e9};
  for (int i = 0; i < 60; ++i) {
    w.step(Real(1.0 / 60));
    for (int k = 0; k < 2; ++k) {
      const Vec3 p = w.body(ids[k]).position_m;
      Real h;
      Vec3 n;
      ASSERT_TRUE(field.surfaceAt(p.x(), p.z(), &h, &n)) << "body " << k << " left the field at step " << i << ": "
                                                         << p.transpose();
      lowest[k] = std::min(lowest[k], p.y() - h);
    }
  }
  std::printf("fast: lowest centre above the surface: sphere %.4f m, box %.4f m\n", lowest[0], lowest[1]);
  EXPECT_GT(lowest[0], 0);
  EXPECT_GT(lowest[1], 0);
}

// World::rayCast sees the height field (null body), and bodies in front of it.
TEST(HeightField, RayCastHitsTheFieldAndBodies) {
  GridField field(21, 21, 1, -10, -10, [](Real x, Real) { return Real(0.25) * x + 2; });
  World w;
  w.setHeightField(&field);
  RayHit hit;
  ASSERT_TRUE(w.rayCast(Vec3(3, 100, 1), Vec3(0, -1, 0), 1000, &hit));
  EXPECT_TRUE(hit.body.isNull());
  EXPECT_NEAR(hit.point_m.y(), Real(2.75), Real(1e-4));
  BodyId ball = addBody(w, Shape::sphere(Real(0.5)), Vec3(3, 10, 1));
  ASSERT_TRUE(w.rayCast(Vec3(3, 100, 1), Vec3(0, -1, 0), 1000, &hit));
  EXPECT_EQ(hit.body, ball);
  EXPECT_EQ(w.rayCastAll(Vec3(3, 100, 1), Vec3(0, -1, 0), 1000).size(), 2u);
}

// Shapes come to rest on a bumpy field, on its surface, and sleep.
TEST(HeightField, ShapesComeToRestOnBumpyGround) {
  GridField field(41, 41, 1, -20, -20, [](Real x, Real z) { return Real(0.4) * std::sin(Real(0.7) * x) + Real(0.3) * std::cos(Real(0.5) * z); });
  World w;
  w.setHeightField(&field);
  BodyDef sphere = dynamicDef(Shape::sphere(Real(0.4)), Vec3(1, 3, 1));
  sphere.rollingResistance = Real(0.2);
  BodyDef capsule = dynamicDef(Shape::capsule(Real(0.3), Real(0.5)), Vec3(5, 3, -3));
  capsule.rollingResistance = Real(0.2);
  BodyId ids[3] = {w.createBody(sphere).value(),
                   w.createBody(dynamicDef(Shape::box(Vec3(Real(0.5), Real(0.3), Real(0.4))), Vec3(-4, 3, 2))).value(),
                   w.createBody(capsule).value()};
  w.setOrientation(ids[2], Quat(Eigen::AngleAxis<Real>(Real(kPi / 2), Vec3::UnitZ())));
  simulate(w, 15);
  for (BodyId id : ids) {
    const Body& b = w.body(id);
    Real h = 0;
    Vec3 n;
    EXPECT_TRUE(field.surfaceAt(b.position_m.x(), b.position_m.z(), &h, &n));
    std::printf("%s at (%.2f, %.3f, %.2f), surface %.3f, speed %.2e, awake %d\n", shapeTypeName(b.shape.type),
                b.position_m.x(), b.position_m.y(), b.position_m.z(), h, b.linearVelocity_mps.norm(), b.awake);
    EXPECT_GT(b.position_m.y(), h);
    EXPECT_LT(b.position_m.y(), h + b.shape.boundingRadius() + Real(0.05));
    EXPECT_LT(b.linearVelocity_mps.norm(), Real(0.05));
  }
  EXPECT_LT(w.errorStats().penetrationMax_m, Real(0.05));
}

// Sharp ridges (a sawtooth with 56 degree flanks, 1.5 m high, every 2 m):
// spheres and tumbling boxes dropped on them must not get phantom deep
// contacts from triangles whose plane they are behind (a sphere near a
// ridge is behind the far flank's plane, yet above the ground) or sink onto
// a ridge that crosses under a box face between its corners. Both happened
// on rough generated terrain (0.67 m and 0.43 m "penetrations").
TEST(HeightField, SharpRidgesGiveNoPhantomDeepContacts) {
  GridField field(41, 41, 1, -20, -20, [](Real x, Real) {
    const Real f = x / 2 - std::floor(x / 2);  // 0..1 over each 2 m period
    return Real(1.5) * (1 - std::abs(2 * f - 1));
  });
  World w;
  w.setHeightField(&field);
  std::vector<BodyId> ids;
  for (int i = 0; i < 6; ++i) {
    const Vec3 at(Real(-6 + 2.3 * i), 4, Real(-3 + 1.1 * i));
    BodyDef def = i % 2 ? dynamicDef(Shape::box(Vec3(Real(0.6), Real(0.25), Real(0.45))), at)
                        : dynamicDef(Shape::sphere(Real(0.35 + 0.1 * i)), at);
    def.rollingResistance = Real(0.3);
    BodyId id = w.createBody(def).value();
    w.setOrientation(id, Quat(Eigen::AngleAxis<Real>(Real(0.7 * i), Vec3(1, 1, 0).normalized())));
    ids.push_back(id);
  }
  simulate(w, 8);
  std::printf("penetration max %.4f m\n", double(w.errorStats().penetrationMax_m));
  EXPECT_LT(w.errorStats().penetrationMax_m, Real(0.03));
  for (BodyId id : ids) {
    const Body& b = w.body(id);
    Real h = 0;
    Vec3 n;
    ASSERT_TRUE(field.surfaceAt(b.position_m.x(), b.position_m.z(), &h, &n));
    EXPECT_GT(b.position_m.y(), h) << shapeTypeName(b.shape.type) << " centre under the ground";
    EXPECT_LT(b.linearVelocity_mps.norm(), Real(0.05)) << shapeTypeName(b.shape.type);
  }
}

}  // namespace
}  // namespace tumble::physics::test
