// The rigid-body world's integrator strategies (physics/integrate.h): each
// method's free fall against its closed form, a soft spring against the
// analytic oscillation, a k/m = 1e6 spring at dt = 1/60 (implicit methods
// stay bounded, explicit ones blow up and are caught, never a crash),
// internal springs conserve momentum, and contacts still hold a box up.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/world.h"

namespace tumble::physics {
namespace {

constexpr Real kDt = Real(1.0 / 60.0);

BodyId addSphere(World& w, const Vec3& p, Real mass = 1) {
  BodyDef d;
  d.shape = Shape::sphere(Real(0.1));
  d.position_m = p;
  d.mass_kg = mass;
  d.allowSleep = false;
  return w.createBody(d).value();
}

World makeWorld(BodyIntegrator method, int substeps, const Vec3& gravity) {
  WorldSettings s;
  s.integrator = method;
  s.substeps = substeps;
  s.gravity_mps2 = gravity;
  return World(s);
}

TEST(WorldIntegrator, NamesParseAndUnknownNamesListTheValidOnes) {
  EXPECT_EQ(parseBodyIntegrator("rk4").value(), BodyIntegrator::Rk4);
  EXPECT_EQ(parseBodyIntegrator("trapezoid").value(), BodyIntegrator::Heun);
  EXPECT_EQ(parseBodyIntegrator("stiff").value(), BodyIntegrator::Sdirk2);
  auto bad = parseBodyIntegrator("rk5");
  ASSERT_FALSE(bad);
  for (const auto& info : bodyIntegrators())
    EXPECT_NE(bad.error().find(info.name), std::string::npos) << bad.error();
  EXPECT_STREQ(bodyIntegrators()[0].name, "symplectic_euler") << "the default comes first";
}

// Constant acceleration: x_n = x0 + g h^2 * c(n) with c = n^2/2 for every
// method of order >= 2, n(n+1)/2 for symplectic and implicit Euler (they use
// the new velocity), n(n-1)/2 for explicit Euler (the old one).
TEST(WorldIntegrator, FreeFallMatchesEachMethodsClosedForm) {
  const int n = 60;
  const double g = 9.81, h = kDt;
  for (const auto& info : bodyIntegrators()) {
    World w = makeWorld(info.method, 1, Vec3(0, Real(-g), 0));
    BodyId b = addSphere(w, Vec3(0, 100, 0));
    for (int i = 0; i < n; ++i) w.step(kDt);
    double c = n * n / 2.0;
    if (info.method == BodyIntegrator::SymplecticEuler || info.method == BodyIntegrator::ImplicitEuler)
      c = n * (n + 1) / 2.0;
    if (info.method == BodyIntegrator::Euler) c = n * (n - 1) / 2.0;
    const double expected = 100 - g * h * h * c;
    EXPECT_NEAR(w.body(b).position_m.y(), expected, 2e-4) << info.name;
    EXPECT_NEAR(w.body(b).linearVelocity_mps.y(), -g * n * h, 1e-4) << info.name;
  }
}

// m x'' = -k x, x(0) = A: x(t) = A cos(w t), energy k A^2 / 2.
TEST(WorldIntegrator, SoftSpringFollowsTheAnalyticOscillation) {
  const double k = 100, A = 0.1, w0 = 10;  // m = 1 kg
  const int steps = 120;                   // 2 s, 8 substeps: w h = 0.021
  for (BodyIntegrator m : {BodyIntegrator::Rk4, BodyIntegrator::Heun, BodyIntegrator::Verlet,
                           BodyIntegrator::Sdirk2, BodyIntegrator::ImplicitMidpoint}) {
    World w = makeWorld(m, 8, Vec3::Zero());
    BodyId b = addSphere(w, Vec3(Real(A), 0, 0));
    ASSERT_TRUE(w.addSpring({b, {}, Vec3::Zero(), Real(k), 0, 0}));
    double maxErr = 0;
    for (int i = 1; i <= steps; ++i) {
      w.step(kDt);
      maxErr = std::max(maxErr, std::abs(w.body(b).position_m.x() - A * std::cos(w0 * i * kDt)));
    }
    // Phase error per step of the second-order methods: at most (w h)^3 / 6
    // (Heun; Verlet / midpoint 1/24, 1/12), so A w t (w h)^2 / 6 over t;
    // plus float rounding of the positions.
    const double wh = w0 * kDt / 8;
    EXPECT_LT(maxErr, A * w0 * steps * kDt * wh * wh / 6 + 2e-5) << bodyIntegratorName(m);
    EXPECT_NEAR(w.totalEnergy(), 0.5 * k * A * A, 2e-3 * 0.5 * k * A * A) << bodyIntegratorName(m);
  }
  // Explicit Euler multiplies the energy by 1 + (w h)^2 every substep.
  World w = makeWorld(BodyIntegrator::Euler, 8, Vec3::Zero());
  BodyId b = addSphere(w, Vec3(Real(A), 0, 0));
  ASSERT_TRUE(w.addSpring({b, {}, Vec3::Zero(), Real(k), 0, 0}));
  for (int i = 0; i < steps; ++i) w.step(kDt);
  const double wh = w0 * kDt / 8;
  const double predicted = 0.5 * k * A * A * std::pow(1 + wh * wh, 8 * steps);
  EXPECT_NEAR(w.totalEnergy() / predicted, 1.0, 0.02);
  (void)b;
}

// k/m = 1e6 at dt = 1/60 in one substep: w h = 16.7, beyond every explicit
// method's limit on the imaginary axis (2 symplectic / Verlet, 2.83 RK4,
// none for Euler and Heun).
TEST(WorldIntegrator, StiffSpringIsStableWithImplicitMethodsAndCaughtOtherwise) {
  const double k = 1e6, A = 0.1;
  const double e0 = 0.5 * k * A * A;
  for (const auto& info : bodyIntegrators()) {
    World w = makeWorld(info.method, 1, Vec3(0, -9.81f, 0));
    BodyId b = addSphere(w, Vec3(Real(A), 0, 0));
    ASSERT_TRUE(w.addSpring({b, {}, Vec3::Zero(), Real(k), 0, 0}));
    double eMax = 0;
    for (int i = 0; i < 60; ++i) {
      w.step(kDt);
      eMax = std::max(eMax, w.body(b).frozen ? INFINITY : w.totalEnergy());
    }
    const bool implicitDamped =
        info.method == BodyIntegrator::ImplicitEuler || info.method == BodyIntegrator::Sdirk2;
    if (implicitDamped) {
      EXPECT_FALSE(w.body(b).frozen) << info.name;
      EXPECT_LE(eMax, e0 * 1.001) << info.name << ": L-stable, energy never grows";
      // Static sag under gravity: m g / k = 9.8 um; the stiff mode is gone.
      EXPECT_NEAR(w.body(b).position_m.y(), -9.81 / k, 2e-6) << info.name;
      EXPECT_LT(std::abs(w.body(b).position_m.x()), 1e-3) << info.name;
    } else if (info.method == BodyIntegrator::ImplicitMidpoint) {
      EXPECT_LE(eMax, e0 * 1.01) << "A-stable: bounded, but the stiff mode rings";
    } else {
      EXPECT_TRUE(w.body(b).frozen || eMax > 1e3 * e0) << info.name << " should have blown up";
      if (w.body(b).frozen) {
        EXPECT_GT(w.errorStats().nanEvents, 0);
      }
    }
  }
  // The default eight substeps give w h = 2.08: just past symplectic
  // Euler's limit of 2, inside RK4's 2.83.
  for (BodyIntegrator m : {BodyIntegrator::SymplecticEuler, BodyIntegrator::Rk4}) {
    World w = makeWorld(m, 8, Vec3::Zero());
    BodyId b = addSphere(w, Vec3(Real(A), 0, 0));
    ASSERT_TRUE(w.addSpring({b, {}, Vec3::Zero(), Real(k), 0, 0}));
    for (int i = 0; i < 60; ++i) w.step(kDt);
    const double e = w.body(b).frozen ? INFINITY : w.totalEnergy();
    if (m == BodyIntegrator::Rk4) EXPECT_LT(e, e0) << "RK4 damps at w h = 2.08";
    else EXPECT_GT(e, 1e3 * e0) << "symplectic Euler grows at w h = 2.08";
  }
}

TEST(WorldIntegrator, SpringsBetweenBodiesConserveMomentum) {
  for (BodyIntegrator m : {BodyIntegrator::Rk4, BodyIntegrator::Sdirk2, BodyIntegrator::SymplecticEuler}) {
    World w = makeWorld(m, 4, Vec3::Zero());
    BodyId a = addSphere(w, Vec3(0, 0, 0), 1);
    BodyId b = addSphere(w, Vec3(2, 0, 0), 3);
    w.setLinearVelocity(a, Vec3(0, 1, 0));
    w.setLinearVelocity(b, Vec3(1, 0, 0.5));
    ASSERT_TRUE(w.addSpring({a, b, Vec3::Zero(), 400, 2, 1}));
    const Eigen::Vector3d p0 = w.totalMomentum();
    for (int i = 0; i < 120; ++i) w.step(kDt);
    EXPECT_LT((w.totalMomentum() - p0).norm(), 1e-4 * p0.norm()) << bodyIntegratorName(m);
    EXPECT_LT(w.errorStats().momentumRelDriftMax, 1e-4) << bodyIntegratorName(m);
  }
}

TEST(WorldIntegrator, SpringDefinitionsAreChecked) {
  World w;
  BodyId a = addSphere(w, Vec3::Zero());
  auto bad = w.addSpring({a, {}, Vec3::Zero(), -5, 0, 0});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().find("stiffness"), std::string::npos) << bad.error();
  auto self = w.addSpring({a, a, Vec3::Zero(), 5, 0, 0});
  EXPECT_FALSE(self);
  // Negative rest length: the current distance.
  auto s = w.addSpring({a, {}, Vec3(0, 3, 4), 5, 0, -1});
  ASSERT_TRUE(s);
  EXPECT_FLOAT_EQ(w.integration().spring(*s).restLength_m, 5);
  w.destroyBody(a);
  w.step(kDt);
  EXPECT_EQ(w.integration().springCount(), 0) << "a spring goes with its body";
}

// Contacts stay velocity-level impulses after each method's free step: a
// box dropped on the ground comes to rest on it with every method.
TEST(WorldIntegrator, ContactsHoldABoxUpWithEveryMethod) {
  for (const auto& info : bodyIntegrators()) {
    World w;
    w.settings().integrator = info.method;
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shape = Shape::plane();
    ASSERT_TRUE(w.createBody(ground));
    BodyDef d;
    d.shape = Shape::box(Vec3(Real(0.5), Real(0.5), Real(0.5)));
    d.position_m = Vec3(0, 1, 0);
    d.mass_kg = 10;
    BodyId box = w.createBody(d).value();
    for (int i = 0; i < 180; ++i) w.step(kDt);
    EXPECT_NEAR(w.body(box).position_m.y(), 0.5, 0.01) << info.name;
    EXPECT_LT(w.errorStats().penetrationMax_m, 0.02) << info.name;
  }
}

}  // namespace
}  // namespace tumble::physics
