// Vehicle definitions: bad data gives a message naming the field.
#include <gtest/gtest.h>

#include "vehicle_fixture.h"

namespace tumble::vehicle::test {
namespace {

TEST(VehicleDef, DefaultTestCarIsValid) { EXPECT_TRUE(validateVehicleDef(testCar(), "car.lua").ok()); }

TEST(VehicleDef, ErrorsNameTheField) {
  VehicleDef d = testCar();
  d.axles[1].suspension.travel_m = 0;
  auto s = validateVehicleDef(d, "car.lua");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("car.lua: axles[2].suspension.travel"), std::string::npos) << s.error();

  d = testCar();
  d.engine.torque = Curve({{1000, 100}, {900, 120}});
  s = validateVehicleDef(d, "car.lua");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("engine.torque point 2"), std::string::npos) << s.error();

  d = testCar();
  d.axles[0].suspension.restLength_m = Real(0.05);  // would sit on the bump stops
  s = validateVehicleDef(d, "car.lua");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("axles[1].suspension"), std::string::npos) << s.error();

  d = testCar();
  for (AxleDef& a : d.axles) a.driven = false;
  EXPECT_FALSE(validateVehicleDef(d, "car.lua").ok());
}

TEST(VehicleDef, SpringRateFromFrequencyAndStaticLoad) {
  VehicleDef d = testCar();
  auto axles = deriveAxles(d);
  // Lever rule: the centre of mass 0.1 m ahead of centre, axles at +-1.3 m.
  const Real front = 1200 * kStandardGravity * (Real(0.1) + Real(1.3)) / Real(2.6) / 2;
  EXPECT_NEAR(axles[0].staticLoad_N, front, 1);
  const Real m = front / kStandardGravity, w = 2 * kPi * d.axles[0].suspension.frequency_hz;
  EXPECT_NEAR(axles[0].stiffness_Npm, m * w * w, 1);
  EXPECT_NEAR(axles[0].staticLoad_N + axles[1].staticLoad_N, 600 * kStandardGravity, 1);
}

TEST(VehicleDef, PeakPowerFromTorqueCurve) {
  EngineDef e;
  e.torque = Curve({{1000, 100}, {6000, 100}});
  e.idleRpm = 1000;
  e.maxRpm = 6000;
  EXPECT_NEAR(peakPower_W(e), 100 * 6000 * 2 * kPi / 60, 1);
}

}  // namespace
}  // namespace tumble::vehicle::test
