#pragma once
// VehicleDef: everything that defines a wheeled vehicle, with units. Filled
// from a mod's vehicles/*.lua (script/bind_vehicle.cpp) or in C++ (tests);
// validateVehicleDef checks it and derives the spring rates.
//
// Chassis frame: origin at the centre of the chassis box, +Z forward, +Y up,
// +X to the left (right-handed). Angles in radians.
//
// Index: Curve (curve.h) | ChassisDef | SuspensionDef | AxleDef | TyreDef |
//        EngineDef | GearboxDef | SteeringDef | VehicleDef | validate
#include <string>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "vehicle/curve.h"

namespace tumble::vehicle {

struct ChassisDef {
  Real mass_kg = 1200;                       ///< whole vehicle, wheels included
  Vec3 size_m = Vec3(1.7f, 0.6f, 4.0f);      ///< collision box, full width / height / length
  /// Centre of mass relative to the box centre (m). The collision box is
  /// centred on the centre of mass (compound shapes are not there yet), so
  /// this moves the wheels relative to the box, not the box.
  Vec3 centerOfMass_m = Vec3::Zero();
  /// Inertia. "box" (default): a solid box of size_m and mass_kg. "mesh":
  /// the moments of the visual mesh taken as a uniform solid scaled to
  /// mass_kg (its diagonal along the chassis axes; the script layer computes
  /// inertia_kgm2 from the mesh when it loads the definition).
  bool inertiaFromMesh = false;
  Vec3 inertia_kgm2 = Vec3::Zero();  ///< principal moments, kg m^2; zero: the box's
  Real dragArea_m2 = Real(0.7);   ///< drag coefficient times frontal area (Cd A), m^2
  Real airDensity_kgpm3 = Real(1.2);
  Real friction = Real(0.4);      ///< body contact friction (crashes, scrapes)
  Real restitution = Real(0.1);
  std::string mesh;               ///< visual mesh inside the mod (empty: drawn as the box)
  /// Drawn instead of mesh when set (more shape than the solid the inertia
  /// comes from: wheel arches, ...); a path inside the mod. Empty: mesh.
  std::string displayMesh;
};

struct SuspensionDef {
  /// The hub travels along chassis -Y from the axle's position (full bump)
  /// down to position - travel_m (full droop). Spring length l is the hub's
  /// distance below full bump, 0..travel_m.
  Real travel_m = Real(0.2);
  Real restLength_m = Real(0.3);  ///< spring force k (restLength - l), zero at and beyond restLength
  /// Stiffness k (N/m) per wheel; 0: from frequency_hz and the static load
  /// on the wheel, k = m_corner (2 pi f)^2.
  Real stiffness_Npm = 0;
  Real frequency_hz = Real(1.5);
  /// Damping (N s/m) while compressing (bump) and extending (rebound); a
  /// value < 0 means "from the ratio": c = ratio * 2 sqrt(k m_corner).
  Real bumpDamping_Nspm = -1, reboundDamping_Nspm = -1;
  Real bumpRatio = Real(0.3), reboundRatio = Real(0.5);  ///< fractions of critical damping
  Real antiRoll_Npm = 0;  ///< anti-roll bar: force per metre of compression difference across the axle
};

enum class Differential { Open, LimitedSlip };

/// Two wheels at (+x, y, z) (left) and (-x, y, z) (right), chassis frame.
struct AxleDef {
  Vec3 position_m = Vec3(0.75f, -0.2f, 1.3f);  ///< left hub at full bump; x = half track
  Real wheelRadius_m = Real(0.31);
  Real wheelWidth_m = Real(0.2);
  Real wheelInertia_kgm2 = Real(1.0);  ///< one wheel with its brake disc and half shaft
  bool steered = false;
  bool driven = false;
  Real brakeTorque_Nm = 1500;   ///< per wheel at full brake
  Real handbrakeTorque_Nm = 0;  ///< per wheel at full handbrake
  Real driveShare = 0;          ///< fraction of drive torque to this axle; 0 = equal among driven axles
  Differential differential = Differential::Open;
  Real lsdBias = 2;             ///< limited slip: largest torque ratio between the two wheels (>= 1)
  SuspensionDef suspension;
};

struct TyreDef {
  /// Friction coefficient against slip ratio (dimensionless, (wr - v)/|v|),
  /// on a surface of friction 1 (dry tarmac); for |slip| beyond the peak the
  /// sliding value. Scaled by the surface friction (the terrain drag map or
  /// the body touched).
  Curve longitudinal{{{0, 0}, {Real(0.08), Real(1.1)}, {Real(0.3), Real(0.95)}, {1, Real(0.8)}}};
  /// Friction coefficient against slip angle (rad).
  Curve lateral{{{0, 0}, {Real(0.14), Real(1.05)}, {Real(0.4), Real(0.9)}, {Real(1.57), Real(0.8)}}};
  Real rollingResistance = Real(0.012);  ///< C_rr: rolling torque C_rr N r per wheel
  /// Extra C_rr per unit of surface softness (ground_softness.h; the
  /// terrain's softness layer, not its friction): mud (softness 0.7) adds
  /// 0.7 * this, grass (0.4) 0.4 * this, asphalt, rock and ice nothing.
  Real softGroundDrag = Real(0.08);
};

struct EngineDef {
  Curve torque{{{1000, 120}, {4000, 160}, {6500, 120}}};  ///< N m at full throttle against rpm
  Real idleRpm = 900;
  Real maxRpm = 6800;          ///< rev limiter: no torque above it
  Real inertia_kgm2 = Real(0.2);  ///< crank, flywheel and clutch
  Real brakingTorque_Nm = 30;  ///< engine braking at max rpm with the throttle closed (linear in rpm)
  Real launchRpm = 2500;       ///< the automatic clutch slips to hold this rpm when starting off
};

struct GearboxDef {
  std::vector<Real> ratios{Real(3.5), Real(2.1), Real(1.4), Real(1.05), Real(0.85)};  ///< forward gears
  Real reverseRatio = Real(3.3);
  Real finalDrive = Real(4.0);
  Real efficiency = Real(0.9);   ///< fraction of engine torque reaching the wheels
  Real shiftUpRpm = 6200;        ///< for the automatic gearbox (Lua controller)
  Real shiftDownRpm = 2600;
  Real shiftTime_s = Real(0.25); ///< no drive torque during a shift
};

struct SteeringDef {
  Real maxAngle_rad = Real(0.55);
  /// The largest angle shrinks with speed: max / (1 + speedSensitivity * v).
  Real speedSensitivity_spm = Real(0.02);
  Real rate_radps = Real(2.5);   ///< how fast the wheels turn towards the asked angle
};

/// How the vehicle sounds (the audio module plays it; docs/vehicles.md).
struct SoundDef {
  Real cylinders = 4;  ///< whole number 1..16: the engine note is rpm / 60 * cylinders / 2 Hz (four-stroke)
  Real volume = 1;     ///< engine gain, 0..4
  /// A loop inside the mod (WAV or Ogg Vorbis) played at pitch rpm /
  /// sampleRpm instead of the synthesised note; empty: synthesised.
  std::string engineSample;
  Real sampleRpm = 3000;                ///< rpm the sample was recorded at
  Real tyreSlipThreshold_mps = Real(1.5);  ///< contact-patch slip speed where tyre noise starts, m/s
  /// engineSample resolved to a file when the definition is loaded (not a Lua field).
  std::string engineSamplePath;
};

/// Where the cameras that ride in the car sit, and what the cockpit view
/// draws (docs/vehicles.md). Eyes are in the frame of the drawn model: origin
/// on the ground line under the model's middle, +Z forward, +Y up, +X left.
struct ViewDef {
  Vec3 hoodEye_m = Vec3(0.0f, 1.07f, 1.6f);      ///< hood camera: just above the bonnet, m
  Vec3 cockpitEye_m = Vec3(0.35f, 1.17f, -0.1f); ///< cockpit camera: the driver's eye, m
  /// A model (a path inside the vehicle's mod) drawn around the cockpit eye,
  /// origin at the eye, +Z forward; empty: the base mod's generic interior.
  std::string interior;
  /// An open car (no roof, no body around the driver): the cockpit view
  /// draws the car's own model and no interior.
  bool open = false;
};

struct VehicleDef {
  std::string name = "vehicle";  ///< shown to the player
  std::string description;       ///< the feel, in a sentence
  ChassisDef chassis;
  std::vector<AxleDef> axles;
  TyreDef tyre;
  EngineDef engine;
  GearboxDef gearbox;
  SteeringDef steering;
  SoundDef sound;
  ViewDef view;
};

/// Numbers derived from a VehicleDef (per axle, static loads on level ground).
struct DerivedAxle {
  Real staticLoad_N = 0;   ///< per wheel
  Real stiffness_Npm = 0;  ///< per wheel
  Real bump_Nspm = 0, rebound_Nspm = 0;
  Real staticLength_m = 0; ///< spring length at rest on level ground
};

/// Checks every field (finite, in range, consistent: the car must not sit
/// on its bump stops); the message names the field ("axles[2].suspension.
/// travel: ...") and what would be valid. `where` prefixes it (the file).
Status validateVehicleDef(const VehicleDef& def, const std::string& where);
/// Static load per wheel, spring rate and damping per axle (def must be valid).
std::vector<DerivedAxle> deriveAxles(const VehicleDef& def);
/// Peak engine power (W) from the torque curve: max of T(rpm) * rpm * 2 pi / 60.
Real peakPower_W(const EngineDef& engine);

}  // namespace tumble::vehicle
