// Vehicle physics against analytic answers: rest without creep, the
// handbrake on a 10 degree slope, top speed from the torque curve and
// gearing, braking distance from brake torque and mu, lateral acceleration
// bounded by mu g, 300 km/h over hills, parameters changed while running.
#include "vehicle_fixture.h"

namespace tumble::vehicle::test {
namespace {

TEST(Vehicle, RestsWithoutCreepOrJitter) {
  physics::World w;
  w.settings().enableSleep = false;  // the tyre model must hold the car, not sleep
  addGround(w);
  VehicleSystem s(w);
  VehicleId car = s.spawn(testCar(), Vec3::Zero(), 0).value();
  run(s, 3);
  const Vec3 p0 = position(s, w, car);
  run(s, 5);
  const Vec3 p1 = position(s, w, car);
  EXPECT_LT((p1 - p0).norm(), 1e-3) << "moved while standing";
  for (int i = 0; i < s.wheelCount(car); ++i) {
    const WheelTelemetry& t = s.wheel(car, i);
    EXPECT_TRUE(t.contact) << "wheel " << i;
    EXPECT_LT(std::abs(t.spin_radps * t.radius_m), 0.01) << "wheel " << i << " turns (m/s)";
  }
  EXPECT_LT(w.body(s.chassis(car)).linearVelocity_mps.norm(), 0.01);
  // Resting on its springs: the loads carry the weight.
  Real load = 0;
  for (int i = 0; i < s.wheelCount(car); ++i) load += s.wheel(car, i).load_N;
  EXPECT_NEAR(load, 1200 * kStandardGravity, 0.01 * 1200 * kStandardGravity);
}

TEST(Vehicle, HandbrakeHoldsOnTenDegreeSlope) {
  // A 10 degree slope: gravity tilted by 10 degrees about X over flat ground
  // (the same physics, and the ground stays a plane). The car faces uphill.
  physics::World w;
  w.settings().enableSleep = false;
  const Real a = 10 * kPi / 180;
  w.settings().gravity_mps2 = kStandardGravity * Vec3(0, -std::cos(a), -std::sin(a));
  addGround(w);
  VehicleSystem s(w);
  VehicleId car = s.spawn(testCar(), Vec3::Zero(), 0).value();
  VehicleControls c;
  c.handbrake = 1;
  s.setControls(car, c);
  run(s, 2);  // settle on the springs
  const Vec3 p0 = position(s, w, car);
  run(s, 10);
  const Vec3 p1 = position(s, w, car);
  EXPECT_LT((p1 - p0).norm(), 0.01) << "slid " << (p1 - p0).norm() << " m in 10 s";
  // Without the handbrake it rolls away (the test can fail).
  s.setControls(car, VehicleControls{});
  run(s, 3);
  EXPECT_GT((position(s, w, car) - p1).norm(), 1.0);
}

/// Speed where the drive force in gear `gear` equals drag + rolling resistance.
Real steadySpeed(const VehicleDef& d, std::size_t gear) {
  const AxleDef& a = d.axles[0];
  const Real G = d.gearbox.ratios[gear] * d.gearbox.finalDrive;
  auto excess = [&](Real v) {
    const Real rpm = v / a.wheelRadius_m * G * 60 / (2 * kPi);
    const Real drive = rpm > d.engine.maxRpm ? 0 : d.engine.torque.eval(rpm) * G * d.gearbox.efficiency / a.wheelRadius_m;
    const Real drag = Real(0.5) * d.chassis.airDensity_kgpm3 * d.chassis.dragArea_m2 * v * v;
    return drive - drag - d.tyre.rollingResistance * d.chassis.mass_kg * kStandardGravity;
  };
  Real lo = 1, hi = 200;
  for (int i = 0; i < 60; ++i) (excess((lo + hi) / 2) > 0 ? lo : hi) = (lo + hi) / 2;
  return lo;
}

TEST(Vehicle, TopSpeedFollowsTorqueCurveAndGearing) {
  // Rev limited: no drag, no rolling resistance; top gear tops out where
  // the engine reaches max_rpm: v = w_max r / (G_top G_final).
  VehicleDef d = testCar();
  d.chassis.dragArea_m2 = 0;
  d.tyre.rollingResistance = 0;
  d.gearbox.ratios = {Real(3.2), Real(1.9), Real(1.3)};
  physics::World w;
  addGround(w);
  VehicleSystem s(w);
  VehicleId car = s.spawn(d, Vec3::Zero(), 0).value();
  VehicleControls c;
  c.throttle = 1;
  s.setControls(car, c);
  for (int i = 0; i < 60 * 40; ++i) {
    autoShift(s, car);
    s.step(kDt);
  }
  const Real limit = d.engine.maxRpm * 2 * kPi / 60 * d.axles[0].wheelRadius_m / (Real(1.3) * d.gearbox.finalDrive);
  EXPECT_EQ(s.telemetry(car).gear, 3);
  EXPECT_NEAR(s.telemetry(car).speed_mps, limit, 0.02 * limit);

  // Drag limited: the default car settles where drive force = drag +
  // rolling resistance, in the gear where that speed is highest (here not
  // the top gear: the engine's torque falls off before it gets there).
  VehicleDef dd = testCar();
  dd.chassis.dragArea_m2 = Real(1.2);
  physics::World w2;
  addGround(w2);
  VehicleSystem s2(w2);
  VehicleId car2 = s2.spawn(dd, Vec3::Zero(), 0).value();
  s2.setControls(car2, c);
  for (int i = 0; i < 60 * 90; ++i) {
    autoShift(s2, car2);
    s2.step(kDt);
  }
  Real expected = 0;
  for (std::size_t g = 0; g < dd.gearbox.ratios.size(); ++g) expected = std::max(expected, steadySpeed(dd, g));
  EXPECT_NEAR(s2.telemetry(car2).speed_mps, expected, 0.03 * expected);
}

/// Brakes from about v0 (m/s); returns the distance to standstill (m) and
/// the speed when the brakes came on.
std::pair<Real, Real> brakingDistance(const VehicleDef& d, Real v0) {
  physics::World w;
  w.settings().enableSleep = false;
  addGround(w);
  VehicleSystem s(w);
  VehicleId car = s.spawn(d, Vec3::Zero(), 0).value();
  VehicleControls c;
  c.gear = 0;  // neutral: no engine braking
  s.setControls(car, c);
  run(s, 1);
  w.setLinearVelocity(s.chassis(car), Vec3(0, 0, v0));
  run(s, Real(0.5));  // wheels spin up to road speed
  const Vec3 p0 = position(s, w, car);
  const Real v = s.telemetry(car).speed_mps;
  c.brake = 1;
  s.setControls(car, c);
  for (int i = 0; i < 60 * 30 && w.body(s.chassis(car)).linearVelocity_mps.norm() > 0.01; ++i) s.step(kDt);
  return {(position(s, w, car) - p0).norm(), v};
}

TEST(Vehicle, BrakingDistanceFromBrakeTorqueAndMu) {
  VehicleDef d = testCar();
  d.chassis.dragArea_m2 = 0;
  d.tyre.rollingResistance = 0;
  const Real r = d.axles[0].wheelRadius_m, g = kStandardGravity;
  // Brake limited: total torque / r below mu m g, so d = v^2 / (2 a) with
  // a = sum(T) / r / (m + sum(I) / r^2) (the brakes also stop the wheels).
  for (AxleDef& a : d.axles) a.brakeTorque_Nm = 400;
  const Real a = 4 * 400 / r / (d.chassis.mass_kg + 4 * d.axles[0].wheelInertia_kgm2 / (r * r));
  auto [dist1, v1] = brakingDistance(d, 25);
  EXPECT_NEAR(v1, 25, 1);
  EXPECT_NEAR(dist1, v1 * v1 / (2 * a), 0.03 * v1 * v1 / (2 * a));
  // Grip limited: strong brakes lock the wheels; the tyres slide at their
  // sliding friction (0.8), never better than their peak (1.1).
  for (AxleDef& ax : d.axles) ax.brakeTorque_Nm = 5000;
  auto [dist2, v2] = brakingDistance(d, 25);
  EXPECT_GE(dist2, v2 * v2 / (2 * Real(1.1) * g) * Real(0.97));
  EXPECT_LE(dist2, v2 * v2 / (2 * Real(0.8) * g) * Real(1.03));
}

TEST(Vehicle, SteadyCorneringKeepsLateralAccelerationBelowMuG) {
  physics::World w;
  addGround(w);
  VehicleSystem s(w);
  VehicleDef d = testCar();
  VehicleId car = s.spawn(d, Vec3::Zero(), 0).value();
  Real maxLat = 0;
  const Real target = 20;  // m/s
  for (int i = 0; i < 60 * 25; ++i) {
    const Real t = i * kDt;
    VehicleControls c = s.controls(car);
    const Real v = s.telemetry(car).speed_mps;
    c.throttle = std::clamp<Real>((target - v) * Real(0.5), 0, 1);
    c.steer = t > 10 ? Real(-1) : 0;  // full left after reaching speed
    s.setControls(car, c);
    autoShift(s, car);
    s.step(kDt);
    const physics::Body& b = w.body(s.chassis(car));
    const Vec3 vel = b.linearVelocity_mps;
    const Real lat = std::abs(b.angularVelocity_radps.y() * Vec2(vel.x(), vel.z()).norm());
    if (t > 12) maxLat = std::max(maxLat, lat);
  }
  const Real muPeak = d.tyre.lateral.maxY();
  EXPECT_LE(maxLat, muPeak * kStandardGravity * Real(1.05));
  EXPECT_GT(maxLat, Real(0.3) * kStandardGravity) << "the car did not corner";
}

TEST(Vehicle, LowSurfaceFrictionLimitsTraction) {
  // On mud (friction 0.3) the tyres cannot push harder than 0.3 * 1.1 g.
  physics::World w;
  addGround(w, Real(0.3));
  VehicleSystem s(w);
  VehicleId car = s.spawn(testCar(), Vec3::Zero(), 0).value();
  VehicleControls c;
  c.throttle = 1;
  s.setControls(car, c);
  run(s, 1);
  const Real v0 = s.telemetry(car).speed_mps;
  run(s, 2);
  const Real accel = (s.telemetry(car).speed_mps - v0) / 2;
  EXPECT_LE(accel, Real(0.3 * 1.1) * kStandardGravity * Real(0.6) * Real(1.05));  // front drive: ~60% of the weight
  EXPECT_GT(accel, 0.5);
  EXPECT_GT(std::abs(s.wheel(car, 0).slipRatio), 0.1) << "driven wheels should spin on mud";
  EXPECT_NEAR(s.wheel(car, 0).surfaceFriction, 0.3, 1e-6);
}

TEST(Vehicle, ParameterChangeWhileRunningChangesBehaviour) {
  physics::World w;
  addGround(w);
  VehicleSystem s(w);
  VehicleDef d = testCar();
  VehicleId car = s.spawn(d, Vec3::Zero(), 0).value();
  VehicleControls c;
  c.throttle = Real(0.5);
  c.gear = 2;
  s.setControls(car, c);
  run(s, 3);
  Real v0 = s.telemetry(car).speed_mps;
  run(s, 1);
  const Real before = s.telemetry(car).speed_mps - v0;
  d.engine.torque = Curve({{1000, 40}, {4000, 50}, {6500, 40}});  // a third of the torque
  ASSERT_TRUE(s.setDef(car, d).ok());
  v0 = s.telemetry(car).speed_mps;
  run(s, 1);
  const Real after = s.telemetry(car).speed_mps - v0;
  EXPECT_LT(after, before * Real(0.6));
  EXPECT_GT(after, 0);
  d.axles[0].suspension.travel_m = -1;
  EXPECT_FALSE(s.setDef(car, d).ok());
}

// Chassis inertia given as principal moments (chassis.inertia = "mesh" puts
// the mesh's there): the body has them, a free yaw torque turns it at
// tau / I_yy, a heavier chassis scales them, and moments no rigid body can
// have are refused.
TEST(Vehicle, GivenChassisInertiaIsUsedAndScalesWithMass) {
  physics::World w;
  w.settings().gravity_mps2 = Vec3::Zero();
  VehicleSystem s(w);
  VehicleDef def = testCar();
  def.chassis.inertia_kgm2 = Vec3(1500, 1700, 320);
  auto spawned = s.spawn(def, Vec3(0, 5, 0), 0);
  ASSERT_TRUE(spawned.ok()) << spawned.error();
  const VehicleId car = spawned.value();
  const physics::BodyId body = s.chassis(car);
  EXPECT_LT((w.body(body).inertiaLocal_kgm2 - def.chassis.inertia_kgm2).norm(), 1e-3);
  // Free in the air: a yaw torque of 300 N m for 0.5 s spins it to tau t / I_yy.
  for (int i = 0; i < 30; ++i) {
    w.applyTorque(body, Vec3(0, 300, 0));
    s.beforeStep(Real(1.0 / 60));
    w.step(Real(1.0 / 60));
  }
  EXPECT_NEAR(w.body(body).angularVelocity_radps.y(), 300 * 0.5 / 1700, 0.02 * 300 * 0.5 / 1700);

  VehicleDef heavier = s.def(car);
  heavier.chassis.mass_kg *= 2;
  ASSERT_TRUE(s.setDef(car, heavier, "car.lua").ok());
  EXPECT_LT((w.body(s.chassis(car)).inertiaLocal_kgm2 - 2 * def.chassis.inertia_kgm2).norm(), 1e-2);

  VehicleDef impossible = testCar();
  impossible.chassis.inertia_kgm2 = Vec3(100, 100, 500);  // 500 > 100 + 100
  auto refused = s.spawn(impossible, Vec3(5, 0, 0), 0);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().find("triangle inequality"), std::string::npos) << refused.error();
}

}  // namespace
}  // namespace tumble::vehicle::test
