// Free rigid bodies: mass properties and the Newton-Euler equations.
#include "physics_fixture.h"

namespace tumble::physics::test {

TEST(RigidBody, InertiaOfShapesMatchesTextbookFormulas) {
  // Solid sphere 2/5 m r^2; box m (b^2 + c^2) / 12 with full sizes.
  EXPECT_NEAR(Shape::sphere(2).unitInertia().x(), 0.4 * 4, 1e-5);
  Vec3 box = Shape::box(Vec3(1, 2, 3)).unitInertia();
  EXPECT_NEAR(box.x(), (16.0 + 36.0) / 12, 1e-4);
  EXPECT_NEAR(box.y(), (4.0 + 36.0) / 12, 1e-4);
  EXPECT_NEAR(box.z(), (4.0 + 16.0) / 12, 1e-4);
  // A capsule with no core is a sphere; a long thin one tends to a rod m L^2/12.
  EXPECT_NEAR(Shape::capsule(1, 0).unitInertia().x(), 0.4, 1e-5);
  Real L = 100, r = Real(0.01);
  EXPECT_NEAR(Shape::capsule(r, L / 2).unitInertia().x(), L * L / 12, L * L / 12 * 1e-3);
}

TEST(RigidBody, IntermediateAxisFlipsWhileEnergyAndMomentumStay) {
  // Dzhanibekov effect: spin about the intermediate principal axis is
  // unstable, so the body flips over periodically. Torque-free motion keeps
  // kinetic energy and |L| constant.
  World w;
  w.settings().gravity_mps2 = Vec3::Zero();
  w.settings().enableSleep = false;
  BodyDef d;
  d.shape = Shape::box(Vec3(Real(0.1), Real(0.4), Real(1.0)));  // Ix > Iy... intermediate = y
  d.mass_kg = 1;
  d.angularVelocity_radps = Vec3(Real(0.01), 6, Real(0.01));
  BodyId b = w.createBody(d).value();
  const Body& body = w.body(b);
  auto energy = [&] {
    Vec3 wl = body.orientation.conjugate() * body.angularVelocity_radps;
    return 0.5 * wl.dot(body.inertiaLocal_kgm2.cwiseProduct(wl));
  };
  auto angularMomentum = [&] {
    Vec3 wl = body.orientation.conjugate() * body.angularVelocity_radps;
    return (body.orientation * body.inertiaLocal_kgm2.cwiseProduct(wl)).norm();
  };
  double e0 = energy(), l0 = angularMomentum();
  int flips = 0;
  Real prevSign = 1;
  for (int i = 0; i < 60 * 20; ++i) {
    w.step(Real(1.0 / 60));
    Vec3 wl = body.orientation.conjugate() * body.angularVelocity_radps;
    Real sign = wl.y() >= 0 ? 1 : -1;
    if (sign != prevSign) ++flips;
    prevSign = sign;
  }
  EXPECT_GE(flips, 2) << "spin about the intermediate axis must flip";
  EXPECT_NEAR(energy(), e0, 0.01 * e0);
  EXPECT_NEAR(angularMomentum(), l0, 0.01 * l0);
}

TEST(RigidBody, StableAxisSpinStaysPut) {
  World w;
  w.settings().gravity_mps2 = Vec3::Zero();
  w.settings().enableSleep = false;
  BodyDef d;
  d.shape = Shape::box(Vec3(Real(0.1), Real(0.4), Real(1.0)));
  d.mass_kg = 1;
  d.angularVelocity_radps = Vec3(6, Real(0.01), Real(0.01));  // about the largest moment
  BodyId b = w.createBody(d).value();
  simulate(w, 10);
  const Body& body = w.body(b);
  Vec3 wl = body.orientation.conjugate() * body.angularVelocity_radps;
  EXPECT_GT(wl.x(), Real(5.9));
}

}  // namespace tumble::physics::test
