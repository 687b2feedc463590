// VehicleSystem::saveState / restoreState: what the vehicles carry from one
// step to the next, as exact bits, for snapshots of a running scene.
//
// A vehicle is its definition (from a Lua table the scenario spawns it
// with; not stored) and its running state (stored): the driver's controls,
// the steering angle reached, engine speed, gear and shift timer, each
// wheel's spin, accumulated angle, lock and telemetry (the drivetrain reads
// the last spin and load), the differentials' state and the bodies near
// each vehicle. The snapshot goes back into a system with the same vehicles,
// spawned again by on_start: a vehicle spawned, removed or re-tuned
// (Vehicle:tune) since is refused by name, as the World refuses a body made
// since.
#include <algorithm>

#include "core/byte_stream.h"
#include "vehicle/vehicle_system.h"

namespace tumble::vehicle {

namespace {

constexpr std::uint32_t kStateMagic = 0x54564843;  // "TVHC"
constexpr std::uint32_t kStateVersion = 1;
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
    w.pod(Running{v.controls, v.steer_rad, v.engine_radps, v.shiftTimer_s, v.gear, v.telemetry});
    w.vec(v.wheels);
    w.vec(v.axleDrive);
    w.vec(v.nearby);
  }
  w.vec(m_free);
  w.vec(m_softBodies);
  return w.take();
}

Status VehicleSystem::restoreState(const std::string& bytes) {
  ByteReader r(bytes);
  if (r.pod<std::uint32_t>() != kStateMagic || !r.ok()) return makeError("not a vehicle state");
  if (const auto v = r.pod<std::uint32_t>(); v != kStateVersion)
    return makeError("vehicle state version " + std::to_string(v) + ", this build reads " +
                     std::to_string(kStateVersion));
  const auto count = r.pod<std::uint64_t>();
  if (!r.ok() || count > kMaxVehicles) return makeError("vehicle state: damaged (vehicle slots)");
  if (count != m_vehicles.size())
    return makeError("the snapshot holds " + std::to_string(count) + " vehicle slots, the scenario made " +
                     std::to_string(m_vehicles.size()) +
                     " (vehicles were spawned or removed since on_start; a snapshot goes back into a scene with the "
                     "same vehicles)");
  // Read and checked whole before anything changes.
  struct Saved {
    Running running;
    std::vector<Wheel> wheels;
    std::vector<AxleDrive> axleDrive;
    std::vector<physics::BodyId> nearby;
  };
  std::vector<Saved> saved(count);
  auto known = [&](physics::BodyId b) { return b.isNull() || b.index < m_world.bodySlotCount(); };
  for (std::size_t i = 0; i < count; ++i) {
    const Vehicle& v = m_vehicles[i];
    const auto layout = r.pod<Layout>();
    if (!r.ok()) return makeError("vehicle state: damaged (vehicle " + std::to_string(i) + ")");
    const Layout here{std::uint8_t(v.alive), v.generation, v.defChanges, v.chassis, std::uint32_t(v.wheels.size()),
                      std::uint32_t(v.derived.size())};
    if (!(layout == here)) {
      const std::string name = v.alive ? "vehicle " + std::to_string(i) + " (" + v.def.name + ")"
                                       : "vehicle slot " + std::to_string(i);
      if (layout.defChanges != here.defChanges && layout.alive && here.alive)
        return makeError(name + " was re-tuned (Vehicle:tune) " + std::to_string(layout.defChanges) +
                         " times in the saved run and " + std::to_string(here.defChanges) +
                         " times here: a snapshot does not hold vehicle definitions (tune in on_start)");
      return makeError(name + " is not the vehicle the snapshot holds there (spawned, removed or remade since "
                       "on_start; a snapshot goes back into a scene with the same vehicles)");
    }
    if (!layout.alive) continue;
    Saved& s = saved[i];
    s.running = r.pod<Running>();
    s.wheels = r.vec<Wheel>(kMaxWheels);
    s.axleDrive = r.vec<AxleDrive>(kMaxWheels);
    s.nearby = r.vec<physics::BodyId>(kMaxBodies);
    // The differentials' state exists from the first step on.
    if (!r.ok() || s.wheels.size() != v.wheels.size() ||
        (!s.axleDrive.empty() && s.axleDrive.size() != v.derived.size()))
      return makeError("vehicle state: damaged (vehicle " + std::to_string(i) + ")");
    // Indices the next step follows: wheels to their axle, bodies into the World.
    if (!validBools(s.running.telemetry.shifting))
      return makeError("vehicle state: damaged (vehicle " + std::to_string(i) + ")");
    for (const Wheel& w : s.wheels)
      if (w.axle < 0 || std::size_t(w.axle) >= v.derived.size() || !known(w.t.ground) ||
          !validBools(w.locked, w.t.contact))
        return makeError("vehicle state: damaged (wheels of vehicle " + std::to_string(i) + ")");
    if (!std::all_of(s.nearby.begin(), s.nearby.end(), known))
      return makeError("vehicle state: damaged (bodies near vehicle " + std::to_string(i) + ")");
  }
  auto freeSlots = r.vec<std::uint32_t>(kMaxVehicles);
  auto softBodies = r.vec<std::pair<physics::BodyId, Real>>(kMaxBodies);
  if (!r.ok() || !r.atEnd()) return makeError("vehicle state: damaged (truncated or bytes after the end)");
  for (std::uint32_t i : freeSlots)
    if (i >= count || m_vehicles[i].alive) return makeError("vehicle state: damaged (free slots)");
  for (const auto& [body, softness] : softBodies)
    if (!known(body)) return makeError("vehicle state: damaged (surface softness)");
  for (std::size_t i = 0; i < count; ++i) {
    Vehicle& v = m_vehicles[i];
    if (!v.alive) continue;
    Saved& s = saved[i];
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
  m_free = std::move(freeSlots);
  m_softBodies = std::move(softBodies);
  return Ok{};
}

}  // namespace tumble::vehicle
