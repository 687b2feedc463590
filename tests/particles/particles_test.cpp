// Particle emitters as a specification: counts and lifetimes match the
// parameters statistically, kinematics match the integrator's discrete sums,
// pools stay within max_count, local space follows the emitter.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "particles/particle_system.h"

namespace tumble::particles {
namespace {

constexpr float kDt = 1.0f / 60.0f;

EmitterDef quiet() {
  EmitterDef d;
  d.rate_per_s = 0;
  d.lifetimeMin_s = d.lifetimeMax_s = 10;
  d.speedMin_mps = d.speedMax_mps = 0;
  return d;
}

struct Stats {
  double mean = 0, sd = 0, lo = 1e30, hi = -1e30;
  int n = 0;
};
Stats stats(const std::vector<double>& v) {
  Stats s;
  s.n = int(v.size());
  for (double x : v) s.mean += x, s.lo = std::min(s.lo, x), s.hi = std::max(s.hi, x);
  s.mean /= s.n;
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = std::sqrt(s.sd / (s.n - 1));
  return s;
}

TEST(Particles, SteadyStateCountIsRateTimesMeanLifetime) {
  // Little's law: N = rate * E[lifetime] = 200/s * 1.5 s = 300.
  EmitterDef d = quiet();
  d.rate_per_s = 200;
  d.lifetimeMin_s = 1.0f;
  d.lifetimeMax_s = 2.0f;
  ParticleSystem ps(7);
  EmitterId id = ps.create(d, Eigen::Vector3f::Zero());
  for (int i = 0; i < 180; ++i) ps.step(kDt);  // 3 s: past the longest lifetime
  double sum = 0;
  int samples = 0;
  for (int i = 0; i < 600; ++i) {
    ps.step(kDt);
    sum += ps.count(id);
    ++samples;
  }
  const double mean = sum / samples;
  // Sampled at step ends, a particle born in a step has lived (0, dt] there:
  // the count is within one step's births of 300; the rest is noise.
  EXPECT_NEAR(mean, 300.0, 8.0);
}

TEST(Particles, RateWithFractionalAccumulationEmitsExactly) {
  // 7.5 particles/s for 4 s is exactly 30, though 7.5 / 60 per step is fractional.
  EmitterDef d = quiet();
  d.rate_per_s = 7.5f;
  ParticleSystem ps(1);
  EmitterId id = ps.create(d, Eigen::Vector3f::Zero());
  for (int i = 0; i < 240; ++i) ps.step(kDt);
  EXPECT_EQ(ps.count(id), 30);
}

TEST(Particles, LifetimeAndSpeedDistributionsMatchTheirRanges) {
  EmitterDef d = quiet();
  d.bursts = {{0, 4000}};
  d.maxCount = 4000;
  d.lifetimeMin_s = 0.5f;
  d.lifetimeMax_s = 2.5f;
  d.speedMin_mps = 2;
  d.speedMax_mps = 6;
  ParticleSystem ps(3);
  ps.setGravity(Eigen::Vector3f::Zero());
  EmitterId id = ps.create(d, Eigen::Vector3f::Zero());
  ps.step(kDt);
  const ParticlePool& p = ps.get(id)->pool;
  ASSERT_EQ(p.count, 4000u);
  std::vector<double> life, speed;
  for (std::uint32_t i = 0; i < p.count; ++i) {
    life.push_back(1.0 / p.invLifetime[i]);
    speed.push_back(Eigen::Vector3f(p.vx[i], p.vy[i], p.vz[i]).norm());
  }
  // Uniform on [a, b]: mean (a + b) / 2, sd (b - a) / sqrt(12).
  Stats l = stats(life), s = stats(speed);
  const double n = 4000;
  EXPECT_NEAR(l.mean, 1.5, 4 * (2.0 / std::sqrt(12.0)) / std::sqrt(n));
  EXPECT_NEAR(l.sd, 2.0 / std::sqrt(12.0), 0.03);
  EXPECT_GE(l.lo, 0.5 - 1e-5);
  EXPECT_LE(l.hi, 2.5 + 1e-5);
  EXPECT_NEAR(s.mean, 4.0, 4 * (4.0 / std::sqrt(12.0)) / std::sqrt(n));
  EXPECT_GE(s.lo, 2.0 - 1e-4);
  EXPECT_LE(s.hi, 6.0 + 1e-4);
  // Deaths follow the lifetimes: after 1.5 s half are gone (uniform life on [0.5, 2.5]).
  for (int i = 1; i < 90; ++i) ps.step(kDt);
  EXPECT_NEAR(ps.count(id), 2000, 4 * std::sqrt(4000 * 0.25) + 70);  // noise + one step of deaths (1/120 of them)
}

TEST(Particles, ConeAndSpreadBoundTheDirections) {
  for (EmitterShape shape : {EmitterShape::Point, EmitterShape::Cone}) {
    EmitterDef d = quiet();
    d.shape = shape;
    d.radius_m = 0.3f;
    d.coneAngle_rad = shape == EmitterShape::Cone ? 0.4f : 0.0f;
    d.spread_rad = 0.2f;
    d.direction = Eigen::Vector3f(1, 1, 0);
    d.speedMin_mps = d.speedMax_mps = 5;
    d.bursts = {{0, 3000}};
    d.maxCount = 3000;
    ParticleSystem ps(11);
    ps.setGravity(Eigen::Vector3f::Zero());
    EmitterId id = ps.create(d, Eigen::Vector3f::Zero());
    ps.step(kDt);
    const ParticlePool& p = ps.get(id)->pool;
    const Eigen::Vector3f axis = Eigen::Vector3f(1, 1, 0).normalized();
    const float bound = d.coneAngle_rad + d.spread_rad;
    float widest = 0;
    for (std::uint32_t i = 0; i < p.count; ++i) {
      const float angle = std::acos(std::clamp(Eigen::Vector3f(p.vx[i], p.vy[i], p.vz[i]).normalized().dot(axis), -1.0f, 1.0f));
      widest = std::max(widest, angle);
    }
    EXPECT_LE(widest, bound + 1e-3f) << "shape " << int(shape);
    EXPECT_GE(widest, 0.9f * bound) << "the cone is filled out to its bound";
  }
}

TEST(Particles, SpreadCapIsUniformInSolidAngle) {
  // On a cap of half angle s, cos(theta) is uniform on [cos s, 1]: mean (1 + cos s) / 2.
  Random r{5};
  const float s = 0.8f;
  double sum = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) sum += ParticleSystem::sampleCap(r, Eigen::Vector3f::UnitZ(), s).z();
  const double sd = (1 - std::cos(s)) / std::sqrt(12.0) / std::sqrt(double(n));
  EXPECT_NEAR(sum / n, (1 + std::cos(s)) / 2, 4 * sd);
}

TEST(Particles, GravityKinematicsMatchTheIntegratorExactly) {
  // Semi-implicit Euler: v_k = v0 + k g dt, x_n = x0 + n v0 dt + g dt^2 n (n + 1) / 2.
  EmitterDef d = quiet();
  d.gravityScale = 1;
  d.direction = Eigen::Vector3f(1, 0, 0);
  d.speedMin_mps = d.speedMax_mps = 3;
  ParticleSystem ps(1);
  ps.setGravity(Eigen::Vector3f(0, -9.81f, 0));
  const Eigen::Vector3f x0(1, 20, -2);
  EmitterId id = ps.create(d, x0);
  ps.burst(id, 1);
  const int n = 90;
  for (int i = 0; i < n; ++i) ps.step(kDt);
  const ParticlePool& p = ps.get(id)->pool;
  ASSERT_EQ(p.count, 1u);
  const double dt = kDt;
  EXPECT_NEAR(p.px[0], 1 + n * 3 * dt, 1e-4);
  EXPECT_NEAR(p.py[0], 20 - 9.81 * dt * dt * n * (n + 1) / 2, 1e-4);
  EXPECT_NEAR(p.pz[0], -2, 1e-6);
  EXPECT_NEAR(p.vy[0], -9.81 * dt * n, 1e-4);
  EXPECT_NEAR(p.age_s[0], n * dt, 1e-5);
}

TEST(Particles, DragGivesTheDiscreteTerminalVelocity) {
  // v_{k+1} = (v_k + a dt) e^{-c dt}  ->  v_inf = a dt e^{-c dt} / (1 - e^{-c dt}) ~ a / c.
  EmitterDef d = quiet();
  d.gravityScale = 1;
  d.drag_per_s = 2;
  ParticleSystem ps(1);
  ps.setGravity(Eigen::Vector3f(0, -10, 0));
  EmitterId id = ps.create(d, Eigen::Vector3f::Zero());
  ps.burst(id, 1);
  for (int i = 0; i < 600; ++i) ps.step(kDt);
  const double e = std::exp(-2.0 * kDt);
  EXPECT_NEAR(ps.get(id)->pool.vy[0], -10 * kDt * e / (1 - e), 1e-3);
  EXPECT_NEAR(ps.get(id)->pool.vy[0], -5.0, 0.1);  // a / c, to O(c dt / 2) = 1.7 %
}

TEST(Particles, MaxCountIsNeverExceededAndOverflowIsCounted) {
  EmitterDef d = quiet();
  d.rate_per_s = 1000;
  d.maxCount = 50;
  ParticleSystem ps(1);
  EmitterId id = ps.create(d, Eigen::Vector3f::Zero());
  ps.burst(id, 80);
  int most = 0;
  for (int i = 0; i < 60; ++i) {
    ps.step(kDt);
    most = std::max(most, ps.count(id));
  }
  EXPECT_EQ(most, 50);
  // 80 + 1000 asked for in 1 s, 50 kept (lifetime 10 s: none died).
  EXPECT_EQ(ps.get(id)->dropped, 80u + 1000u - 50u);
}

TEST(Particles, LocalSpaceParticlesMoveWithTheEmitterWorldOnesStay) {
  EmitterDef d = quiet();
  d.bursts = {{0, 10}};
  d.shape = EmitterShape::Sphere;
  d.radius_m = 0.5f;
  ParticleSystem ps(2);
  ps.setGravity(Eigen::Vector3f::Zero());
  EmitterDef local = d;
  local.space = SimSpace::Local;
  EmitterId w = ps.create(d, Eigen::Vector3f::Zero());
  EmitterId l = ps.create(local, Eigen::Vector3f::Zero());
  ps.step(kDt);
  auto positions = [&](EmitterId id) {
    std::vector<Eigen::Vector3f> out;
    const ParticlePool& p = ps.get(id)->pool;
    for (std::uint32_t i = 0; i < p.count; ++i) out.emplace_back(p.px[i], p.py[i], p.pz[i]);
    return out;
  };
  auto before = positions(w), beforeLocal = positions(l);
  for (EmitterId id : {w, l}) ps.setPose(id, Eigen::Vector3f(5, 0, 0), Eigen::Quaternionf::Identity());
  ps.step(kDt);
  auto after = positions(w), afterLocal = positions(l);
  ASSERT_EQ(after.size(), 10u);
  for (std::size_t i = 0; i < after.size(); ++i) {
    // World space: at rest where they were born. Local space: stored in the
    // emitter's frame, unchanged, so in the world they moved 5 m with it.
    EXPECT_LT((after[i] - before[i]).norm(), 1e-6f);
    EXPECT_LT((afterLocal[i] - beforeLocal[i]).norm(), 1e-6f);
    EXPECT_LE(afterLocal[i].norm(), 0.5f + 1e-5f);
  }
}

TEST(Particles, AttachedEmitterFollowsItsAnchorAndInheritsVelocity) {
  EmitterDef d = quiet();
  d.inheritVelocity = 1;
  ParticleSystem ps(2);
  ps.setGravity(Eigen::Vector3f::Zero());
  EmitterId id = ps.create(d, Eigen::Vector3f::Zero());
  ps.attach(id, 42, Eigen::Vector3f(0, 0, 1));
  // A body at (2, 0, 0) spinning about y at 3 rad/s: the offset point moves at w x r = (3, 0, 0).
  ps.setAnchorState(id, Eigen::Vector3f(2, 0, 0), Eigen::Quaternionf::Identity(), Eigen::Vector3f(0, 1, 0),
                    Eigen::Vector3f(0, 3, 0));
  ps.burst(id, 1);
  ps.step(kDt);
  const Emitter* e = ps.get(id);
  EXPECT_TRUE(e->position_m.isApprox(Eigen::Vector3f(2, 0, 1)));
  EXPECT_NEAR(e->pool.vx[0], 3, 1e-5);
  EXPECT_NEAR(e->pool.vy[0], 1, 1e-5);
  ps.anchorLost(id);  // the body was removed: stop, particles finish
  EXPECT_TRUE(ps.isValid(id));
  for (int i = 0; i < 601 && ps.isValid(id); ++i) ps.step(kDt);
  EXPECT_FALSE(ps.isValid(id)) << "a stopped emitter frees itself when its last particle dies";
}

TEST(Particles, AFreeEmitterMovedByHandPassesOnItsVelocity) {
  EmitterDef d = quiet();
  d.inheritVelocity = 0.5f;
  ParticleSystem ps(2);
  ps.setGravity(Eigen::Vector3f::Zero());
  EmitterId id = ps.create(d, Eigen::Vector3f::Zero());
  ps.step(kDt);
  // Moved 0.1 m along x during the next step: 6 m/s, half of it inherited.
  ps.setPose(id, Eigen::Vector3f(0.1f, 0, 0), Eigen::Quaternionf::Identity());
  ps.burst(id, 1);
  ps.step(kDt);
  EXPECT_NEAR(ps.get(id)->pool.vx[0], 3.0f, 1e-4f);
}

TEST(Particles, ShapesFillTheirVolumesUniformly) {
  auto spawn = [](EmitterDef d) {
    d.rate_per_s = 0;
    d.speedMin_mps = d.speedMax_mps = 0;
    d.lifetimeMin_s = d.lifetimeMax_s = 10;
    d.bursts = {{0, 20000}};
    d.maxCount = 20000;
    auto ps = std::make_unique<ParticleSystem>(5);
    ps->setGravity(Eigen::Vector3f::Zero());
    EmitterId id = ps->create(d, Eigen::Vector3f(1, 2, 3));
    ps->step(kDt);
    std::vector<Eigen::Vector3f> out;
    const ParticlePool& p = ps->get(id)->pool;
    for (std::uint32_t i = 0; i < p.count; ++i) out.emplace_back(p.px[i] - 1, p.py[i] - 2, p.pz[i] - 3);
    return out;
  };
  const double n = 20000;
  // Box 2 x 4 x 0: uniform on each axis, variance size^2 / 12.
  EmitterDef box;
  box.shape = EmitterShape::Box;
  box.boxSize_m = Eigen::Vector3f(2, 4, 0);
  double vx = 0, vy = 0;
  for (const auto& p : spawn(box)) {
    EXPECT_LE(std::abs(p.x()), 1.0f + 1e-5f);
    EXPECT_LE(std::abs(p.y()), 2.0f + 1e-5f);
    EXPECT_NEAR(p.z(), 0.0f, 1e-5f);
    vx += p.x() * p.x() / n, vy += p.y() * p.y() / n;
  }
  EXPECT_NEAR(vx, 4.0 / 12, 0.02);
  EXPECT_NEAR(vy, 16.0 / 12, 0.06);
  // Ball of radius 2, uniform in volume: P(r < s) = (s / R)^3, E[r] = 3/4 R.
  EmitterDef ball;
  ball.shape = EmitterShape::Sphere;
  ball.radius_m = 2;
  double mean = 0;
  for (const auto& p : spawn(ball)) {
    EXPECT_LE(p.norm(), 2.0f + 1e-5f);
    mean += p.norm() / n;
  }
  EXPECT_NEAR(mean, 1.5, 4 * 0.39 / std::sqrt(n));  // sd of r: R sqrt(3/80) = 0.39 m
  // Cone base: a disc of radius 1 across the direction, E[r] = 2/3 R.
  EmitterDef cone;
  cone.shape = EmitterShape::Cone;
  cone.radius_m = 1;
  cone.direction = Eigen::Vector3f(0, 0, 1);
  mean = 0;
  for (const auto& p : spawn(cone)) {
    EXPECT_NEAR(p.z(), 0.0f, 1e-5f) << "on the disc across the direction";
    EXPECT_LE(p.norm(), 1.0f + 1e-5f);
    mean += p.norm() / n;
  }
  EXPECT_NEAR(mean, 2.0 / 3, 4 * 0.236 / std::sqrt(n));  // sd of r: R / sqrt(18)
}

TEST(Particles, DurationStopsAndBurstsComeAtTheirTimes) {
  EmitterDef d = quiet();
  d.lifetimeMin_s = d.lifetimeMax_s = 0.2f;
  d.bursts = {{0.51f, 20}, {0.0f, 10}};
  d.duration_s = 1.0f;
  ParticleSystem ps(4);
  EmitterId id = ps.create(d, Eigen::Vector3f::Zero());
  ps.step(kDt);
  EXPECT_EQ(ps.count(id), 10);
  for (int i = 1; i < 30; ++i) ps.step(kDt);  // t = 0.5 s: the 0.51 s burst not yet
  EXPECT_EQ(ps.count(id), 0);
  ps.step(kDt);
  EXPECT_EQ(ps.count(id), 20);
  for (int i = 0; i < 60 && ps.isValid(id); ++i) ps.step(kDt);
  EXPECT_FALSE(ps.isValid(id)) << "duration over and particles gone: freed";
}

TEST(Particles, SameSeedSameParticlesRemovedHandlesAreStale) {
  EmitterDef d = quiet();
  d.rate_per_s = 100;
  d.spread_rad = 1;
  d.speedMax_mps = 3;
  auto run = [&](std::uint64_t seed) {
    ParticleSystem ps(seed);
    EmitterId id = ps.create(d, Eigen::Vector3f::Zero());
    for (int i = 0; i < 30; ++i) ps.step(kDt);
    return std::vector<float>(ps.get(id)->pool.vx.begin(), ps.get(id)->pool.vx.begin() + ps.count(id));
  };
  EXPECT_EQ(run(9), run(9));
  EXPECT_NE(run(9), run(10));
  ParticleSystem ps(1);
  EmitterId a = ps.create(d, Eigen::Vector3f::Zero());
  EXPECT_TRUE(ps.remove(a));
  EXPECT_FALSE(ps.isValid(a));
  EmitterId b = ps.create(d, Eigen::Vector3f::Zero());
  EXPECT_EQ(a.index, b.index);
  EXPECT_FALSE(ps.isValid(a)) << "the old handle must not reach the slot's new emitter";
  EXPECT_EQ(ps.count(a), 0);
}

TEST(Particles, CurvesInterpolateAndValidationNamesTheField) {
  Curve1 c{{{0, 1}, {0.5f, 3}, {1, 0}}};
  EXPECT_FLOAT_EQ(c.eval(-1), 1);
  EXPECT_FLOAT_EQ(c.eval(0.25f), 2);
  EXPECT_FLOAT_EQ(c.eval(0.75f), 1.5f);
  EXPECT_FLOAT_EQ(c.eval(2), 0);
  EmitterDef d;
  EXPECT_TRUE(validate(d));
  d.lifetimeMin_s = 3;
  d.lifetimeMax_s = 1;
  auto s = validate(d);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().find("field 'lifetime'"), std::string::npos) << s.error();
  d = EmitterDef{};
  d.alpha = Curve1{{{0.5f, 1}, {0.2f, 0}}};
  s = validate(d);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().find("field 'alpha'"), std::string::npos) << s.error();
  EXPECT_NE(s.error().find("sorted"), std::string::npos) << s.error();
}

}  // namespace
}  // namespace tumble::particles
