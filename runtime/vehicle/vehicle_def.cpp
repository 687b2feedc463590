#include "vehicle/vehicle_def.h"

#include <algorithm>
#include <cmath>

namespace tumble::vehicle {
namespace {

std::string num(Real v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", double(v));
  return b;
}

/// Fails unless lo <= v <= hi (and finite); names field, unit and range.
Status inRange(const std::string& where, const std::string& field, Real v, Real lo, Real hi, const char* unit) {
  if (std::isfinite(v) && v >= lo && v <= hi) return Ok{};
  return makeError(where + ": " + field + " = " + num(v) + " " + unit + " must be between " + num(lo) + " and " +
                   num(hi));
}

}  // namespace

Real peakPower_W(const EngineDef& e) {
  Real best = 0;
  for (Real rpm = e.idleRpm; rpm <= e.maxRpm; rpm += 25)
    best = std::max(best, e.torque.eval(rpm) * rpm * 2 * kPi / 60);
  return best;
}

std::vector<DerivedAxle> deriveAxles(const VehicleDef& def) {
  const std::size_t n = def.axles.size();
  std::vector<DerivedAxle> out(n);
  const Real weight = def.chassis.mass_kg * kStandardGravity;
  // Static load: lever rule between the front-most and rear-most axle for
  // two axles; an even share otherwise (a 6x6 carries its load on a bogie).
  std::vector<Real> share(n, Real(1) / Real(n));
  if (n == 2) {
    const Real zc = def.chassis.centerOfMass_m.z();
    const Real z0 = def.axles[0].position_m.z(), z1 = def.axles[1].position_m.z();
    if (std::abs(z0 - z1) > Real(1e-3)) {
      share[0] = std::clamp((zc - z1) / (z0 - z1), Real(0.05), Real(0.95));
      share[1] = 1 - share[0];
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const AxleDef& a = def.axles[i];
    const SuspensionDef& s = a.suspension;
    DerivedAxle& d = out[i];
    d.staticLoad_N = weight * share[i] / 2;
    const Real cornerMass = d.staticLoad_N / kStandardGravity;
    const Real w = 2 * kPi * s.frequency_hz;
    d.stiffness_Npm = s.stiffness_Npm > 0 ? s.stiffness_Npm : cornerMass * w * w;
    const Real critical = 2 * std::sqrt(d.stiffness_Npm * cornerMass);
    d.bump_Nspm = s.bumpDamping_Nspm >= 0 ? s.bumpDamping_Nspm : s.bumpRatio * critical;
    d.rebound_Nspm = s.reboundDamping_Nspm >= 0 ? s.reboundDamping_Nspm : s.reboundRatio * critical;
    d.staticLength_m = s.restLength_m - d.staticLoad_N / d.stiffness_Npm;
  }
  return out;
}

Status validateVehicleDef(const VehicleDef& v, const std::string& where) {
  auto check = [&](const std::string& field, Real value, Real lo, Real hi, const char* unit) {
    return inRange(where, field, value, lo, hi, unit);
  };
  const ChassisDef& c = v.chassis;
  for (const Status& s : {check("chassis.mass", c.mass_kg, 1, 1e6f, "kg"),
                          check("chassis.size[1] (width)", c.size_m.x(), 0.05f, 50, "m"),
                          check("chassis.size[2] (height)", c.size_m.y(), 0.05f, 50, "m"),
                          check("chassis.size[3] (length)", c.size_m.z(), 0.05f, 50, "m"),
                          check("chassis.drag_area", c.dragArea_m2, 0, 100, "m^2"),
                          check("chassis.air_density", c.airDensity_kgpm3, 0, 100, "kg/m^3"),
                          check("chassis.friction", c.friction, 0, 10, ""),
                          check("chassis.restitution", c.restitution, 0, 1, "")})
    if (!s) return s;
  const SoundDef& snd = v.sound;
  for (const Status& s : {check("sound.cylinders", snd.cylinders, 1, 16, ""), check("sound.volume", snd.volume, 0, 4, ""),
                          check("sound.sample_rpm", snd.sampleRpm, 100, 30000, "rpm"),
                          check("sound.tyre_slip_threshold", snd.tyreSlipThreshold_mps, 0, 50, "m/s")})
    if (!s) return s;
  if (snd.cylinders != std::floor(snd.cylinders))
    return makeError(where + ": sound.cylinders must be a whole number (1..16), got " + std::to_string(snd.cylinders));
  // A camera eye belongs on the car: no coordinate beyond the chassis
  // length from the model's origin (a roof or bonnet may stand above the
  // collision box, so the box itself is not the bound).
  for (const auto& [field, eye] : {std::pair{"view.hood_eye", v.view.hoodEye_m}, {"view.cockpit_eye", v.view.cockpitEye_m}})
    if (!eye.allFinite() || eye.cwiseAbs().maxCoeff() > c.size_m.z())
      return makeError(where + ": " + field + " must be finite and on the car: {x, y, z} in the drawn model's frame, " +
                       "m, each within the chassis length (size[3]) of its origin");
  if (!c.centerOfMass_m.allFinite() || (c.centerOfMass_m.array().abs() > c.size_m.array()).any())
    return makeError(where + ": chassis.com must be finite and within the chassis size (m from the box centre)");
  if (v.axles.size() < 2 || v.axles.size() > 8)
    return makeError(where + ": axles must list 2 to 8 axles, front first (found " + std::to_string(v.axles.size()) +
                     ")");
  int driven = 0;
  Real share = 0;
  for (std::size_t i = 0; i < v.axles.size(); ++i) {
    const AxleDef& a = v.axles[i];
    const std::string p = "axles[" + std::to_string(i + 1) + "].";
    if (!a.position_m.allFinite() || a.position_m.x() <= 0)
      return makeError(where + ": " + p + "position must be finite with x > 0 (the left wheel; x is half the track, m)");
    const SuspensionDef& s = a.suspension;
    for (const Status& st : {check(p + "radius", a.wheelRadius_m, 0.05f, 5, "m"),
                             check(p + "width", a.wheelWidth_m, 0.01f, 3, "m"),
                             check(p + "inertia", a.wheelInertia_kgm2, 0.01f, 1000, "kg m^2"),
                             check(p + "brake", a.brakeTorque_Nm, 0, 1e6f, "N m"),
                             check(p + "handbrake", a.handbrakeTorque_Nm, 0, 1e6f, "N m"),
                             check(p + "drive_share", a.driveShare, 0, 1, ""),
                             check(p + "differential.bias", a.lsdBias, 1, 100, ""),
                             check(p + "suspension.travel", s.travel_m, 0.01f, 3, "m"),
                             check(p + "suspension.rest_length", s.restLength_m, 0.01f, 6, "m"),
                             check(p + "suspension.stiffness", s.stiffness_Npm, 0, 1e8f, "N/m"),
                             check(p + "suspension.frequency", s.frequency_hz, 0.2f, 10, "Hz"),
                             check(p + "suspension.bump_ratio", s.bumpRatio, 0, 5, ""),
                             check(p + "suspension.rebound_ratio", s.reboundRatio, 0, 5, ""),
                             check(p + "suspension.bump", std::max<Real>(s.bumpDamping_Nspm, 0), 0, 1e7f, "N s/m"),
                             check(p + "suspension.rebound", std::max<Real>(s.reboundDamping_Nspm, 0), 0, 1e7f,
                                   "N s/m"),
                             check(p + "suspension.anti_roll", s.antiRoll_Npm, 0, 1e8f, "N/m")})
      if (!st) return st;
    if (a.driven) ++driven, share += a.driveShare;
  }
  if (driven == 0) return makeError(where + ": no axle has driven = true; at least one must be driven");
  if (share > 0 && std::abs(share - 1) > 0.01f)
    return makeError(where + ": drive_share of the driven axles adds up to " + num(share) +
                     "; give all of them (summing to 1) or none (equal shares)");
  // The car must rest between its stops on level ground.
  auto derived = deriveAxles(v);
  for (std::size_t i = 0; i < v.axles.size(); ++i) {
    const Real l = derived[i].staticLength_m, travel = v.axles[i].suspension.travel_m;
    if (l <= Real(0.1) * travel || l >= Real(0.95) * travel)
      return makeError(where + ": axles[" + std::to_string(i + 1) + "].suspension: at rest the spring length would be " +
                       num(l) + " m of a " + num(travel) + " m travel (rest_length - load / stiffness); it must stay "
                       "between 10% and 95% of travel, so change rest_length, stiffness or frequency");
  }
  if (auto s = v.tyre.longitudinal.validate(where + ": tyre.longitudinal", 0); !s) return s;
  if (auto s = v.tyre.lateral.validate(where + ": tyre.lateral", 0); !s) return s;
  if (v.tyre.longitudinal.maxY() <= 0 || v.tyre.lateral.maxY() <= 0)
    return makeError(where + ": tyre curves must reach a friction above 0");
  for (const Status& s : {check("tyre.rolling_resistance", v.tyre.rollingResistance, 0, 1, ""),
                          check("tyre.soft_ground_drag", v.tyre.softGroundDrag, 0, 2, "")})
    if (!s) return s;
  const EngineDef& e = v.engine;
  if (auto s = e.torque.validate(where + ": engine.torque", 0); !s) return s;
  for (const Status& s : {check("engine.idle_rpm", e.idleRpm, 100, 30000, "rpm"),
                          check("engine.max_rpm", e.maxRpm, e.idleRpm + 100, 40000, "rpm"),
                          check("engine.launch_rpm", e.launchRpm, e.idleRpm, e.maxRpm, "rpm"),
                          check("engine.inertia", e.inertia_kgm2, 0.001f, 100, "kg m^2"),
                          check("engine.braking_torque", e.brakingTorque_Nm, 0, 1e5f, "N m")})
    if (!s) return s;
  const GearboxDef& g = v.gearbox;
  if (g.ratios.empty() || g.ratios.size() > 12)
    return makeError(where + ": gearbox.ratios must list 1 to 12 forward ratios, e.g. {3.5, 2.1, 1.4, 1.0}");
  for (std::size_t i = 0; i < g.ratios.size(); ++i)
    if (auto s = check("gearbox.ratios[" + std::to_string(i + 1) + "]", g.ratios[i], 0.05f, 50, ""); !s) return s;
  for (const Status& s : {check("gearbox.reverse", g.reverseRatio, 0.05f, 50, ""),
                          check("gearbox.final_drive", g.finalDrive, 0.1f, 50, ""),
                          check("gearbox.efficiency", g.efficiency, 0.1f, 1, ""),
                          check("gearbox.shift_up_rpm", g.shiftUpRpm, e.idleRpm, e.maxRpm, "rpm"),
                          check("gearbox.shift_down_rpm", g.shiftDownRpm, e.idleRpm, g.shiftUpRpm, "rpm"),
                          check("gearbox.shift_time", g.shiftTime_s, 0, 5, "s"),
                          check("steering.max_angle", v.steering.maxAngle_rad, 0, 1.4f, "rad"),
                          check("steering.speed_sensitivity", v.steering.speedSensitivity_spm, 0, 10, "s/m"),
                          check("steering.rate", v.steering.rate_radps, 0.1f, 100, "rad/s")})
    if (!s) return s;
  return Ok{};
}

}  // namespace tumble::vehicle
