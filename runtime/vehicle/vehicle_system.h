#pragma once
// VehicleSystem: wheeled vehicles in a physics::World. The chassis is an
// ordinary dynamic box body (so it collides with walls, boxes and rag-dolls
// through the contact solver); the wheels are ray casts along the
// suspension, integrated in every world substep (World::addSubstepHook).
// vehicle_system.cpp derives the wheel, tyre and drivetrain model.
//
//   VehicleSystem vehicles(world);
//   VehicleId car = vehicles.spawn(def, {0, 0, 0}, 0).value();
//   vehicles.setControls(car, {.throttle = 1});
//   vehicles.beforeStep(dt); world.step(dt);   // or vehicles.step(dt)
//
// Index: VehicleControls | WheelTelemetry | VehicleTelemetry | VehicleSystem
#include <cstdint>
#include <functional>
#include <vector>

#include "core/handle.h"
#include "core/math.h"
#include "core/result.h"
#include "physics/world.h"
#include "vehicle/ground_softness.h"
#include "vehicle/vehicle_def.h"

namespace tumble::vehicle {

struct VehicleTag;
using VehicleId = Handle<VehicleTag>;

/// What a driver (a Lua controller) asks for.
struct VehicleControls {
  Real throttle = 0;   ///< 0..1
  Real brake = 0;      ///< 0..1, all braked wheels
  Real steer = 0;      ///< -1 full left .. +1 full right
  Real handbrake = 0;  ///< 0..1
  int gear = 1;        ///< -1 reverse, 0 neutral, 1..N forward
};

struct WheelTelemetry {
  bool contact = false;
  Real load_N = 0;            ///< suspension force pressing the tyre on the ground
  Real slipRatio = 0;         ///< (w r - v) / max(|v|, 0.5 m/s), longitudinal
  Real slipAngle_rad = 0;     ///< atan(v_lateral / |v_forward|), signed
  Real slipSpeed_mps = 0;     ///< speed of the contact patch over the ground (dust)
  Real surfaceFriction = 0;   ///< of what the tyre touches (terrain drag map or body friction)
  /// Softness of what the tyre touches (ground_softness.h; unitless: 0
  /// hard, 0.4 grass, 0.7 mud): adds tyre.soft_ground_drag times it to the
  /// rolling resistance coefficient. Terrain softness layer, or a body's
  /// setSurfaceSoftness (0 by default).
  Real surfaceSoftness = 0;
  Real spin_radps = 0;        ///< wheel angular velocity, + rolling forward
  /// Torque the differential delivered to this wheel, mean over the last
  /// step's substeps, N m (+ drives forward; 0 on an undriven axle). Open:
  /// both wheels of an axle get the same; limited slip: up to lsd_bias
  /// times the other's.
  Real driveTorque_Nm = 0;
  Real rotation_rad = 0;      ///< accumulated spin angle (for drawing)
  Real steer_rad = 0;         ///< + to the left
  Real springLength_m = 0;    ///< hub below full bump, 0..travel
  /// Spring length at rest on level ground (rest_length minus the static
  /// sag), m: where the hub sits when the car stands still. Drawing puts
  /// the chassis model's ground a wheel radius below it.
  Real staticLength_m = 0;
  Vec3 hub_m = Vec3::Zero();  ///< world
  Vec3 contactPoint_m = Vec3::Zero();
  Vec3 contactNormal = Vec3::UnitY();
  physics::BodyId ground;     ///< body under the tyre; null for terrain or none
  Real radius_m = 0, width_m = 0;
};

struct VehicleTelemetry {
  Real speed_mps = 0;        ///< along the chassis forward axis, signed
  Real rpm = 0;              ///< engine
  int gear = 1;              ///< the gear engaged (-1 R, 0 N, 1..N)
  bool shifting = false;     ///< clutch open for a gear change
  Real engineTorque_Nm = 0;  ///< at the crank (negative: engine braking)
  Real driveTorque_Nm = 0;   ///< at the wheels, total
};

class VehicleSystem {
 public:
  explicit VehicleSystem(physics::World& world);  ///< adds its substep hook to the world
  ~VehicleSystem();                               ///< removes it and every vehicle's chassis
  VehicleSystem(const VehicleSystem&) = delete;
  VehicleSystem& operator=(const VehicleSystem&) = delete;

  /// Creates a vehicle resting on its springs on the ground point
  /// groundPoint_m (the point under its centre), facing heading_rad
  /// (0: +Z, + turns towards +X). The definition is validated first.
  Result<VehicleId> spawn(const VehicleDef& def, const Vec3& groundPoint_m, Real heading_rad,
                          const std::string& where = "vehicle");
  bool remove(VehicleId id);
  bool isValid(VehicleId id) const;
  int count() const { return m_alive; }

  void setControls(VehicleId id, const VehicleControls& controls);
  const VehicleControls& controls(VehicleId id) const;
  /// Softness (unitless, >= 0; ground_softness.h) of a body's surface under
  /// the tyres: a static box of mud, say. Bodies are hard (0) unless set;
  /// setting 0 forgets the body. Terrain softness comes from the height
  /// field (its softness layer). Not finite or negative: false, unchanged.
  bool setSurfaceSoftness(physics::BodyId body, Real softness);
  /// The softness set for a body, or 0.
  Real surfaceSoftness(physics::BodyId body) const;
  /// Replaces the definition while running (tunables): validated; the
  /// chassis keeps its pose and velocity, the wheels their spin. A new
  /// chassis size or mass remakes the chassis body (a new chassis() id).
  Status setDef(VehicleId id, const VehicleDef& def, const std::string& where = "vehicle");
  const VehicleDef& def(VehicleId id) const;
  /// Upright at groundPoint_m facing heading_rad, at rest, engine idling.
  void reset(VehicleId id, const Vec3& groundPoint_m, Real heading_rad);

  physics::BodyId chassis(VehicleId id) const;
  const VehicleTelemetry& telemetry(VehicleId id) const;
  /// Wheels in axle order, left then right on each axle.
  int wheelCount(VehicleId id) const;
  const WheelTelemetry& wheel(VehicleId id, int index) const;

  /// Before World::step: steering, gear shifts, and the bodies near each
  /// vehicle its wheels may touch during the step.
  void beforeStep(Real dt_s);
  /// beforeStep then World::step (tests, benchmarks).
  void step(Real dt_s);

  template <typename F>
  void forEach(F&& f) const {
    for (std::uint32_t i = 0; i < m_vehicles.size(); ++i)
      if (m_vehicles[i].alive) f(VehicleId{i, m_vehicles[i].generation});
  }

  /// Every vehicle's definition and running state between steps as exact
  /// bits, for snapshots of a running scene (vehicle_state.cpp): controls,
  /// steering, engine speed, gear and shift timer, each wheel's spin, angle
  /// and telemetry, the differentials' state, the bodies the wheels test,
  /// and surface softness set on bodies. Restore runs after the World's (it
  /// puts the chassis bodies back): a vehicle spawned or re-tuned since is
  /// made again from its stored definition around its chassis, one removed
  /// since is removed. Every stored definition passes validateVehicleDef;
  /// its files stay inside its mod, and a resolved engine sample must be a
  /// file `fileInMods` accepts (none without it).
  std::string saveState() const;
  /// The state of a system without vehicles (restoring it removes every vehicle).
  static std::string emptyState();
  Status restoreState(const std::string& bytes, const std::function<bool(const std::string&)>& fileInMods = {});

 private:
  struct Wheel {
    int axle = 0;
    Vec3 mount_local = Vec3::Zero();  ///< hub at full bump, relative to the centre of mass
    bool locked = false;
    Real driveImpulse_Nms = 0, driveTime_s = 0;  ///< this step so far: telemetry's mean drive torque
    WheelTelemetry t;
  };
  /// One axle's differential in the current substep (vehicle_system.cpp, 1.).
  struct AxleDrive {
    Real torque_Nm = 0;      ///< from the gearbox into the differential's carrier
    Real carrier_kgm2 = 0;   ///< engine inertia reflected onto the carrier (0: clutch open)
    Real invInertia[2][2] = {};  ///< spin change of wheel j per unit angular impulse on wheel k, 1/(kg m^2)
    Real spin0_radps[2] = {};    ///< wheel spins at the start of the substep
    Real lock_Nms = 0;       ///< limited-slip transfer impulse this substep (+ to the left wheel)
  };
  struct Vehicle {
    bool alive = false;
    std::uint32_t generation = 0;
    VehicleDef def;
    std::vector<DerivedAxle> derived;
    physics::BodyId chassis;
    std::vector<Wheel> wheels;
    std::vector<Real> axleShare;  ///< drive share per axle (0: not driven)
    std::vector<AxleDrive> axleDrive;
    VehicleControls controls;
    Real steer_rad = 0;
    Real engine_radps = 0;
    Real shiftTimer_s = 0;
    int gear = 1;
    std::vector<physics::BodyId> nearby;  ///< bodies the wheel rays test this step
    VehicleTelemetry telemetry;
    std::uint32_t defChanges = 0;  ///< setDef calls since spawn (snapshots: the definition must be the same)
  };

  Vehicle& get(VehicleId id);
  const Vehicle& get(VehicleId id) const;
  void configure(Vehicle& v);
  void place(Vehicle& v, const Vec3& groundPoint_m, Real heading_rad);
  void substep(Real h);
  void substepVehicle(Vehicle& v, Real h);
  void drivetrain(Vehicle& v, Real h);
  void updateAxleInertia(Vehicle& v, std::size_t axle);
  void spinImpulse(Vehicle& v, std::size_t wheel, Real impulse_Nms);
  void solveLimitedSlip(Vehicle& v, Real h);
  bool castWheel(const Vehicle& v, const Vec3& origin, const Vec3& down, Real length, physics::RayHit* hit,
                 Real* friction, Real* softness) const;

  physics::World& m_world;
  int m_hook = 0;
  std::vector<Vehicle> m_vehicles;
  std::vector<std::uint32_t> m_free;
  std::vector<std::pair<physics::BodyId, Real>> m_softBodies;  ///< setSurfaceSoftness (few: a linear search)
  const GroundSoftness* m_groundSoftness = nullptr;            ///< the height field's, this substep (or none)
  int m_alive = 0;
};

}  // namespace tumble::vehicle
