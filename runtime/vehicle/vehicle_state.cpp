// VehicleSystem::saveState / restoreState: what the vehicles carry from one
// step to the next, as exact bits, for snapshots of a running scene.
//
// A vehicle is its definition and its running state, both stored: the
// definition (every field of VehicleDef; writeDef below), and the driver's
// controls, the steering angle reached, engine speed, gear and shift timer,
// each wheel's spin, accumulated angle, lock and telemetry (the drivetrain
// reads the last spin and load), the differentials' state and the bodies
// near each vehicle. Restoring goes into the system on_start made again:
// a vehicle that is there with the same slot, generation, chassis and
// definition keeps its definition; one spawned or re-tuned (Vehicle:tune)
// since on_start is made again from the stored definition around its
// chassis body, which the World's restore has already put back; one
// removed since is removed (its chassis is the World's business).
#include <algorithm>
#include <filesystem>

#include "core/byte_stream.h"
#include "vehicle/vehicle_system.h"

namespace tumble::vehicle {

namespace {

constexpr std::uint32_t kStateMagic = 0x54564843;  // "TVHC"
constexpr std::uint32_t kStateVersion = 2;  // 2: definitions stored
constexpr std::size_t kMaxVehicles = std::size_t(1) << 16;
constexpr std::size_t kMaxWheels = 64;
constexpr std::size_t kMaxBodies = std::size_t(1) << 24;

/// What must match between the saved vehicle and the one spawned again.
struct Layout {
  std::uint8_t alive = 0;
  std::uint32_t generation = 0, defChanges = 0;
  physics::BodyId chassis;
  std::uint32_t wheels = 0, axles = 0;
  bool operator==(const Layout&) const = default;
};

/// The running state besides the per-wheel and per-axle arrays.
struct Running {
  VehicleControls controls;
  Real steer_rad, engine_radps, shiftTimer_s;
  std::int32_t gear;
  VehicleTelemetry telemetry;
};

constexpr std::size_t kMaxText = 4096;
constexpr std::size_t kMaxPoints = 1024;
constexpr std::size_t kMaxAxles = kMaxWheels / 2;

void writeCurve(ByteWriter& w, const Curve& c) { w.vec(c.points()); }
bool readCurve(ByteReader& r, Curve& c) {
  auto points = r.vec<std::pair<Real, Real>>(kMaxPoints);
  c = Curve(std::move(points));
  return r.ok();
}

/// The plain parts of each record, copied as bytes (no strings or vectors in them).
struct ChassisNumbers {
  Real mass_kg;
  Vec3 size_m, centerOfMass_m, inertia_kgm2;
  Real dragArea_m2, airDensity_kgpm3, friction, restitution;
  bool inertiaFromMesh;
};
struct TyreNumbers {
  Real rollingResistance, softGroundDrag;
};
struct EngineNumbers {
  Real idleRpm, maxRpm, inertia_kgm2, brakingTorque_Nm, launchRpm;
};
struct GearboxNumbers {
  Real reverseRatio, finalDrive, efficiency, shiftUpRpm, shiftDownRpm, shiftTime_s;
};
struct SoundNumbers {
  Real cylinders, volume, sampleRpm, tyreSlipThreshold_mps;
};
struct ViewNumbers {
  Vec3 hoodEye_m, cockpitEye_m;
  bool open;
};

/// Every field of a definition, in a fixed order.
void writeDef(ByteWriter& w, const VehicleDef& d) {
  static_assert(kBitwise<AxleDef> && kBitwise<SteeringDef>);
  w.text(d.name);
  w.text(d.description);
  const ChassisDef& c = d.chassis;
  w.pod(ChassisNumbers{c.mass_kg, c.size_m, c.centerOfMass_m, c.inertia_kgm2, c.dragArea_m2, c.airDensity_kgpm3,
                       c.friction, c.restitution, c.inertiaFromMesh});
  w.text(c.mesh);
  w.text(c.displayMesh);
  w.vec(d.axles);
  writeCurve(w, d.tyre.longitudinal);
  writeCurve(w, d.tyre.lateral);
  w.pod(TyreNumbers{d.tyre.rollingResistance, d.tyre.softGroundDrag});
  writeCurve(w, d.engine.torque);
  const EngineDef& e = d.engine;
  w.pod(EngineNumbers{e.idleRpm, e.maxRpm, e.inertia_kgm2, e.brakingTorque_Nm, e.launchRpm});
  w.vec(d.gearbox.ratios);
  const GearboxDef& g = d.gearbox;
  w.pod(GearboxNumbers{g.reverseRatio, g.finalDrive, g.efficiency, g.shiftUpRpm, g.shiftDownRpm, g.shiftTime_s});
  w.pod(d.steering);
  const SoundDef& s = d.sound;
  w.pod(SoundNumbers{s.cylinders, s.volume, s.sampleRpm, s.tyreSlipThreshold_mps});
  w.text(s.engineSample);
  w.text(s.engineSamplePath);
  w.pod(ViewNumbers{d.view.hoodEye_m, d.view.cockpitEye_m, d.view.open});
  w.text(d.view.interior);
}

/// A path a definition names inside its mod: relative, and never up out of it.
bool insideItsMod(const std::string& path) {
  if (path.empty()) return true;
  const std::filesystem::path p(path);
  if (p.is_absolute() || p.has_root_name()) return false;
  for (const std::filesystem::path& part : p)
    if (part == "..") return false;
  return true;
}

/// What writeDef wrote, or an error naming what is wrong; the numbers are
/// checked by validateVehicleDef, the paths here.
Result<VehicleDef> readDef(ByteReader& r, const std::string& where,
                           const std::function<bool(const std::string&)>& fileInMods) {
  VehicleDef d;
  d.name = r.text(kMaxText);
  d.description = r.text(kMaxText);
  const auto c = r.pod<ChassisNumbers>();
  d.chassis.mesh = r.text(kMaxText);
  d.chassis.displayMesh = r.text(kMaxText);
  d.axles = r.vec<AxleDef>(kMaxAxles);
  const bool curves = readCurve(r, d.tyre.longitudinal) && readCurve(r, d.tyre.lateral);
  const auto t = r.pod<TyreNumbers>();
  const bool torque = readCurve(r, d.engine.torque);
  const auto e = r.pod<EngineNumbers>();
  d.gearbox.ratios = r.vec<Real>(kMaxPoints);
  const auto g = r.pod<GearboxNumbers>();
  d.steering = r.pod<SteeringDef>();
  const auto s = r.pod<SoundNumbers>();
  d.sound.engineSample = r.text(kMaxText);
  d.sound.engineSamplePath = r.text(kMaxText);
  const auto v = r.pod<ViewNumbers>();
  d.view.interior = r.text(kMaxText);
  if (!r.ok() || !curves || !torque) return makeError(where + ": damaged (definition)");
  // Bools and enums read as bytes: checked before they are used.
  if (!validBools(c.inertiaFromMesh, v.open)) return makeError(where + ": damaged (definition)");
  for (const AxleDef& a : d.axles) {
    static_assert(sizeof(Differential) == sizeof(int));
    int raw = 0;
    std::memcpy(&raw, &a.differential, sizeof(Differential));
    if (!validBools(a.steered, a.driven) || (raw != int(Differential::Open) && raw != int(Differential::LimitedSlip)))
      return makeError(where + ": damaged (definition of the axles)");
  }
  d.chassis.mass_kg = c.mass_kg;
  d.chassis.size_m = c.size_m;
  d.chassis.centerOfMass_m = c.centerOfMass_m;
  d.chassis.inertia_kgm2 = c.inertia_kgm2;
  d.chassis.dragArea_m2 = c.dragArea_m2;
  d.chassis.airDensity_kgpm3 = c.airDensity_kgpm3;
  d.chassis.friction = c.friction;
  d.chassis.restitution = c.restitution;
  d.chassis.inertiaFromMesh = c.inertiaFromMesh;
  d.tyre.rollingResistance = t.rollingResistance;
  d.tyre.softGroundDrag = t.softGroundDrag;
  d.engine.idleRpm = e.idleRpm;
  d.engine.maxRpm = e.maxRpm;
  d.engine.inertia_kgm2 = e.inertia_kgm2;
  d.engine.brakingTorque_Nm = e.brakingTorque_Nm;
  d.engine.launchRpm = e.launchRpm;
  d.gearbox.reverseRatio = g.reverseRatio;
  d.gearbox.finalDrive = g.finalDrive;
  d.gearbox.efficiency = g.efficiency;
  d.gearbox.shiftUpRpm = g.shiftUpRpm;
  d.gearbox.shiftDownRpm = g.shiftDownRpm;
  d.gearbox.shiftTime_s = g.shiftTime_s;
  d.sound.cylinders = s.cylinders;
  d.sound.volume = s.volume;
  d.sound.sampleRpm = s.sampleRpm;
  d.sound.tyreSlipThreshold_mps = s.tyreSlipThreshold_mps;
  d.view.hoodEye_m = v.hoodEye_m;
  d.view.cockpitEye_m = v.cockpitEye_m;
  d.view.open = v.open;
  if (Status st = validateVehicleDef(d, where); !st) return makeError(st.error());
  if (!d.chassis.inertia_kgm2.allFinite() || (d.chassis.inertia_kgm2 != Vec3::Zero() &&
                                              !(d.chassis.inertia_kgm2.minCoeff() > 0)))
    return makeError(where + ": damaged (chassis inertia)");
  for (const std::string* path : {&d.chassis.mesh, &d.chassis.displayMesh, &d.sound.engineSample, &d.view.interior})
    if (!insideItsMod(*path)) return makeError(where + ": a file outside its mod (\"" + *path + "\")");
  if (!d.sound.engineSamplePath.empty() && !(fileInMods && fileInMods(d.sound.engineSamplePath)))
    return makeError(where + ": the engine sample is not a file of a mod here (\"" + d.sound.engineSamplePath + "\")");
  return d;
}

std::string defBytes(const VehicleDef& d) {
  ByteWriter w;
  writeDef(w, d);
  return w.take();
}

}  // namespace

std::string VehicleSystem::saveState() const {
  static_assert(kBitwise<Layout> && kBitwise<Running> && kBitwise<Wheel> && kBitwise<AxleDrive>);
  ByteWriter w;
  w.pod(kStateMagic);
  w.pod(kStateVersion);
  w.pod(std::uint64_t(m_vehicles.size()));
  for (const Vehicle& v : m_vehicles) {
    w.pod(Layout{std::uint8_t(v.alive), v.generation, v.defChanges, v.chassis, std::uint32_t(v.wheels.size()),
                 std::uint32_t(v.derived.size())});
    if (!v.alive) continue;
    writeDef(w, v.def);
    w.pod(Running{v.controls, v.steer_rad, v.engine_radps, v.shiftTimer_s, v.gear, v.telemetry});
    w.vec(v.wheels);
    w.vec(v.axleDrive);
    w.vec(v.nearby);
  }
  w.vec(m_free);
  w.vec(m_softBodies);
  return w.take();
}

std::string VehicleSystem::emptyState() {
  ByteWriter w;
  w.pod(kStateMagic);
  w.pod(kStateVersion);
  w.pod(std::uint64_t(0));
  w.vec(std::vector<std::uint32_t>{});
  w.vec(std::vector<std::pair<physics::BodyId, Real>>{});
  return w.take();
}

Status VehicleSystem::restoreState(const std::string& bytes,
                                   const std::function<bool(const std::string&)>& fileInMods) {
  ByteReader r(bytes);
  if (r.pod<std::uint32_t>() != kStateMagic || !r.ok()) return makeError("not a vehicle state");
  if (const auto v = r.pod<std::uint32_t>(); v != kStateVersion)
    return makeError("vehicle state version " + std::to_string(v) + ", this build reads " +
                     std::to_string(kStateVersion));
  const auto count = r.pod<std::uint64_t>();
  // Each slot takes at least its Layout bytes: a damaged count allocates no
  // more than the bytes could hold.
  if (!r.ok() || count > kMaxVehicles || count > r.remaining() / sizeof(Layout))
    return makeError("vehicle state: damaged (vehicle slots)");
  // Read and checked whole before anything changes.
  struct Saved {
    Layout layout;
    bool remake = false;  ///< spawned or re-tuned since on_start: made again from the stored definition
    VehicleDef def;
    Running running;
    std::vector<Wheel> wheels;
    std::vector<AxleDrive> axleDrive;
    std::vector<physics::BodyId> nearby;
  };
  std::vector<Saved> saved(count);
  auto known = [&](physics::BodyId b) { return b.isNull() || b.index < m_world.bodySlotCount(); };
  for (std::size_t i = 0; i < count; ++i) {
    Saved& s = saved[i];
    const std::string where = "vehicle state: vehicle " + std::to_string(i);
    s.layout = r.pod<Layout>();
    if (!r.ok() || s.layout.alive > 1) return makeError(where + ": damaged");
    if (!s.layout.alive) continue;
    const std::size_t defStart = r.position();
    auto def = readDef(r, where, fileInMods);
    if (!def) return makeError(def.error());
    s.def = std::move(def.value());
    const std::string stored = bytes.substr(defStart, r.position() - defStart);
    const Vehicle* here = i < m_vehicles.size() ? &m_vehicles[i] : nullptr;
    // Compared as written bytes. The records written whole (an axle, the
    // chassis numbers) carry padding bytes, so an equal definition may
    // compare unequal and be made again from the stored one: the same
    // vehicle, as every field it has is stored or derived from them.
    s.remake = !(here && here->alive &&
                 Layout{std::uint8_t(here->alive), here->generation, here->defChanges, here->chassis,
                        std::uint32_t(here->wheels.size()), std::uint32_t(here->derived.size())} == s.layout &&
                 defBytes(here->def) == stored);
    const std::uint32_t axles = std::uint32_t(s.def.axles.size());
    if (s.layout.wheels != 2 * axles || s.layout.axles != axles) return makeError(where + ": damaged (wheels)");
    // Made again around its chassis, which the World's restore put back.
    if (s.remake && !(m_world.isValid(s.layout.chassis) && m_world.body(s.layout.chassis).type == physics::BodyType::Dynamic))
      return makeError(where + " (" + s.def.name + "): its chassis, body slot " + std::to_string(s.layout.chassis.index) +
                       ", is not a dynamic body of the restored world");
    s.running = r.pod<Running>();
    s.wheels = r.vec<Wheel>(kMaxWheels);
    s.axleDrive = r.vec<AxleDrive>(kMaxWheels);
    s.nearby = r.vec<physics::BodyId>(kMaxBodies);
    // The differentials' state exists from the first step on.
    if (!r.ok() || s.wheels.size() != s.layout.wheels || (!s.axleDrive.empty() && s.axleDrive.size() != axles))
      return makeError(where + ": damaged");
    // Indices the next step follows: wheels to their axle, bodies into the World.
    if (!validBools(s.running.telemetry.shifting)) return makeError(where + ": damaged");
    for (const Wheel& w : s.wheels)
      if (w.axle < 0 || std::uint32_t(w.axle) >= axles || !known(w.t.ground) || !validBools(w.locked, w.t.contact))
        return makeError(where + ": damaged (wheels)");
    if (!std::all_of(s.nearby.begin(), s.nearby.end(), known)) return makeError(where + ": damaged (nearby bodies)");
  }
  auto freeSlots = r.vec<std::uint32_t>(kMaxVehicles);
  auto softBodies = r.vec<std::pair<physics::BodyId, Real>>(kMaxBodies);
  if (!r.ok() || !r.atEnd()) return makeError("vehicle state: damaged (truncated or bytes after the end)");
  if (!allDistinct(freeSlots)) return makeError("vehicle state: damaged (free slots)");
  for (std::uint32_t i : freeSlots)
    if (i >= count || saved[i].layout.alive) return makeError("vehicle state: damaged (free slots)");
  for (const auto& [body, softness] : softBodies)
    if (!known(body) || !std::isfinite(softness) || softness < 0)
      return makeError("vehicle state: damaged (surface softness)");
  // Slots past the saved ones hold vehicles spawned after the snapshot was
  // taken (world.restore in the same run): removed, their slots free again
  // after the saved free ones, lowest first, as the run went on from there.
  std::vector<std::uint32_t> extra;
  for (std::size_t i = m_vehicles.size(); i-- > count;) {
    Vehicle& v = m_vehicles[i];
    const std::uint32_t gen = v.generation + 1;  // handles to what was there stay invalid
    v = Vehicle{};
    v.generation = gen;
    extra.push_back(std::uint32_t(i));
  }
  if (m_vehicles.size() < count) m_vehicles.resize(count);
  m_alive = 0;
  for (std::size_t i = 0; i < count; ++i) {
    Vehicle& v = m_vehicles[i];
    Saved& s = saved[i];
    if (!s.layout.alive) {
      v = Vehicle{};
      v.generation = s.layout.generation;
      continue;
    }
    if (s.remake) {
      v = Vehicle{};
      v.alive = true;
      v.generation = s.layout.generation;
      v.def = std::move(s.def);
      v.chassis = s.layout.chassis;
      v.defChanges = s.layout.defChanges;
      configure(v);
    }
    ++m_alive;
    v.controls = s.running.controls;
    v.steer_rad = s.running.steer_rad;
    v.engine_radps = s.running.engine_radps;
    v.shiftTimer_s = s.running.shiftTimer_s;
    v.gear = s.running.gear;
    v.telemetry = s.running.telemetry;
    v.wheels = std::move(s.wheels);
    v.axleDrive = std::move(s.axleDrive);
    v.nearby = std::move(s.nearby);
  }
  m_free = std::move(extra);
  m_free.insert(m_free.end(), freeSlots.begin(), freeSlots.end());
  m_softBodies = std::move(softBodies);
  return Ok{};
}

}  // namespace tumble::vehicle
