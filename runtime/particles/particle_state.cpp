// ParticleSystem::saveState / restoreState: every emitter and its live
// particles as exact bits, for snapshots of a running scene. An emitter is
// plain data (no body, no GL: the app resolves its anchor number each step),
// so a snapshot holds whole emitters, those spawned after on_start too, and
// the saved set replaces the system's. Each particle's ten arrays are stored
// up to its live count; the pool's size (max_count) comes back as it was.
#include <algorithm>
#include <cmath>

#include "particles/particle_system.h"

namespace tumble::particles {

namespace {

constexpr std::uint32_t kStateMagic = 0x54505254;  // "TPRT"
constexpr std::uint32_t kStateVersion = 1;
constexpr std::size_t kMaxSlots = std::size_t(1) << 20;
constexpr std::size_t kMaxKeys = std::size_t(1) << 16;

/// The definition's fixed-size fields, in one plain struct.
struct DefFields {
  float rate_per_s, duration_s, lifetimeMin_s, lifetimeMax_s;
  std::int32_t maxCount;
  std::int32_t shape;
  Eigen::Vector3f boxSize_m;
  float radius_m, coneAngle_rad;
  Eigen::Vector3f direction;
  float spread_rad, speedMin_mps, speedMax_mps, inheritVelocity, gravityScale;
  Eigen::Vector3f acceleration_mps2;
  float drag_per_s, spinMin_radps, spinMax_radps, stretch_s;
  std::int32_t blend, space;
};

void writeDef(ByteWriter& w, const EmitterDef& d) {
  w.pod(DefFields{d.rate_per_s, d.duration_s, d.lifetimeMin_s, d.lifetimeMax_s, d.maxCount, std::int32_t(d.shape),
                  d.boxSize_m, d.radius_m, d.coneAngle_rad, d.direction, d.spread_rad, d.speedMin_mps,
                  d.speedMax_mps, d.inheritVelocity, d.gravityScale, d.acceleration_mps2, d.drag_per_s,
                  d.spinMin_radps, d.spinMax_radps, d.stretch_s, std::int32_t(d.blend), std::int32_t(d.space)});
  w.vec(d.bursts);
  w.vec(d.size_m.keys);
  w.vec(d.color.keys);
  w.vec(d.alpha.keys);
}

EmitterDef readDef(ByteReader& r) {
  const auto f = r.pod<DefFields>();
  EmitterDef d;
  d.rate_per_s = f.rate_per_s;
  d.duration_s = f.duration_s;
  d.lifetimeMin_s = f.lifetimeMin_s;
  d.lifetimeMax_s = f.lifetimeMax_s;
  d.maxCount = f.maxCount;
  d.shape = EmitterShape(f.shape);
  d.boxSize_m = f.boxSize_m;
  d.radius_m = f.radius_m;
  d.coneAngle_rad = f.coneAngle_rad;
  d.direction = f.direction;
  d.spread_rad = f.spread_rad;
  d.speedMin_mps = f.speedMin_mps;
  d.speedMax_mps = f.speedMax_mps;
  d.inheritVelocity = f.inheritVelocity;
  d.gravityScale = f.gravityScale;
  d.acceleration_mps2 = f.acceleration_mps2;
  d.drag_per_s = f.drag_per_s;
  d.spinMin_radps = f.spinMin_radps;
  d.spinMax_radps = f.spinMax_radps;
  d.stretch_s = f.stretch_s;
  d.blend = BlendMode(f.blend);
  d.space = SimSpace(f.space);
  d.bursts = r.vec<Burst>(kMaxKeys);
  d.size_m.keys = r.vec<Curve1::Key>(kMaxKeys);
  d.color.keys = r.vec<Curve3::Key>(kMaxKeys);
  d.alpha.keys = r.vec<Curve1::Key>(kMaxKeys);
  return d;
}

/// The emitter's state besides its definition and pool, in one plain struct.
struct EmitterFields {
  Eigen::Vector3f position_m;
  Eigen::Quaternionf rotation;
  Eigen::Vector3f previousPosition_m, velocity_mps;
  std::uint64_t anchor;
  Eigen::Vector3f anchorOffset_m;
  float rate_per_s;
  double age_s, carry;
  std::uint64_t nextBurst;
  std::int32_t pendingBurst;
  std::uint8_t stopAfterBurst, stopped;
  std::uint64_t dropped, random;
  std::uint64_t poolSize;  ///< the arrays' length (max_count when created or redefined)
  std::uint32_t count;     ///< live particles
};

}  // namespace

std::string ParticleSystem::saveState() const {
  static_assert(kBitwise<DefFields> && kBitwise<EmitterFields> && kBitwise<Burst> && kBitwise<Curve1::Key> &&
                kBitwise<Curve3::Key>);
  ByteWriter w;
  w.pod(kStateMagic);
  w.pod(kStateVersion);
  w.pod(std::uint64_t(m_slots.size()));
  for (const Slot& s : m_slots) {
    w.pod(s.generation);
    w.pod(std::uint8_t(s.live));
    if (!s.live) continue;
    const Emitter& e = s.emitter;
    writeDef(w, e.def);
    const ParticlePool& p = e.pool;
    w.pod(EmitterFields{e.position_m, e.rotation, e.previousPosition_m, e.velocity_mps, e.anchor, e.anchorOffset_m,
                        e.rate_per_s, e.age_s, e.carry, std::uint64_t(e.nextBurst), std::int32_t(e.pendingBurst),
                        std::uint8_t(e.stopAfterBurst), std::uint8_t(e.stopped), e.dropped, e.random.state,
                        std::uint64_t(p.px.size()), p.count});
    for (const std::vector<float>* a : {&p.px, &p.py, &p.pz, &p.vx, &p.vy, &p.vz, &p.age_s, &p.invLifetime,
                                        &p.angle_rad, &p.spin_radps})
      w.vec(std::vector<float>(a->begin(), a->begin() + p.count));
  }
  w.vec(m_free);
  w.pod(std::int32_t(m_live));
  w.pod(m_seed);
  w.pod(m_created);
  w.pod(m_gravity);
  return w.take();
}

Status ParticleSystem::restoreState(const std::string& bytes) {
  ByteReader r(bytes);
  if (r.pod<std::uint32_t>() != kStateMagic || !r.ok()) return makeError("not a particle state");
  if (const auto v = r.pod<std::uint32_t>(); v != kStateVersion)
    return makeError("particle state version " + std::to_string(v) + ", this build reads " +
                     std::to_string(kStateVersion));
  const auto slotCount = r.pod<std::uint64_t>();
  // Each slot takes at least its generation and liveness bytes: a damaged
  // count allocates no more than the bytes could hold.
  if (!r.ok() || slotCount > kMaxSlots || slotCount > r.remaining() / (sizeof(std::uint32_t) + 1))
    return makeError("particle state: damaged (emitter slots)");
  // Read and checked whole before anything changes: a refused restore
  // leaves the system as it was.
  std::vector<Slot> slots(slotCount);
  int live = 0;
  for (std::size_t i = 0; i < slotCount; ++i) {
    Slot& s = slots[i];
    s.generation = r.pod<std::uint32_t>();
    s.live = r.pod<std::uint8_t>() != 0;
    if (!s.live) continue;
    ++live;
    Emitter& e = s.emitter;
    e.def = readDef(r);
    const auto f = r.pod<EmitterFields>();
    if (!r.ok()) return makeError("particle state: damaged (emitter " + std::to_string(i) + ")");
    if (Status st = validate(e.def); !st) return makeError("emitter " + std::to_string(i) + ": " + st.error());
    // Bounds that keep the next step's work what a script could ask for:
    // the carried fraction below one particle, a rate and a pending burst
    // within the per-emitter limits.
    if (f.poolSize > std::size_t(kMaxParticlesPerEmitter) || f.count > f.poolSize ||
        f.nextBurst > e.def.bursts.size() || f.pendingBurst < 0 || f.pendingBurst > kMaxParticlesPerEmitter ||
        !(f.carry >= 0 && f.carry <= 1) || !(f.rate_per_s >= 0 && f.rate_per_s <= 1e6f) ||
        !(f.age_s >= 0 && std::isfinite(f.age_s)) || !f.position_m.allFinite() || !f.rotation.coeffs().allFinite())
      return makeError("particle state: damaged (emitter " + std::to_string(i) + ")");
    e.position_m = f.position_m;
    e.rotation = f.rotation;
    e.previousPosition_m = f.previousPosition_m;
    e.velocity_mps = f.velocity_mps;
    e.anchor = f.anchor;
    e.anchorOffset_m = f.anchorOffset_m;
    e.rate_per_s = f.rate_per_s;
    e.age_s = f.age_s;
    e.carry = f.carry;
    e.nextBurst = std::size_t(f.nextBurst);
    e.pendingBurst = f.pendingBurst;
    e.stopAfterBurst = f.stopAfterBurst != 0;
    e.stopped = f.stopped != 0;
    e.dropped = f.dropped;
    e.random.state = f.random;
    ParticlePool& p = e.pool;
    p.reserve(std::size_t(f.poolSize));
    p.count = f.count;
    for (std::vector<float>* a : {&p.px, &p.py, &p.pz, &p.vx, &p.vy, &p.vz, &p.age_s, &p.invLifetime,
                                  &p.angle_rad, &p.spin_radps}) {
      const std::vector<float> values = r.vec<float>(f.count);
      if (!r.ok() || values.size() != f.count)
        return makeError("particle state: damaged (particles of emitter " + std::to_string(i) + ")");
      std::copy(values.begin(), values.end(), a->begin());
    }
  }
  auto freeSlots = r.vec<std::uint32_t>(kMaxSlots);
  const auto liveCount = r.pod<std::int32_t>();
  const auto seed = r.pod<std::uint64_t>();
  const auto created = r.pod<std::uint64_t>();
  const auto gravity = r.pod<Eigen::Vector3f>();
  if (!r.ok() || !r.atEnd()) return makeError("particle state: damaged (truncated or bytes after the end)");
  if (liveCount != live) return makeError("particle state: damaged (emitter count)");
  if (!allDistinct(freeSlots)) return makeError("particle state: damaged (free slots)");
  for (std::uint32_t i : freeSlots)
    if (i >= slotCount || slots[i].live) return makeError("particle state: damaged (free slots)");
  m_slots = std::move(slots);
  m_free = std::move(freeSlots);
  m_live = live;
  m_seed = seed;
  m_created = created;
  m_gravity = gravity;
  return Ok{};
}

}  // namespace tumble::particles
