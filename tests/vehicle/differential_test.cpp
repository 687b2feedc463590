// Open and limited-slip differentials against analytic answers: a rear-drive
// car with its left driven wheel on ice (mu_low) and the right on dry ground,
// full throttle from rest in first gear; and with the left driven wheel in
// the air. An open differential gives both wheels the same torque, so the
// car accelerates at about 2 mu_low N / m and the slipping wheel spins up to
// the rev limiter; a Torsen-style limited slip of bias B gives the gripping
// wheel B times the slipping wheel's torque: about (1 + B) mu_low N / m.
#include "vehicle_fixture.h"

namespace tumble::vehicle::test {
namespace {

constexpr Real kLowMu = Real(0.1);   // ice
constexpr Real kBias = Real(2.5);
constexpr Real kStripX = Real(0.3);  // left wheels (x = +0.75) on the ice, right ones (x = -0.75) on dry ground

/// testCar() with rear drive instead of front drive; no drag and no rolling
/// resistance (on any ground), so the tyres and inertias alone set the motion.
VehicleDef rearDrive(Differential diff) {
  VehicleDef d = testCar();
  d.axles[0].driven = false;
  d.axles[1].driven = true;
  d.axles[1].differential = diff;
  d.axles[1].lsdBias = kBias;
  d.chassis.dragArea_m2 = 0;
  d.tyre.rollingResistance = 0;
  d.tyre.softGroundDrag = 0;
  return d;
}

/// A static slab with its top at y = 0 over x in [x0, x1], z in [z0, z1].
void addSlab(physics::World& w, Real x0, Real x1, Real z0, Real z1, Real friction) {
  physics::BodyDef g;
  g.type = physics::BodyType::Static;
  g.shape = physics::Shape::box(Vec3((x1 - x0) / 2, Real(0.5), (z1 - z0) / 2));
  g.position_m = Vec3((x0 + x1) / 2, Real(-0.5), (z0 + z1) / 2);
  g.friction = friction;
  w.createBody(g).value();
}

void splitMu(physics::World& w) {
  addSlab(w, kStripX, 20, -20, 100, kLowMu);
  addSlab(w, -20, kStripX, -20, 100, 1);
}
void dry(physics::World& w) { addSlab(w, -20, 20, -20, 100, 1); }
/// Dry ground with a pit under the rear left wheel (which hangs at full droop).
void pitUnderRearLeft(physics::World& w) {
  addSlab(w, -20, kStripX, -20, 100, 1);
  addSlab(w, kStripX, 20, Real(-0.4), 100, 1);
}

struct Launch {
  Real accel_mps2 = 0;      ///< mean forward acceleration over the window
  Real loadLeft_N = 0;      ///< mean load on the rear left wheel over the window
  Real torqueLeft_Nm = 0;   ///< mean drive torque the differential gave each rear wheel over the window
  Real torqueRight_Nm = 0;
  Real spinLeft_radps = 0, spinRight_radps = 0;  ///< at the end
  Real speed_mps = 0;       ///< at the end
  Real rpm = 0;             ///< at the end
  bool leftContact = false; ///< the rear left tyre touched the ground during the window
};

/// Full throttle in first gear from rest; measures over [t0, t1] s.
template <typename Ground>
Launch launch(const VehicleDef& d, Ground&& ground, Real t0, Real t1) {
  physics::World w;
  w.settings().enableSleep = false;
  ground(w);
  VehicleSystem s(w);
  VehicleId car = s.spawn(d, Vec3::Zero(), 0).value();
  run(s, Real(0.5));  // settle on the springs
  VehicleControls c;
  c.throttle = 1;
  c.gear = 1;
  s.setControls(car, c);
  run(s, t0);
  Launch out;
  const Real v0 = s.telemetry(car).speed_mps;
  const int steps = int(std::lround((t1 - t0) / kDt));
  for (int i = 0; i < steps; ++i) {
    s.step(kDt);
    out.loadLeft_N += s.wheel(car, 2).load_N / Real(steps);
    out.torqueLeft_Nm += s.wheel(car, 2).driveTorque_Nm / Real(steps);
    out.torqueRight_Nm += s.wheel(car, 3).driveTorque_Nm / Real(steps);
    out.leftContact |= s.wheel(car, 2).contact;
  }
  out.speed_mps = s.telemetry(car).speed_mps;
  out.accel_mps2 = (out.speed_mps - v0) / (t1 - t0);
  out.spinLeft_radps = s.wheel(car, 2).spin_radps;
  out.spinRight_radps = s.wheel(car, 3).spin_radps;
  out.rpm = s.telemetry(car).rpm;
  return out;
}

/// Carrier speed at the rev limiter in first gear, rad/s.
Real limiterCarrier(const VehicleDef& d) {
  return d.engine.maxRpm * 2 * kPi / 60 / (d.gearbox.ratios[0] * d.gearbox.finalDrive);
}

// Window from 2 s to 4 s: the slipping wheel has taken the engine to the
// limiter, so the carrier turns at a constant speed (w_l + w_r = 2 w_c):
// the left wheel slows as fast as the right one speeds up. With I the wheel
// inertia and r its radius, F_l = mu_low mu_slide N_l (the tyre slides far
// beyond its peak: the curve's last value), and the front wheels roll:
//   open:  T_l = T_r       ->  a = 2 F_l / (m + 4 I / r^2)
//   LSD:   T_r = B T_l     ->  a = (1 + B) F_l / (m + (B + 3) I / r^2)
// The tolerance (2 %) covers the load transfer and yaw the asymmetric push
// causes (the mean load on the wheel is measured, not assumed).
TEST(Differential, OpenOnSplitMuAcceleratesAtTwiceTheSlippingWheelsGrip) {
  const VehicleDef d = rearDrive(Differential::Open);
  const Launch l = launch(d, splitMu, 2, 4);
  const Real m = d.chassis.mass_kg, I = d.axles[1].wheelInertia_kgm2, r = d.axles[1].wheelRadius_m;
  const Real Fl = kLowMu * d.tyre.longitudinal.eval(100) * l.loadLeft_N;
  const Real expected = 2 * Fl / (m + 4 * I / (r * r));
  EXPECT_NEAR(l.accel_mps2, expected, 0.02 * expected);
  EXPECT_LE(l.accel_mps2, 2 * kLowMu * d.tyre.longitudinal.maxY() * l.loadLeft_N / m) << "beyond 2 mu_low N / m";
  // Equal torques, the slipping wheel spun up and the engine on its limiter.
  EXPECT_NEAR(l.torqueLeft_Nm, l.torqueRight_Nm, 1e-3 * std::abs(l.torqueRight_Nm));
  EXPECT_NEAR(l.rpm, d.engine.maxRpm, 0.01 * d.engine.maxRpm);
  EXPECT_NEAR(l.spinLeft_radps + l.spinRight_radps, 2 * limiterCarrier(d), 0.02 * limiterCarrier(d));
  EXPECT_GT(l.spinLeft_radps, 10 * l.spinRight_radps);
}

TEST(Differential, LimitedSlipOnSplitMuGivesTheGrippingWheelBiasTimesTheTorque) {
  const VehicleDef d = rearDrive(Differential::LimitedSlip);
  const Launch l = launch(d, splitMu, 2, 4);
  const Real m = d.chassis.mass_kg, I = d.axles[1].wheelInertia_kgm2, r = d.axles[1].wheelRadius_m;
  const Real Fl = kLowMu * d.tyre.longitudinal.eval(100) * l.loadLeft_N;
  const Real expected = (1 + kBias) * Fl / (m + (kBias + 3) * I / (r * r));
  EXPECT_NEAR(l.accel_mps2, expected, 0.02 * expected);
  EXPECT_NEAR(l.torqueRight_Nm / l.torqueLeft_Nm, kBias, 0.02 * kBias);
  // Against the open differential on the same ground: about (1 + B) / 2 times the acceleration.
  const Launch open = launch(rearDrive(Differential::Open), splitMu, 2, 4);
  EXPECT_NEAR(l.accel_mps2 / open.accel_mps2, (1 + kBias) / 2, 0.06 * (1 + kBias) / 2);
}

TEST(Differential, OnDryGroundOpenAndLimitedSlipAccelerateAlike) {
  const Launch open = launch(rearDrive(Differential::Open), dry, 1, 3);
  const Launch lsd = launch(rearDrive(Differential::LimitedSlip), dry, 1, 3);
  EXPECT_GT(open.accel_mps2, 2) << "the car should pull away properly on dry ground";
  EXPECT_NEAR(lsd.accel_mps2, open.accel_mps2, 0.01 * open.accel_mps2);
  EXPECT_NEAR(open.spinLeft_radps, open.spinRight_radps, 0.01 * open.spinRight_radps) << "no wheel slips";
}

// One driven wheel in the air: with an open differential both wheels get
// the torque that spins the airborne one up, T = I dw_l/dt, so the whole
// angular impulse the ground wheel passes on is I w_l (a few hundred N s):
// the car creeps at most v <= I w_l / (r m) while the free wheel and the
// engine go to the limiter. A limited slip gives the ground wheel B times
// that: the car moves about B times as fast.
TEST(Differential, OneDrivenWheelInTheAirOpenSpinsItLimitedSlipMoves) {
  VehicleDef open = rearDrive(Differential::Open);
  open.chassis.centerOfMass_m = Vec3(Real(-0.3), 0, Real(0.4));  // stands on the other three wheels
  VehicleDef lsd = open;
  lsd.axles[1].differential = Differential::LimitedSlip;
  const Real m = open.chassis.mass_kg, I = open.axles[1].wheelInertia_kgm2, r = open.axles[1].wheelRadius_m;

  const Launch o = launch(open, pitUnderRearLeft, 1, 3);
  EXPECT_FALSE(o.leftContact) << "the rear left wheel should hang in the pit";
  EXPECT_NEAR(o.rpm, open.engine.maxRpm, 0.01 * open.engine.maxRpm);
  EXPECT_NEAR(o.spinLeft_radps + o.spinRight_radps, 2 * limiterCarrier(open), 0.02 * limiterCarrier(open));
  const Real creep = I * o.spinLeft_radps / (r * m);
  EXPECT_LE(o.speed_mps, 1.02 * creep) << "open: the car should barely move";
  EXPECT_GE(o.speed_mps, 0.8 * creep);

  const Launch l = launch(lsd, pitUnderRearLeft, 1, 3);
  EXPECT_FALSE(l.leftContact);
  EXPECT_GT(l.speed_mps, 0.7 * kBias * o.speed_mps) << "limited slip: the ground wheel should drive the car";
}

}  // namespace
}  // namespace tumble::vehicle::test
