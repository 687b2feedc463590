#include "particles/particle_system.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace tumble::particles {

void ParticlePool::reserve(std::size_t n) {
  for (auto* a : {&px, &py, &pz, &vx, &vy, &vz, &age_s, &invLifetime, &angle_rad, &spin_radps}) a->resize(n);
}

void ParticlePool::removeSwap(std::uint32_t i) {
  const std::uint32_t last = --count;
  if (i == last) return;
  for (auto* a : {&px, &py, &pz, &vx, &vy, &vz, &age_s, &invLifetime, &angle_rad, &spin_radps})
    (*a)[i] = (*a)[last];
}

ParticleSystem::ParticleSystem(std::uint64_t seed) : m_seed(seed) {}

bool ParticleSystem::redefine(EmitterId id, const EmitterDef& def) {
  assert(validate(def) && "EmitterDef must pass particles::validate() before redefine()");
  Emitter* e = get(id);
  if (!e) return false;
  const bool scriptRate = e->rate_per_s != e->def.rate_per_s;
  e->def = def;
  std::stable_sort(e->def.bursts.begin(), e->def.bursts.end(),
            [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
  if (!scriptRate) e->rate_per_s = def.rate_per_s;
  if (std::size_t(def.maxCount) > e->pool.px.size()) e->pool.reserve(std::size_t(def.maxCount));
  e->nextBurst = std::min(e->nextBurst, e->def.bursts.size());
  return true;
}

EmitterId ParticleSystem::create(const EmitterDef& def, const Eigen::Vector3f& position_m,
                                 const Eigen::Quaternionf& rotation) {
  assert(validate(def) && "EmitterDef must pass particles::validate() before create()");
  std::uint32_t index;
  if (!m_free.empty()) {
    index = m_free.back();
    m_free.pop_back();
  } else {
    index = std::uint32_t(m_slots.size());
    m_slots.emplace_back();
  }
  Slot& slot = m_slots[index];
  slot.live = true;
  Emitter& e = slot.emitter;
  e = Emitter{};
  e.def = def;
  e.def.direction.normalize();
  std::stable_sort(e.def.bursts.begin(), e.def.bursts.end(),
                   [](const Burst& a, const Burst& b) { return a.time_s < b.time_s; });
  e.position_m = e.previousPosition_m = position_m;
  e.rotation = rotation.normalized();
  e.rate_per_s = def.rate_per_s;
  // A stream of its own per emitter: the run's seed mixed with the creation count.
  e.random.state = m_seed * 0xD1B54A32D192ED03ull + (++m_created) * 0x9E3779B97F4A7C15ull;
  e.random.next();
  e.pool.reserve(std::size_t(def.maxCount));
  ++m_live;
  return EmitterId{index, slot.generation};
}

bool ParticleSystem::isValid(EmitterId id) const {
  return !id.isNull() && id.index < m_slots.size() && m_slots[id.index].live &&
         m_slots[id.index].generation == id.generation;
}

const Emitter* ParticleSystem::get(EmitterId id) const {
  return isValid(id) ? &m_slots[id.index].emitter : nullptr;
}

Emitter* ParticleSystem::get(EmitterId id) { return isValid(id) ? &m_slots[id.index].emitter : nullptr; }

bool ParticleSystem::remove(EmitterId id) {
  if (!isValid(id)) return false;
  Slot& slot = m_slots[id.index];
  slot.live = false;
  ++slot.generation;
  slot.emitter.pool = ParticlePool{};  // give the memory back
  m_free.push_back(id.index);
  --m_live;
  return true;
}

void ParticleSystem::stop(EmitterId id) {
  if (Emitter* e = get(id)) {
    e->stopped = true;
    e->pendingBurst = 0;
  }
}

void ParticleSystem::burst(EmitterId id, int n, bool thenStop) {
  Emitter* e = get(id);
  if (!e || e->stopped) return;
  if (n > 0) e->pendingBurst = int(std::min<long long>(kMaxParticlesPerEmitter, (long long)e->pendingBurst + n));
  e->stopAfterBurst = e->stopAfterBurst || thenStop;
}

void ParticleSystem::setRate(EmitterId id, float rate_per_s) {
  if (Emitter* e = get(id)) e->rate_per_s = std::isfinite(rate_per_s) ? std::clamp(rate_per_s, 0.0f, 1e6f) : 0.0f;
}

void ParticleSystem::setPose(EmitterId id, const Eigen::Vector3f& position_m, const Eigen::Quaternionf& rotation,
                             bool teleport) {
  Emitter* e = get(id);
  if (!e) return;
  e->position_m = position_m;
  if (teleport) e->previousPosition_m = position_m;
  e->rotation = rotation.normalized();
}

void ParticleSystem::setDirection(EmitterId id, const Eigen::Vector3f& direction) {
  Emitter* e = get(id);
  if (e && direction.allFinite() && direction.norm() > 1e-6f) e->def.direction = direction.normalized();
}

void ParticleSystem::attach(EmitterId id, std::uint64_t anchor, const Eigen::Vector3f& offset_m) {
  if (Emitter* e = get(id)) {
    e->anchor = anchor;
    e->anchorOffset_m = offset_m;
  }
}

void ParticleSystem::setAnchorState(EmitterId id, const Eigen::Vector3f& position_m,
                                    const Eigen::Quaternionf& rotation, const Eigen::Vector3f& velocity_mps,
                                    const Eigen::Vector3f& angularVelocity_radps) {
  Emitter* e = get(id);
  if (!e) return;
  const Eigen::Vector3f arm = rotation * e->anchorOffset_m;
  e->position_m = position_m + arm;
  e->rotation = rotation.normalized();
  e->velocity_mps = velocity_mps + angularVelocity_radps.cross(arm);
}

void ParticleSystem::anchorLost(EmitterId id) {
  if (Emitter* e = get(id)) {
    e->anchor = kNoAnchor;
    e->velocity_mps.setZero();
  }
  stop(id);
}

int ParticleSystem::count(EmitterId id) const {
  const Emitter* e = get(id);
  return e ? int(e->pool.count) : 0;
}

int ParticleSystem::particleCount() const {
  int n = 0;
  forEach([&](EmitterId, const Emitter& e) { n += int(e.pool.count); });
  return n;
}

Eigen::Vector3f ParticleSystem::sampleCap(Random& r, const Eigen::Vector3f& axis, float spread_rad) {
  // Uniform on the cap: cos(theta) uniform in [cos(spread), 1], phi uniform.
  const float cosTheta = 1.0f - r.uniform() * (1.0f - std::cos(spread_rad));
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  const float phi = 6.28318530718f * r.uniform();
  // Any basis (u, w) perpendicular to the axis.
  Eigen::Vector3f u = std::abs(axis.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
  u = (u - axis * axis.dot(u)).normalized();
  const Eigen::Vector3f w = axis.cross(u);
  return (axis * cosTheta + (u * std::cos(phi) + w * std::sin(phi)) * sinTheta).normalized();
}

// One new particle born at `birthFraction` of the step (0: its start, 1: its
// end), advanced over the rest of the step with the same update rule.
void ParticleSystem::spawnOne(Emitter& e, float birthFraction, float dt_s) {
  ParticlePool& p = e.pool;
  if (p.count >= std::uint32_t(e.def.maxCount)) {
    ++e.dropped;
    return;
  }
  const EmitterDef& d = e.def;
  Random& r = e.random;
  // Start point and direction in the emitter's frame.
  Eigen::Vector3f local = Eigen::Vector3f::Zero();
  Eigen::Vector3f dir = d.direction;
  switch (d.shape) {
    case EmitterShape::Point: break;
    case EmitterShape::Box: {
      // Three draws in a fixed order: a constructor's arguments are evaluated
      // in an order C++ leaves open (GCC goes right to left, clang left to
      // right), so drawing inside the call gave each compiler other
      // particles. z, y, x is the order the GCC builds always drew in, so
      // recorded hashes and replays are kept.
      const float z = r.uniform() - 0.5f;
      const float y = r.uniform() - 0.5f;
      const float x = r.uniform() - 0.5f;
      local = Eigen::Vector3f(x, y, z).cwiseProduct(d.boxSize_m);
      break;
    }
    case EmitterShape::Sphere: {
      // Uniform in the ball: a uniform direction, radius ~ cbrt(u).
      Eigen::Vector3f n = sampleCap(r, Eigen::Vector3f::UnitY(), 3.14159265f);
      local = n * (d.radius_m * std::cbrt(r.uniform()));
      break;
    }
    case EmitterShape::Cone: {
      // A point on the base disc (uniform: radius ~ sqrt(u)); the direction
      // leans outwards with it, up to cone_angle at the rim, so the flow
      // spreads like a cone (as a nozzle or a chimney).
      Eigen::Vector3f u = std::abs(dir.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
      u = (u - dir * dir.dot(u)).normalized();
      const Eigen::Vector3f w = dir.cross(u);
      const float rho = std::sqrt(r.uniform());
      const float phi = 6.28318530718f * r.uniform();
      const Eigen::Vector3f radial = u * std::cos(phi) + w * std::sin(phi);
      local = radial * (rho * d.radius_m);
      const float lean = rho * d.coneAngle_rad;
      dir = dir * std::cos(lean) + radial * std::sin(lean);
      break;
    }
  }
  if (d.spread_rad > 0) dir = sampleCap(r, dir, d.spread_rad);
  const float speed = r.range(d.speedMin_mps, d.speedMax_mps);
  Eigen::Vector3f pos, vel;
  Eigen::Vector3f accel;
  if (d.space == SimSpace::World) {
    const Eigen::Vector3f origin = e.previousPosition_m + (e.position_m - e.previousPosition_m) * birthFraction;
    pos = origin + e.rotation * local;
    vel = e.rotation * dir * speed + d.inheritVelocity * e.velocity_mps;
    accel = m_gravity * d.gravityScale + d.acceleration_mps2;
  } else {
    pos = local;
    vel = dir * speed;
    accel = e.rotation.conjugate() * (m_gravity * d.gravityScale) + d.acceleration_mps2;
  }
  // The rest of the step, with the update rule of updateParticles.
  const float tau = (1.0f - birthFraction) * dt_s;
  vel = (vel + accel * tau) * std::exp(-d.drag_per_s * tau);
  pos += vel * tau;
  const std::uint32_t i = p.count++;
  p.px[i] = pos.x(), p.py[i] = pos.y(), p.pz[i] = pos.z();
  p.vx[i] = vel.x(), p.vy[i] = vel.y(), p.vz[i] = vel.z();
  p.age_s[i] = tau;
  p.invLifetime[i] = 1.0f / r.range(d.lifetimeMin_s, d.lifetimeMax_s);
  p.spin_radps[i] = r.range(d.spinMin_radps, d.spinMax_radps);
  p.angle_rad[i] = 6.28318530718f * r.uniform() + p.spin_radps[i] * tau;
}

void ParticleSystem::updateParticles(Emitter& e, float dt_s) const {
  ParticlePool& p = e.pool;
  const std::uint32_t n = p.count;
  if (n == 0) return;
  const EmitterDef& d = e.def;
  Eigen::Vector3f a = m_gravity * d.gravityScale;
  if (d.space == SimSpace::Local) a = e.rotation.conjugate() * a;
  a += d.acceleration_mps2;
  const float damp = std::exp(-d.drag_per_s * dt_s);
  const float ax = a.x() * dt_s, ay = a.y() * dt_s, az = a.z() * dt_s;
  // Plain loops over contiguous floats: the compiler vectorises them.
  float* __restrict px = p.px.data();
  float* __restrict py = p.py.data();
  float* __restrict pz = p.pz.data();
  float* __restrict vx = p.vx.data();
  float* __restrict vy = p.vy.data();
  float* __restrict vz = p.vz.data();
  float* __restrict age = p.age_s.data();
  float* __restrict angle = p.angle_rad.data();
  const float* __restrict spin = p.spin_radps.data();
  for (std::uint32_t i = 0; i < n; ++i) {
    vx[i] = (vx[i] + ax) * damp;
    vy[i] = (vy[i] + ay) * damp;
    vz[i] = (vz[i] + az) * damp;
    px[i] += vx[i] * dt_s;
    py[i] += vy[i] * dt_s;
    pz[i] += vz[i] * dt_s;
    age[i] += dt_s;
    angle[i] += spin[i] * dt_s;
  }
  // Remove the dead: age >= lifetime.
  const float* invLife = p.invLifetime.data();
  for (std::uint32_t i = 0; i < p.count;) {
    if (p.age_s[i] * invLife[i] >= 1.0f) p.removeSwap(i);
    else ++i;
  }
}

void ParticleSystem::spawnParticles(Emitter& e, float dt_s) {
  if (e.stopped) return;
  const EmitterDef& d = e.def;
  const double t0 = e.age_s, t1 = e.age_s + double(dt_s);
  // Emission ends at the duration, if there is one.
  const double window = d.duration_s > 0 ? std::clamp(double(d.duration_s) - t0, 0.0, double(dt_s)) : double(dt_s);
  // Timed bursts due in [t0, t1) (the first step includes time 0).
  while (e.nextBurst < d.bursts.size() && double(d.bursts[e.nextBurst].time_s) < t1) {
    const Burst& b = d.bursts[e.nextBurst++];
    const float f = std::clamp(float((double(b.time_s) - t0) / double(dt_s)), 0.0f, 1.0f);
    for (int k = 0; k < b.count; ++k) spawnOne(e, f, dt_s);
  }
  // Continuous rate: the k-th whole particle is due at fraction f_k of the step.
  const double emitted = double(e.rate_per_s) * window;
  if (emitted > 0) {
    const double total = e.carry + emitted;
    const long long whole = (long long)std::floor(total + 1e-9);  // 1e-9: 0.999999... from rounding is 1
    for (long long k = 1; k <= whole; ++k) {
      const double f = (double(k) - e.carry) / emitted * window / double(dt_s);
      spawnOne(e, float(std::clamp(f, 0.0, 1.0)), dt_s);
    }
    e.carry = std::max(0.0, total - double(whole));
  }
  if (d.duration_s > 0 && t1 >= d.duration_s) e.stopped = true;
}

void ParticleSystem::step(float dt_s) {
  if (!(dt_s > 0)) return;
  for (std::uint32_t i = 0; i < m_slots.size(); ++i) {
    Slot& slot = m_slots[i];
    if (!slot.live) continue;
    Emitter& e = slot.emitter;
    if (e.anchor == kNoAnchor) e.velocity_mps = (e.position_m - e.previousPosition_m) / dt_s;
    // burst(n) from the script: born at the step's start at the old pose,
    // then moved by the full step like every other particle.
    if (e.pendingBurst > 0) {
      const Eigen::Vector3f keep = e.position_m;
      e.position_m = e.previousPosition_m;
      const int n = e.pendingBurst;
      e.pendingBurst = 0;
      for (int k = 0; k < n; ++k) spawnOne(e, 1.0f, dt_s);  // fraction 1: not advanced here
      e.position_m = keep;
    }
    if (e.stopAfterBurst) e.stopped = true;
    updateParticles(e, dt_s);
    spawnParticles(e, dt_s);
    e.age_s += double(dt_s);
    e.previousPosition_m = e.position_m;
    if (e.stopped && e.pool.count == 0) remove(EmitterId{i, slot.generation});
  }
}

}  // namespace tumble::particles
