#pragma once
// Fixture for the vehicle tests: a car definition close to mods/base's
// hatchback, a flat ground plane, and helpers to drive and measure.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/world.h"
#include "vehicle/vehicle_system.h"

namespace tumble::vehicle::test {

constexpr Real kDt = Real(1.0 / 60.0);

inline VehicleDef testCar() {
  VehicleDef d;
  d.name = "test car";
  d.chassis.mass_kg = 1200;
  d.chassis.size_m = Vec3(Real(1.7), Real(0.6), Real(4.0));
  d.chassis.centerOfMass_m = Vec3(0, 0, Real(0.1));
  AxleDef front;
  front.position_m = Vec3(Real(0.75), Real(-0.2), Real(1.3));
  front.steered = true;
  front.driven = true;
  front.brakeTorque_Nm = 1800;
  AxleDef rear = front;
  rear.position_m.z() = Real(-1.3);
  rear.steered = false;
  rear.driven = false;
  rear.brakeTorque_Nm = 1200;
  rear.handbrakeTorque_Nm = 2000;
  d.axles = {front, rear};
  return d;
}

inline physics::BodyId addGround(physics::World& w, Real friction = 1) {
  physics::BodyDef g;
  g.type = physics::BodyType::Static;
  g.shape = physics::Shape::plane();
  g.friction = friction;
  return w.createBody(g).value();
}

inline void run(VehicleSystem& s, Real seconds) {
  const int steps = int(std::lround(seconds / kDt));
  for (int i = 0; i < steps; ++i) s.step(kDt);
}

/// Automatic gearbox like scripts/tumble/drive.lua's, for tests in C++.
inline void autoShift(VehicleSystem& s, VehicleId id) {
  VehicleControls c = s.controls(id);
  const VehicleTelemetry& t = s.telemetry(id);
  const GearboxDef& g = s.def(id).gearbox;
  if (t.shifting || c.gear < 1) return;
  if (t.rpm > g.shiftUpRpm && c.gear < int(g.ratios.size())) ++c.gear;
  else if (t.rpm < g.shiftDownRpm && c.gear > 1) --c.gear;
  s.setControls(id, c);
}

inline Vec3 position(const VehicleSystem& s, const physics::World& w, VehicleId id) {
  return w.body(s.chassis(id)).position_m;
}

}  // namespace tumble::vehicle::test
