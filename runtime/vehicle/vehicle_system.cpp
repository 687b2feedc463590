// The wheel model, run in every world substep of length h (after gravity,
// before the contact solver), per vehicle:
//
// 1. Drivetrain. The engine turns with the driven wheels through the gearbox
//    (ratio G = gear * final drive) when the clutch is closed: w_engine =
//    G * mean driven wheel speed, torque T(rpm) * throttle, or engine
//    braking with the throttle shut; the rev limiter cuts torque above
//    max_rpm. Starting off, the automatic clutch slips: the engine is held at
//    idle + throttle * (launch - idle) and its whole torque passes. Each
//    driven axle gets its share T_a of the torque at the wheels, into the
//    carrier of its differential.
//    Differential. The carrier turns at w_c = (w_l + w_r) / 2 (an open
//    differential lets the wheel speeds differ by any amount) and carries
//    the engine's inertia reflected through the gears, I_c = I_e G^2 * share
//    (0 while the clutch slips or is open). With the wheel spins as the
//    coordinates, the kinetic energy 1/2 I_w (w_l^2 + w_r^2) + 1/2 I_c w_c^2
//    gives the axle's mass matrix M = I_w E + I_c / 4 [1 1; 1 1], and the
//    carrier's torque acts on both wheels alike. Every angular impulse on a
//    wheel (drive, brake, rolling resistance, tyre) changes both spins by
//    M^-1 times it, and the tyre solve below sees r^2 (M^-1)_ii as the
//    wheel's share of its effective mass. So both wheels always get the
//    same torque from the differential, T_l = T_r = T_sum / 2 with
//    T_sum = T_a - I_c dw_c/dt: when one wheel slips (ice, or in the air)
//    it spins up and takes the engine with it, and the torque the other
//    wheel gets is what the slipping one can hold (its traction plus its
//    own angular acceleration), so the car barely moves and the engine
//    revs to the limiter. A limited-slip (Torsen-style) axle adds a
//    locking constraint w_l - w_r = 0 whose impulse moves torque from the
//    faster to the slower wheel, bounded by the bias ratio B:
//    |T_l - T_r| <= (B - 1) / (B + 1) |T_sum|, i.e. the gripping wheel
//    gets at most B times the slipping wheel's torque (T_sum taken from
//    the current iterate, as a friction bound takes the normal impulse).
//    It is solved with the tyres in the same Gauss-Seidel passes (its
//    effective mass is 2 / I_w: the carrier's inertia cancels in w_l - w_r).
//    A wheel whose brake can stop it within the substep is locked (w = 0)
//    and leaves the axle's mass matrix (the other wheel then drives the
//    carrier alone, M = I_w + I_c / 4); its tyre acts on the chassis alone,
//    with the brake torque / r as a further limit. Brake, handbrake and
//    rolling resistance are torques that stop a wheel but never reverse it.
//    Rejected: splitting the axle torque evenly (or by a bias) from the
//    engine torque whatever the wheels do: a car with one driven wheel on
//    ice drove away on the other; and a separate carrier body with a
//    rigid w_l + w_r = 2 w_c constraint in the Gauss-Seidel loop: with
//    I_c 40 times I_w (first gear) two passes converge poorly.
// 2. Suspension. A ray from the hub's full-bump point along chassis -Y finds
//    the ground (height field and the bodies near the vehicle). Spring length
//    l = hit distance - radius; force k (rest - l) plus bump or rebound
//    damping (implicit) on dl/dt (from the velocity along the contact normal, so a
//    slope under a moving wheel compresses it) plus the anti-roll bar
//    k_arb (compression - other side's compression); never pulling. Applied
//    along the contact normal at the contact point; a body under the wheel
//    gets the opposite. Beyond full bump a non-penetration impulse is the
//    bump stop (no wheel sinks into the ground on a hard landing).
// 3. Tyre. In the contact plane, u = v_forward - w r (patch slip speed) and
//    v_lateral. A slip curve mu(x) with initial slope mu'(0) means a force
//    N mu'(0) u / |v|: a damper of coefficient c = N mu'(0) / max(|v|, 1 mm/s)
//    on the slip speed. It is solved implicitly as a soft velocity
//    constraint (Catto's soft step: gamma = 1 / (c h)), so it is stable at
//    any speed and becomes a rigid stick constraint as |v| -> 0: no creep or
//    jitter at rest, and a car holds on a slope on its brakes. The
//    accumulated impulses are limited by the friction circle
//    (P / Pmax)^2 + (Q / Qmax)^2 <= 1 with Pmax = mu_long N h, Qmax =
//    mu_lat N h, each mu from its curve beyond the peak (the sliding value
//    once the tyre slides) times the surface friction (the terrain drag
//    map: mud 0.3, grass 0.6, rock 0.8; or the body's friction). Rolling
//    resistance is a torque C_rr N r against the spin, with C_rr =
//    tyre.rolling_resistance + tyre.soft_ground_drag * s for the surface's
//    softness s (ground_softness.h: the terrain's softness layer, mud 0.7,
//    grass 0.4; bodies 0 unless setSurfaceSoftness). Rejected: softness
//    inferred as 1 - friction: ice (0.1) dragged harder than mud. Two
//    Gauss-Seidel passes over the wheels per substep, each followed by the
//    limited-slip locks (1.); a wheel's spin changes through its axle's
//    M^-1, so a tyre impulse on one wheel of an open axle also turns the
//    other (through the carrier's inertia).
// 4. Aerodynamic drag 0.5 rho CdA |v| v at the centre of mass.
//
// Rejected: wheels as rigid bodies on joints (a stiff, slow chain whose
// contacts jitter at speed); a force-only tyre (creeps at rest and needs
// tiny steps at low speed, the classic slip singularity).
#include "vehicle/vehicle_system.h"

#include <algorithm>
#include <cmath>

namespace tumble::vehicle {
namespace {

constexpr Real kRpmPerRadps = Real(60) / (2 * kPi);
constexpr Real kMinSlipSpeed_mps = Real(0.001);  ///< see 3. above: the tyre becomes rigid below this
constexpr Real kSlipRatioFloor_mps = Real(0.5);  ///< telemetry slip ratio: denominator floor
constexpr int kTyrePasses = 2;

Real gearRatio(const GearboxDef& g, int gear) {
  if (gear == 0) return 0;
  if (gear < 0) return -g.reverseRatio * g.finalDrive;
  return g.ratios[std::size_t(std::min<int>(gear, int(g.ratios.size())) - 1)] * g.finalDrive;
}

/// Inverse effective mass of a body at point p along unit direction d.
Real invMassAlong(const physics::Body& b, const Vec3& p, const Vec3& d) {
  if (!b.isDynamic() || !b.awake) return 0;
  const Vec3 rd = (p - b.position_m).cross(d);
  return b.invMass_per_kg + rd.dot(b.invInertiaWorld * rd);
}

Vec3 pointVelocity(const physics::World& w, physics::BodyId id, const Vec3& p) {
  if (id.isNull() || !w.isValid(id)) return Vec3::Zero();
  const physics::Body& b = w.body(id);
  if (!b.isDynamic() || !b.awake) return Vec3::Zero();
  return w.currentLinearVelocity(id) + w.currentAngularVelocity(id).cross(p - b.position_m);
}

}  // namespace

VehicleSystem::VehicleSystem(physics::World& world) : m_world(world) {
  m_hook = m_world.addSubstepHook([this](physics::World&, Real h) { substep(h); });
}

VehicleSystem::~VehicleSystem() {
  m_world.removeSubstepHook(m_hook);
  for (Vehicle& v : m_vehicles)
    if (v.alive && m_world.isValid(v.chassis)) m_world.destroyBody(v.chassis);
}

VehicleSystem::Vehicle& VehicleSystem::get(VehicleId id) {
  TUMBLE_ASSERT(isValid(id), "stale or null VehicleId. Check isValid() first.");
  return m_vehicles[id.index];
}
const VehicleSystem::Vehicle& VehicleSystem::get(VehicleId id) const {
  TUMBLE_ASSERT(isValid(id), "stale or null VehicleId. Check isValid() first.");
  return m_vehicles[id.index];
}

bool VehicleSystem::isValid(VehicleId id) const {
  return !id.isNull() && id.index < m_vehicles.size() && m_vehicles[id.index].alive &&
         m_vehicles[id.index].generation == id.generation;
}

void VehicleSystem::configure(Vehicle& v) {
  const VehicleDef& d = v.def;
  v.derived = deriveAxles(d);
  const std::size_t axles = d.axles.size();
  v.axleShare.assign(axles, 0);
  int driven = 0;
  for (const AxleDef& a : d.axles) driven += a.driven ? 1 : 0;
  for (std::size_t i = 0; i < axles; ++i)
    if (d.axles[i].driven) v.axleShare[i] = d.axles[i].driveShare > 0 ? d.axles[i].driveShare : Real(1) / Real(driven);
  std::vector<Wheel> old = std::move(v.wheels);
  v.wheels.clear();
  for (std::size_t i = 0; i < axles; ++i)
    for (int side : {1, -1}) {
      Wheel w;
      w.axle = int(i);
      const Vec3& p = d.axles[i].position_m;
      w.mount_local = Vec3(side * p.x(), p.y(), p.z()) - d.chassis.centerOfMass_m;
      w.t.radius_m = d.axles[i].wheelRadius_m;
      w.t.width_m = d.axles[i].wheelWidth_m;
      w.t.springLength_m = w.t.staticLength_m = v.derived[i].staticLength_m;
      if (v.wheels.size() < old.size()) {  // keep the wheel's state across a change of parameters
        const Real radius = w.t.radius_m, width = w.t.width_m, rest = w.t.staticLength_m;
        w.t = old[v.wheels.size()].t;
        w.t.radius_m = radius, w.t.width_m = width, w.t.staticLength_m = rest;
      }
      v.wheels.push_back(w);
    }
}

void VehicleSystem::place(Vehicle& v, const Vec3& ground, Real heading) {
  // Centre of mass height so that the first axle rests at its static length.
  const AxleDef& a = v.def.axles[0];
  const Wheel& w = v.wheels[0];
  const Real comY = ground.y() + a.wheelRadius_m + v.derived[0].staticLength_m - w.mount_local.y();
  const Quat q(Eigen::AngleAxis<Real>(heading, Vec3::UnitY()));
  const Vec3 offset = q * Vec3(0, 0, -v.def.chassis.centerOfMass_m.z());
  m_world.setPosition(v.chassis, Vec3(ground.x(), comY, ground.z()) + Vec3(offset.x(), 0, offset.z()));
  m_world.setOrientation(v.chassis, q);
  m_world.setLinearVelocity(v.chassis, Vec3::Zero());
  m_world.setAngularVelocity(v.chassis, Vec3::Zero());
  const Vec3 com = m_world.body(v.chassis).position_m;
  for (Wheel& wh : v.wheels) {
    wh.t.spin_radps = 0, wh.locked = false;
    wh.t.hub_m = com + q * (wh.mount_local - Vec3::UnitY() * wh.t.springLength_m);
  }
  v.engine_radps = v.def.engine.idleRpm / kRpmPerRadps;
  v.steer_rad = 0;
  v.shiftTimer_s = 0;
  v.telemetry.speed_mps = 0;
  v.telemetry.rpm = v.def.engine.idleRpm;
}

Result<VehicleId> VehicleSystem::spawn(const VehicleDef& def, const Vec3& ground, Real heading,
                                       const std::string& where) {
  if (auto s = validateVehicleDef(def, where); !s) return makeError(s.error());
  if (!ground.allFinite() || !std::isfinite(heading))
    return makeError(where + ": spawn position and heading must be finite");
  physics::BodyDef bd;
  bd.shape = physics::Shape::box(def.chassis.size_m / 2);
  bd.mass_kg = def.chassis.mass_kg;
  bd.friction = def.chassis.friction;
  bd.restitution = def.chassis.restitution;
  auto body = m_world.createBody(bd);
  if (!body) return makeError(where + ": " + body.error());
  std::uint32_t index;
  if (!m_free.empty()) {
    index = m_free.back();
    m_free.pop_back();
  } else {
    index = std::uint32_t(m_vehicles.size());
    m_vehicles.emplace_back();
  }
  Vehicle& v = m_vehicles[index];
  const std::uint32_t generation = v.generation + 1;  // a stale handle to the slot no longer matches
  v = Vehicle{};
  v.generation = generation;
  v.alive = true;
  v.def = def;
  v.chassis = body.value();
  if (def.chassis.inertia_kgm2 != Vec3::Zero())
    if (auto st = m_world.setPrincipalInertia(v.chassis, def.chassis.inertia_kgm2); !st) {
      m_world.destroyBody(v.chassis);
      v.alive = false;
      m_free.push_back(index);
      return makeError(where + ": chassis inertia: " + st.error());
    }
  configure(v);
  place(v, ground, heading);
  ++m_alive;
  return VehicleId{index, v.generation};
}

bool VehicleSystem::remove(VehicleId id) {
  if (!isValid(id)) return false;
  Vehicle& v = m_vehicles[id.index];
  if (m_world.isValid(v.chassis)) m_world.destroyBody(v.chassis);
  const std::uint32_t gen = v.generation;
  v = Vehicle{};
  v.generation = gen;
  m_free.push_back(id.index);
  --m_alive;
  return true;
}

void VehicleSystem::setControls(VehicleId id, const VehicleControls& c) {
  Vehicle& v = get(id);
  VehicleControls k = c;
  auto clamp01 = [](Real x) { return std::isfinite(x) ? std::clamp<Real>(x, 0, 1) : Real(0); };
  k.throttle = clamp01(c.throttle);
  k.brake = clamp01(c.brake);
  k.handbrake = clamp01(c.handbrake);
  k.steer = std::isfinite(c.steer) ? std::clamp<Real>(c.steer, -1, 1) : Real(0);
  k.gear = std::clamp(c.gear, -1, int(v.def.gearbox.ratios.size()));
  // A driver asking for anything wakes the car (a sleeping chassis skips the wheel model).
  const bool asks = k.throttle > 0 || k.gear != v.controls.gear || k.steer != v.controls.steer ||
                    (v.controls.brake + v.controls.handbrake > 0 && k.brake + k.handbrake == 0);
  v.controls = k;
  if (asks && m_world.isValid(v.chassis)) m_world.wake(v.chassis);
}

const VehicleControls& VehicleSystem::controls(VehicleId id) const { return get(id).controls; }
const VehicleDef& VehicleSystem::def(VehicleId id) const { return get(id).def; }
physics::BodyId VehicleSystem::chassis(VehicleId id) const { return get(id).chassis; }
const VehicleTelemetry& VehicleSystem::telemetry(VehicleId id) const { return get(id).telemetry; }

int VehicleSystem::wheelCount(VehicleId id) const { return int(get(id).wheels.size()); }

const WheelTelemetry& VehicleSystem::wheel(VehicleId id, int i) const {
  const Vehicle& v = get(id);
  TUMBLE_ASSERT(i >= 0 && i < int(v.wheels.size()), "wheel index out of range. Check wheelCount().");
  return v.wheels[std::size_t(i)].t;
}

Status VehicleSystem::setDef(VehicleId id, const VehicleDef& def, const std::string& where) {
  if (auto s = validateVehicleDef(def, where); !s) return s;
  Vehicle& v = get(id);
  const bool reshape = def.chassis.size_m != v.def.chassis.size_m || def.chassis.mass_kg != v.def.chassis.mass_kg;
  if (!reshape) m_world.setMaterial(v.chassis, def.chassis.friction, def.chassis.restitution);
  // Given moments (from the mesh) scale with the mass; the shape of the distribution stays.
  Vec3 inertia = def.chassis.inertia_kgm2;
  if (inertia != Vec3::Zero() && def.chassis.mass_kg != v.def.chassis.mass_kg)
    inertia *= def.chassis.mass_kg / v.def.chassis.mass_kg;
  if (reshape) {
    // A new size or mass: the chassis body is remade with the same pose and
    // velocities (a new BodyId: Vehicle::chassis() gives it).
    const physics::Body& old = m_world.body(v.chassis);
    physics::BodyDef bd;
    bd.shape = physics::Shape::box(def.chassis.size_m / 2);
    bd.mass_kg = def.chassis.mass_kg;
    bd.friction = def.chassis.friction;
    bd.restitution = def.chassis.restitution;
    bd.position_m = old.position_m;
    bd.orientation = old.orientation;
    bd.linearVelocity_mps = old.linearVelocity_mps;
    bd.angularVelocity_radps = old.angularVelocity_radps;
    auto body = m_world.createBody(bd);
    if (!body) return makeError(where + ": " + body.error());
    if (inertia != Vec3::Zero()) {
      if (auto st = m_world.setPrincipalInertia(body.value(), inertia); !st) {
        m_world.destroyBody(body.value());
        return makeError(where + ": chassis inertia: " + st.error());
      }
    }
    m_world.destroyBody(v.chassis);
    v.chassis = body.value();
  }
  v.def = def;
  v.def.chassis.inertia_kgm2 = inertia;
  ++v.defChanges;
  configure(v);
  v.controls.gear = std::clamp(v.controls.gear, -1, int(def.gearbox.ratios.size()));
  v.gear = std::clamp(v.gear, -1, int(def.gearbox.ratios.size()));
  m_world.wake(v.chassis);
  return Ok{};
}

void VehicleSystem::reset(VehicleId id, const Vec3& ground, Real heading) {
  Vehicle& v = get(id);
  place(v, ground, heading);
  v.gear = v.controls.gear;
}

void VehicleSystem::beforeStep(Real dt) {
  for (Vehicle& v : m_vehicles) {
    if (!v.alive || !m_world.isValid(v.chassis)) continue;
    const physics::Body& b = m_world.body(v.chassis);
    const Vec3 forward = b.orientation * Vec3::UnitZ();
    const Real speed = b.linearVelocity_mps.dot(forward);
    // Steering: towards the asked angle at the steering rate; the largest
    // angle shrinks with speed.
    const SteeringDef& s = v.def.steering;
    const Real target = -v.controls.steer * s.maxAngle_rad / (1 + s.speedSensitivity_spm * std::abs(speed));
    const Real step = s.rate_radps * dt;
    v.steer_rad += std::clamp(target - v.steer_rad, -step, step);
    // Gear changes open the clutch for shift_time.
    if (v.controls.gear != v.gear) {
      v.gear = v.controls.gear;
      v.shiftTimer_s = v.def.gearbox.shiftTime_s;
    } else {
      v.shiftTimer_s = std::max<Real>(0, v.shiftTimer_s - dt);
    }
    for (Wheel& w : v.wheels) w.driveImpulse_Nms = w.driveTime_s = 0;
    // Bodies the wheel rays may hit during this step: those whose bounding
    // sphere comes within reach of the vehicle's (swept over the step).
    Real reach = v.def.chassis.size_m.norm() / 2 + b.linearVelocity_mps.norm() * dt + 0.5f;
    for (const AxleDef& a : v.def.axles) reach = std::max(reach, a.position_m.norm() + a.suspension.travel_m + a.wheelRadius_m);
    v.nearby.clear();
    m_world.forEachBody([&](physics::BodyId id, const physics::Body& o) {
      if (id == v.chassis) return;
      if (o.shape.type == physics::ShapeType::Plane) {
        v.nearby.push_back(id);
        return;
      }
      const Real r = reach + o.shape.boundingRadius();
      if ((o.position_m - b.position_m).squaredNorm() <= r * r) v.nearby.push_back(id);
    });
  }
}

void VehicleSystem::step(Real dt) {
  beforeStep(dt);
  m_world.step(dt);
  // Telemetry that reads the stored state.
  for (Vehicle& v : m_vehicles) {
    if (!v.alive || !m_world.isValid(v.chassis)) continue;
    const physics::Body& b = m_world.body(v.chassis);
    v.telemetry.speed_mps = b.linearVelocity_mps.dot(b.orientation * Vec3::UnitZ());
  }
}

namespace {

enum class FastRay { Hit, Miss, Unknown };

/// A short ray against a height field through surfaceAt (O(1) on a grid)
/// instead of a tree walk: intersect the plane of the triangle under the
/// current point, move there, repeat. When the point lands on the plane of
/// the triangle under it, it is on the surface: an exact hit. Rays that start
/// below the surface, run nearly parallel to it or do not settle in four
/// rounds return Unknown (the caller casts the full ray). Wheel rays are at
/// most a metre or so long, so a second crossing within one is not a concern.
FastRay surfaceRay(const physics::HeightField& f, const Vec3& o, const Vec3& d, Real length,
                   physics::HeightFieldHit* hit) {
  Real h;
  Vec3 n;
  if (!f.surfaceAt(o.x(), o.z(), &h, &n) || o.y() < h) return FastRay::Unknown;
  Vec3 p = o;
  for (int it = 0; it < 4; ++it) {
    const Real denom = n.dot(d);
    if (denom > Real(-0.2)) return FastRay::Unknown;  // grazing
    const Real t = n.dot(Vec3(p.x(), h, p.z()) - o) / denom;
    const Vec3 q = o + d * t;
    Real hq;
    Vec3 nq;
    if (!f.surfaceAt(q.x(), q.z(), &hq, &nq)) return FastRay::Unknown;
    if (std::abs(q.y() - hq) < Real(1e-4)) {
      if (t < 0) return FastRay::Unknown;
      if (t > length) return FastRay::Miss;
      hit->distance_m = t, hit->point_m = q, hit->normal = nq;
      return FastRay::Hit;
    }
    p = q, h = hq, n = nq;
  }
  return FastRay::Unknown;
}

}  // namespace

bool VehicleSystem::castWheel(const Vehicle& v, const Vec3& origin, const Vec3& down, Real length,
                              physics::RayHit* best, Real* friction, Real* softness) const {
  bool found = false;
  if (const physics::HeightField* field = m_world.heightField()) {
    physics::HeightFieldHit h;
    FastRay fast = surfaceRay(*field, origin, down, length, &h);
    if (fast == FastRay::Unknown) fast = field->rayCast(origin, down, length, &h) ? FastRay::Hit : FastRay::Miss;
    if (fast == FastRay::Hit) {
      *best = physics::RayHit{physics::BodyId{}, h.distance_m, h.point_m, h.normal};
      *friction = field->frictionAt(h.point_m.x(), h.point_m.z());
      *softness = m_groundSoftness ? std::max<Real>(m_groundSoftness->softnessAt(h.point_m.x(), h.point_m.z()), 0) : 0;
      length = h.distance_m;
      found = true;
    }
  }
  for (physics::BodyId id : v.nearby) {
    physics::RayHit hit;
    if (m_world.rayCastBody(id, origin, down, length, &hit) && hit.distance_m <= length) {
      *best = hit;
      *friction = m_world.body(id).friction;
      *softness = surfaceSoftness(id);
      length = hit.distance_m;
      found = true;
    }
  }
  return found;
}

bool VehicleSystem::setSurfaceSoftness(physics::BodyId body, Real softness) {
  if (!std::isfinite(softness) || softness < 0) return false;
  std::erase_if(m_softBodies, [&](const auto& e) { return e.first == body || !m_world.isValid(e.first); });
  if (softness > 0) m_softBodies.emplace_back(body, softness);
  return true;
}

Real VehicleSystem::surfaceSoftness(physics::BodyId body) const {
  for (const auto& [id, s] : m_softBodies)
    if (id == body) return s;
  return 0;
}

void VehicleSystem::substep(Real h) {
  m_groundSoftness = dynamic_cast<const GroundSoftness*>(m_world.heightField());
  for (Vehicle& v : m_vehicles)
    if (v.alive && m_world.isValid(v.chassis)) substepVehicle(v, h);
}

void VehicleSystem::drivetrain(Vehicle& v, Real h) {
  const VehicleDef& d = v.def;
  const EngineDef& e = d.engine;
  const Real G = v.shiftTimer_s > 0 ? 0 : gearRatio(d.gearbox, v.gear);
  const Real throttle = v.controls.throttle;
  const Real idle = e.idleRpm / kRpmPerRadps, maxW = e.maxRpm / kRpmPerRadps;
  // Mean driven wheel speed, weighted by drive share.
  Real wheelW = 0;
  for (const Wheel& w : v.wheels) wheelW += v.axleShare[std::size_t(w.axle)] / 2 * w.t.spin_radps;
  Real engineTorque = 0;
  bool engaged = false;
  if (G == 0) {
    // Neutral or shifting: the engine revs freely (idle governor below idle).
    const Real t = throttle * e.torque.eval(v.engine_radps * kRpmPerRadps) -
                   (1 - throttle) * e.brakingTorque_Nm * v.engine_radps / maxW;
    v.engine_radps = std::clamp(v.engine_radps + h * t / e.inertia_kgm2, idle, maxW);
  } else {
    const Real coupled = wheelW * G;
    const Real engage = idle * Real(1.1);
    if (coupled >= engage) {
      engaged = true;
      v.engine_radps = coupled;
      engineTorque = throttle * e.torque.eval(coupled * kRpmPerRadps) -
                     (1 - throttle) * e.brakingTorque_Nm * std::min<Real>(coupled / maxW, 1);
      if (coupled > maxW) engineTorque = std::min<Real>(engineTorque, 0);  // rev limiter
    } else if (throttle > 0) {
      // Slipping clutch: the engine held near the launch rpm passes its torque.
      v.engine_radps = std::max(coupled, idle + throttle * (e.launchRpm / kRpmPerRadps - idle));
      engineTorque = throttle * e.torque.eval(v.engine_radps * kRpmPerRadps);
    } else {
      v.engine_radps = idle;  // clutch open at a crawl with the throttle shut: no creep, no stall
    }
  }
  const Real wheelTorque = engineTorque * G * d.gearbox.efficiency;
  v.telemetry.engineTorque_Nm = engineTorque;
  v.telemetry.driveTorque_Nm = wheelTorque;
  v.telemetry.rpm = v.engine_radps * kRpmPerRadps;
  v.telemetry.gear = v.gear;
  v.telemetry.shifting = v.shiftTimer_s > 0;
  const Real reflected = engaged ? e.inertia_kgm2 * G * G : 0;
  v.axleDrive.resize(d.axles.size());
  for (std::size_t i = 0; i < d.axles.size(); ++i) {
    AxleDrive& ad = v.axleDrive[i];
    ad.torque_Nm = wheelTorque * v.axleShare[i];
    ad.carrier_kgm2 = reflected * v.axleShare[i];
    ad.lock_Nms = 0;
    ad.spin0_radps[0] = v.wheels[2 * i].t.spin_radps;
    ad.spin0_radps[1] = v.wheels[2 * i + 1].t.spin_radps;
    v.wheels[2 * i].locked = v.wheels[2 * i + 1].locked = false;
    updateAxleInertia(v, i);
  }
}

/// M^-1 of the axle's free (unlocked) wheels: M = I_w E + I_c / 4 [1 1; 1 1]
/// with both free, I_w + I_c / 4 with one (see 1. above).
void VehicleSystem::updateAxleInertia(Vehicle& v, std::size_t axle) {
  AxleDrive& ad = v.axleDrive[axle];
  const Real I = v.def.axles[axle].wheelInertia_kgm2, c = ad.carrier_kgm2 / 4;
  const bool freeL = !v.wheels[2 * axle].locked, freeR = !v.wheels[2 * axle + 1].locked;
  Real(&W)[2][2] = ad.invInertia;
  W[0][0] = W[0][1] = W[1][0] = W[1][1] = 0;
  if (freeL && freeR) {
    const Real det = I * (I + 2 * c);
    W[0][0] = W[1][1] = (I + c) / det;
    W[0][1] = W[1][0] = -c / det;
  } else if (freeL) {
    W[0][0] = 1 / (I + c);
  } else if (freeR) {
    W[1][1] = 1 / (I + c);
  }
}

/// An angular impulse (N m s, + forward) on one wheel: both wheels of its
/// axle respond through the differential (zero on a locked wheel).
void VehicleSystem::spinImpulse(Vehicle& v, std::size_t wheel, Real impulse) {
  const AxleDrive& ad = v.axleDrive[wheel / 2];
  const std::size_t k = wheel % 2, base = wheel - k;
  for (std::size_t j = 0; j < 2; ++j) v.wheels[base + j].t.spin_radps += ad.invInertia[j][k] * impulse;
}

/// Limited-slip locking constraint w_l - w_r = 0 on every driven LSD axle
/// with both wheels free; the accumulated impulse is bounded by the bias.
void VehicleSystem::solveLimitedSlip(Vehicle& v, Real h) {
  for (std::size_t i = 0; i < v.axleDrive.size(); ++i) {
    const AxleDef& a = v.def.axles[i];
    AxleDrive& ad = v.axleDrive[i];
    Wheel& l = v.wheels[2 * i];
    Wheel& r = v.wheels[2 * i + 1];
    if (!a.driven || a.differential != Differential::LimitedSlip || l.locked || r.locked) continue;
    const Real(&W)[2][2] = ad.invInertia;
    const Real k = W[0][0] + W[1][1] - W[0][1] - W[1][0];
    const Real carrierRate = (l.t.spin_radps - ad.spin0_radps[0] + r.t.spin_radps - ad.spin0_radps[1]) / (2 * h);
    const Real sum = ad.torque_Nm - ad.carrier_kgm2 * carrierRate;
    const Real bound = (a.lsdBias - 1) / (a.lsdBias + 1) * std::abs(sum) * h / 2;
    const Real lock = std::clamp(ad.lock_Nms - (l.t.spin_radps - r.t.spin_radps) / k, -bound, bound);
    const Real d = lock - ad.lock_Nms;
    ad.lock_Nms = lock;
    spinImpulse(v, 2 * i, d);
    spinImpulse(v, 2 * i + 1, -d);
  }
}

void VehicleSystem::substepVehicle(Vehicle& v, Real h) {
  const physics::Body& body = m_world.body(v.chassis);
  if (!body.isDynamic() || !body.awake) {
    for (Wheel& w : v.wheels) w.t.spin_radps = 0;
    return;
  }
  const VehicleDef& d = v.def;
  const Quat q = body.orientation;
  const Vec3 up = q * Vec3::UnitY();
  const Vec3 com = body.position_m;
  drivetrain(v, h);

  // Aerodynamic drag at the centre of mass.
  {
    const Vec3 vel = m_world.currentLinearVelocity(v.chassis);
    const Real k = Real(0.5) * d.chassis.airDensity_kgpm3 * d.chassis.dragArea_m2;
    if (k > 0) m_world.applyImpulseNow(v.chassis, -k * vel.norm() * vel * h, com);
  }

  // Wheel spin: drive, then brakes and rolling resistance (never reversing).
  const Real brakeIn = v.controls.brake, handIn = v.controls.handbrake;
  for (std::size_t i = 0; i < v.axleDrive.size(); ++i) {
    const Real half = v.axleDrive[i].torque_Nm * h / 2;  // the carrier's torque acts on both wheels alike
    spinImpulse(v, 2 * i, half);
    spinImpulse(v, 2 * i + 1, half);
  }
  for (std::size_t i = 0; i < v.wheels.size(); ++i) {
    Wheel& w = v.wheels[i];
    const AxleDef& a = d.axles[std::size_t(w.axle)];
    const Real brake = a.brakeTorque_Nm * brakeIn + a.handbrakeTorque_Nm * handIn;
    if (brake <= 0) continue;
    const Real Wii = v.axleDrive[i / 2].invInertia[i % 2][i % 2];
    if (std::abs(w.t.spin_radps) <= Wii * brake * h) {
      spinImpulse(v, i, -w.t.spin_radps / Wii);
      w.t.spin_radps = 0;
      w.locked = true;
      updateAxleInertia(v, i / 2);
    } else {
      spinImpulse(v, i, -std::copysign(brake * h, w.t.spin_radps));
    }
  }

  // Suspension: ray casts and spring lengths first (the anti-roll bar needs both sides).
  struct Contact {
    Vec3 point, normal, longDir, latDir;
    Real load = 0, friction = 1, softness = 0, cLong = 0, cLat = 0, pMaxMu = 0, qMaxMu = 0, brakeLimit = 0;
    Real P = 0, Q = 0;
    physics::BodyId ground;
  };
  Contact contacts[16];
  const std::size_t nw = std::min<std::size_t>(v.wheels.size(), 16);
  for (std::size_t i = 0; i < nw; ++i) {
    Wheel& w = v.wheels[i];
    const AxleDef& a = d.axles[std::size_t(w.axle)];
    const Vec3 mount = com + q * w.mount_local;
    physics::RayHit hit;
    Real friction = 1, softness = 0;
    const Real reach = a.suspension.travel_m + a.wheelRadius_m;
    w.t.contact = castWheel(v, mount, -up, reach, &hit, &friction, &softness) && hit.normal.dot(up) > Real(0.2);
    w.t.springLength_m = w.t.contact ? hit.distance_m - a.wheelRadius_m : a.suspension.travel_m;
    w.t.hub_m = mount - up * std::max<Real>(w.t.springLength_m, 0);
    w.t.steer_rad = a.steered ? v.steer_rad : 0;
    w.t.load_N = 0;
    if (!w.t.contact) {
      w.t.ground = {};
      w.t.slipRatio = w.t.slipAngle_rad = w.t.slipSpeed_mps = w.t.surfaceFriction = w.t.surfaceSoftness = 0;
      continue;
    }
    Contact& c = contacts[i];
    c.point = hit.point_m;
    c.normal = hit.normal;
    c.ground = hit.body;
    c.friction = friction;
    c.softness = softness;
    w.t.ground = hit.body;
    w.t.contactPoint_m = hit.point_m;
    w.t.contactNormal = hit.normal;
    w.t.surfaceFriction = friction;
    w.t.surfaceSoftness = softness;
  }
  for (std::size_t i = 0; i < nw; ++i) {
    Wheel& w = v.wheels[i];
    if (!w.t.contact) continue;
    const AxleDef& a = d.axles[std::size_t(w.axle)];
    const DerivedAxle& da = v.derived[std::size_t(w.axle)];
    Contact& c = contacts[i];
    const Vec3 mount = com + q * w.mount_local;
    const Vec3 rel = pointVelocity(m_world, v.chassis, mount) - pointVelocity(m_world, c.ground, c.point);
    const Real lengthRate = rel.dot(c.normal) / std::max<Real>(c.normal.dot(up), Real(0.2));
    const Real l = w.t.springLength_m;
    const Wheel& other = v.wheels[i ^ 1];
    const Real otherLength = other.t.contact ? other.t.springLength_m : a.suspension.travel_m;
    const Real spring = da.stiffness_Npm * std::max<Real>(a.suspension.restLength_m - l, 0) +
                        a.suspension.antiRoll_Npm * (otherLength - l);
    // The damper is implicit (c h k / (1 + c h k) of the relative normal
    // velocity at most): explicit, it would blow up a light body under the
    // wheel (c h / m > 2 for a rag-doll's forearm).
    const Real kn = invMassAlong(body, c.point, c.normal) +
                    (c.ground.isNull() ? 0 : invMassAlong(m_world.body(c.ground), c.point, c.normal));
    const Real damping = lengthRate < 0 ? da.bump_Nspm : da.rebound_Nspm;
    const Real damper = -damping * lengthRate * h / (1 + damping * h * kn);
    Real impulse = std::max<Real>(spring * h + damper, 0);
    if (l < 0) {
      // Bump stop: the hub is above full bump; stop the approach along the
      // normal and push out a fifth of the overlap per substep.
      const Vec3 vc = pointVelocity(m_world, v.chassis, c.point) - pointVelocity(m_world, c.ground, c.point);
      const Real target = -Real(0.2) * l / h;
      const Real extra = kn > 0 ? std::max<Real>((target - vc.dot(c.normal)) / kn - impulse, 0) : 0;
      impulse += extra;
    }
    m_world.applyImpulseNow(v.chassis, impulse * c.normal, c.point);
    if (!c.ground.isNull()) m_world.applyImpulseNow(c.ground, -impulse * c.normal, c.point);
    c.load = impulse / h;
    w.t.load_N = c.load;
  }

  // Tyres: contact frames, slip, limits.
  const TyreDef& tyre = d.tyre;
  const Real slopeLong = tyre.longitudinal.initialSlope(), slopeLat = tyre.lateral.initialSlope();
  const Real peakLong = tyre.longitudinal.argMax(), peakLat = tyre.lateral.argMax();
  for (std::size_t i = 0; i < nw; ++i) {
    Wheel& w = v.wheels[i];
    if (!w.t.contact) continue;
    Contact& c = contacts[i];
    const AxleDef& a = d.axles[std::size_t(w.axle)];
    const Real s = std::sin(w.t.steer_rad), co = std::cos(w.t.steer_rad);
    const Vec3 heading = q * Vec3(s, 0, co);
    Vec3 lon = heading - c.normal * c.normal.dot(heading);
    if (lon.squaredNorm() < Real(1e-8)) {
      w.t.contact = false;
      continue;
    }
    lon.normalize();
    c.longDir = lon;
    c.latDir = c.normal.cross(lon);
    const Vec3 vc = pointVelocity(m_world, v.chassis, c.point) - pointVelocity(m_world, c.ground, c.point);
    const Real vLong = vc.dot(lon), vLat = vc.dot(c.latDir);
    const Real speed = std::max(std::abs(vLong), kMinSlipSpeed_mps);
    const Real r = a.wheelRadius_m;
    const Real u = vLong - w.t.spin_radps * r;
    const Real kappa = -u / std::max(std::abs(vLong), kSlipRatioFloor_mps);
    const Real alpha = std::atan2(vLat, std::max(std::abs(vLong), kSlipRatioFloor_mps));
    w.t.slipRatio = kappa;
    w.t.slipAngle_rad = alpha;
    w.t.slipSpeed_mps = std::sqrt(u * u + vLat * vLat);
    const Real N = c.load * c.friction;
    c.cLong = N * slopeLong / speed;
    c.cLat = N * slopeLat / speed;
    c.pMaxMu = c.friction * tyre.longitudinal.eval(std::max(std::abs(kappa), peakLong));
    c.qMaxMu = c.friction * tyre.lateral.eval(std::max(std::abs(alpha), peakLat));
    c.brakeLimit = w.locked ? (a.brakeTorque_Nm * brakeIn + a.handbrakeTorque_Nm * handIn) * h / r : 0;
    // Rolling resistance (more on soft ground: the surface's softness, not
    // its friction, so ice drags like asphalt): a torque against the spin.
    if (!w.locked) {
      const Real crr = tyre.rollingResistance + tyre.softGroundDrag * c.softness;
      const Real Wii = v.axleDrive[i / 2].invInertia[i % 2][i % 2];
      const Real p = std::min(std::abs(w.t.spin_radps) / Wii, crr * c.load * r * h);
      spinImpulse(v, i, -std::copysign(p, w.t.spin_radps));
    }
  }
  for (int pass = 0; pass < kTyrePasses; ++pass) {
    for (std::size_t i = 0; i < nw; ++i) {
      Wheel& w = v.wheels[i];
      if (!w.t.contact || contacts[i].load <= 0) continue;
      Contact& c = contacts[i];
      const Real r = d.axles[std::size_t(w.axle)].wheelRadius_m;
      const physics::Body* g = c.ground.isNull() ? nullptr : &m_world.body(c.ground);
      const Vec3 vc = pointVelocity(m_world, v.chassis, c.point) - pointVelocity(m_world, c.ground, c.point);
      const Real u = vc.dot(c.longDir) - w.t.spin_radps * r;
      const Real vLat = vc.dot(c.latDir);
      Real kLong = invMassAlong(body, c.point, c.longDir) + (g ? invMassAlong(*g, c.point, c.longDir) : 0);
      const Real kLat = invMassAlong(body, c.point, c.latDir) + (g ? invMassAlong(*g, c.point, c.latDir) : 0);
      if (!w.locked) kLong += r * r * v.axleDrive[i / 2].invInertia[i % 2][i % 2];
      const Real gLong = c.cLong > 0 ? 1 / (c.cLong * h) : Real(1e30);
      const Real gLat = c.cLat > 0 ? 1 / (c.cLat * h) : Real(1e30);
      Real P = c.P - (u + gLong * c.P) / (kLong + gLong);
      Real Q = c.Q - (vLat + gLat * c.Q) / (kLat + gLat);
      // Friction circle (an ellipse when the two curves differ).
      Real pMax = c.pMaxMu * c.load * h, qMax = c.qMaxMu * c.load * h;
      if (w.locked) pMax = std::min(pMax, c.brakeLimit);
      const Real e = (pMax > 0 ? (P / pMax) * (P / pMax) : (P != 0 ? 1e30f : 0)) +
                     (qMax > 0 ? (Q / qMax) * (Q / qMax) : (Q != 0 ? 1e30f : 0));
      if (e > 1) {
        const Real scale = 1 / std::sqrt(e);
        P *= scale, Q *= scale;
      }
      const Vec3 J = (P - c.P) * c.longDir + (Q - c.Q) * c.latDir;
      m_world.applyImpulseNow(v.chassis, J, c.point);
      if (g) m_world.applyImpulseNow(c.ground, -J, c.point);
      if (!w.locked) spinImpulse(v, i, -(P - c.P) * r);
      c.P = P, c.Q = Q;
    }
    solveLimitedSlip(v, h);
  }
  // What the differentials delivered: T_sum / 2 each, plus the limited-slip transfer.
  for (std::size_t i = 0; i < v.axleDrive.size(); ++i) {
    const AxleDrive& ad = v.axleDrive[i];
    Wheel& l = v.wheels[2 * i];
    Wheel& r = v.wheels[2 * i + 1];
    Real left = 0, right = 0;
    if (d.axles[i].driven) {
      const Real carrierRate = (l.t.spin_radps - ad.spin0_radps[0] + r.t.spin_radps - ad.spin0_radps[1]) / (2 * h);
      const Real sum = ad.torque_Nm - ad.carrier_kgm2 * carrierRate;
      left = sum / 2 + ad.lock_Nms / h, right = sum / 2 - ad.lock_Nms / h;
    }
    l.driveImpulse_Nms += left * h, r.driveImpulse_Nms += right * h;
    l.driveTime_s += h, r.driveTime_s += h;
    l.t.driveTorque_Nm = l.driveImpulse_Nms / l.driveTime_s;
    r.t.driveTorque_Nm = r.driveImpulse_Nms / r.driveTime_s;
  }
  for (Wheel& w : v.wheels) w.t.rotation_rad = std::fmod(w.t.rotation_rad + w.t.spin_radps * h, 2 * kPi);
  v.telemetry.speed_mps = m_world.currentLinearVelocity(v.chassis).dot(q * Vec3::UnitZ());
}

}  // namespace tumble::vehicle
