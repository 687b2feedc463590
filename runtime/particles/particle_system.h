#pragma once
// Emitters and their particle pools (structure of arrays), stepped at the
// fixed rate after physics. Depends on core only: no physics, Lua, SDL or GL
// (ARCHITECTURE.md). An emitter attached to a body gets the body's pose and
// velocity from the app every step (setAnchorState); this module never sees
// a body, only an opaque anchor number the app resolves.
//
// Index
//   EmitterId, kNoAnchor        handles; anchor numbers
//   ParticlePool                one emitter's particles as parallel arrays
//   Emitter                     definition, pose, spawn state, pool
//   ParticleSystem              create / remove / step; what render reads
//
// One step (step(dt)):
//   1. every live particle: age, then velocity v += (g*gravity + a) dt, then
//      v *= exp(-drag dt), then x += v dt (semi-implicit Euler, exact for the
//      discrete sums the tests check); dead ones are swap-removed.
//   2. every emitter: bursts due in (t, t + dt], then rate * dt new particles
//      (the fraction carries to the next step). Each new particle is born at
//      its own time inside the step: its start point is interpolated along
//      the emitter's motion and it is advanced over the rest of the step, so
//      a fast emitter leaves an even trail instead of clumps.
//   3. a stopped emitter (stop(), or its duration ran out) with no particles
//      left frees itself; its handle becomes invalid.
//
// A full pool (max_count) drops new particles: the ones alive keep their
// whole lifetime, so nothing pops; droppedCount() tells how many were lost
// (raise max_count if it grows). Deterministic for a seed: every emitter has
// its own random stream from (seed, creation order).
#include <cstdint>
#include <vector>

#include "core/byte_stream.h"
#include "core/handle.h"
#include "core/result.h"
#include "core/random.h"
#include "particles/emitter_def.h"
#include <Eigen/Geometry>

namespace tumble::particles {

struct EmitterTag {};
using EmitterId = Handle<EmitterTag>;

/// Anchor value of an emitter that is not attached to anything.
inline constexpr std::uint64_t kNoAnchor = 0;

/// One emitter's particles. Positions and velocities are in world space, or
/// in the emitter's frame for SimSpace::Local. Only the first `count` entries
/// are live; the arrays keep their capacity (max_count, reserved up front).
struct ParticlePool {
  std::vector<float> px, py, pz;     ///< position, m
  std::vector<float> vx, vy, vz;     ///< velocity, m/s
  std::vector<float> age_s;          ///< time since birth, s
  std::vector<float> invLifetime;    ///< 1 / lifetime, 1/s (normalised life = age * invLifetime)
  std::vector<float> angle_rad;      ///< billboard rotation, rad
  std::vector<float> spin_radps;     ///< its rate, rad/s
  std::uint32_t count = 0;

  void reserve(std::size_t n);
  void removeSwap(std::uint32_t i);  ///< moves the last live particle into slot i
};

/// Small fast deterministic generator (splitmix64). Same numbers on every
/// platform, unlike std:: distributions.
struct Random {
  std::uint64_t state = 0;
  std::uint64_t next() { return splitmix64(state); }
  /// Uniform in [0, 1).
  float uniform() { return float(next() >> 40) * (1.0f / 16777216.0f); }
  float range(float lo, float hi) { return lo + (hi - lo) * uniform(); }
};

struct Emitter {
  EmitterDef def;
  // Pose: where the emitter is now and was at the start of the step.
  Eigen::Vector3f position_m = Eigen::Vector3f::Zero();
  Eigen::Quaternionf rotation = Eigen::Quaternionf::Identity();  ///< emitter frame -> world
  Eigen::Vector3f previousPosition_m = Eigen::Vector3f::Zero();
  /// Of the emitter point, world, for inherit_velocity: from the anchor
  /// (setAnchorState), or for a free emitter its move over the step / dt.
  Eigen::Vector3f velocity_mps = Eigen::Vector3f::Zero();
  // Attachment: the app resolves `anchor` each step and calls setAnchorState.
  std::uint64_t anchor = kNoAnchor;
  Eigen::Vector3f anchorOffset_m = Eigen::Vector3f::Zero();      ///< in the anchor's frame
  // Spawn state.
  float rate_per_s = 0;       ///< current rate (starts as def.rate_per_s; set_rate changes it)
  double age_s = 0;           ///< time since spawn, s
  double carry = 0;           ///< fractional particle carried to the next step
  std::size_t nextBurst = 0;  ///< index into def.bursts (sorted by time)
  int pendingBurst = 0;       ///< burst(n) asked for, spawned at the next step's start
  bool stopAfterBurst = false;  ///< burst(n, thenStop)
  bool stopped = false;
  std::uint64_t dropped = 0;  ///< particles not spawned because the pool was full
  Random random;
  ParticlePool pool;
};

class ParticleSystem {
 public:
  explicit ParticleSystem(std::uint64_t seed = 1);

  /// A new emitter at `position_m`, turned by `rotation` (its definition's
  /// direction is in that frame). The definition must pass validate(); bursts
  /// are sorted by time here. Reserves max_count particles.
  EmitterId create(const EmitterDef& def, const Eigen::Vector3f& position_m,
                   const Eigen::Quaternionf& rotation = Eigen::Quaternionf::Identity());
  bool isValid(EmitterId id) const;
  /// Hot reload: a new definition for a running emitter. Live particles stay
  /// (the pool grows if max_count grew; with a smaller max_count no new
  /// particle is born until the count is under it); a rate the script set
  /// with setRate is kept, otherwise the new definition's rate applies.
  /// False for a stale id.
  bool redefine(EmitterId id, const EmitterDef& def);
  /// Removes the emitter and its particles at once. False for a stale id.
  bool remove(EmitterId id);
  /// Stops emitting (rate, bursts, pending burst); live particles finish, then
  /// the emitter frees itself.
  void stop(EmitterId id);
  /// n particles at once, spawned at the start of the next step (at the
  /// emitter's pose then). Ignored for a stopped emitter. thenStop: stop
  /// right after those are born (a one-shot, e.g. sparks from an impact).
  void burst(EmitterId id, int n, bool thenStop = false);
  void setRate(EmitterId id, float rate_per_s);
  /// Moves the emitter. The move counts as motion during the next step (its
  /// trail is interpolated) unless `teleport`.
  void setPose(EmitterId id, const Eigen::Vector3f& position_m, const Eigen::Quaternionf& rotation,
               bool teleport = false);
  /// Main direction in the emitter's frame (normalised here; zero is ignored).
  void setDirection(EmitterId id, const Eigen::Vector3f& direction);
  /// Attaches to an anchor (the app's number for a body, never kNoAnchor) at
  /// an offset in the anchor's frame.
  void attach(EmitterId id, std::uint64_t anchor, const Eigen::Vector3f& offset_m);
  /// The anchor's pose and velocities this step (world): the emitter moves to
  /// position + rotation * offset and turns with it; its velocity is
  /// v + w x (rotation * offset). Call before step().
  void setAnchorState(EmitterId id, const Eigen::Vector3f& position_m, const Eigen::Quaternionf& rotation,
                      const Eigen::Vector3f& velocity_mps, const Eigen::Vector3f& angularVelocity_radps);
  /// The anchor is gone (its body was removed): detach and stop.
  void anchorLost(EmitterId id);

  /// World gravity (m/s^2); each emitter scales it by its `gravity`.
  void setGravity(const Eigen::Vector3f& gravity_mps2) { m_gravity = gravity_mps2; }
  /// Advances every emitter and particle by dt_s (see the header comment).
  void step(float dt_s);

  const Emitter* get(EmitterId id) const;
  Emitter* get(EmitterId id);
  /// Live particles of one emitter (0 for a stale id).
  int count(EmitterId id) const;
  /// Live particles of all emitters.
  int particleCount() const;
  int emitterCount() const { return m_live; }
  /// Calls f(EmitterId, const Emitter&) for every live emitter, in slot order.
  template <typename F>
  void forEach(F&& f) const {
    for (std::uint32_t i = 0; i < m_slots.size(); ++i)
      if (m_slots[i].live) f(EmitterId{i, m_slots[i].generation}, m_slots[i].emitter);
  }
  /// Attached emitters, for the app's per-step anchor update: f(EmitterId, anchor).
  template <typename F>
  void forEachAnchored(F&& f) const {
    for (std::uint32_t i = 0; i < m_slots.size(); ++i)
      if (m_slots[i].live && m_slots[i].emitter.anchor != kNoAnchor)
        f(EmitterId{i, m_slots[i].generation}, m_slots[i].emitter.anchor);
  }

  /// Every emitter (definition, pose, spawn state, random stream, live
  /// particles) and the system's own counters, as exact bits, for
  /// snapshots of a running scene (particle_state.cpp). Emitters are plain
  /// data, so the saved ones replace whatever this system has, including
  /// those a script spawned after on_start; restoreState refuses damaged
  /// bytes and definitions that do not pass validate().
  std::string saveState() const;
  Status restoreState(const std::string& bytes);

  /// Normalised direction sample: uniform over the spherical cap of half
  /// angle `spread_rad` around `axis` (unit). Exposed for tests.
  static Eigen::Vector3f sampleCap(Random& r, const Eigen::Vector3f& axis, float spread_rad);

 private:
  struct Slot {
    Emitter emitter;
    std::uint32_t generation = 1;
    bool live = false;
  };
  void updateParticles(Emitter& e, float dt_s) const;
  void spawnParticles(Emitter& e, float dt_s);
  void spawnOne(Emitter& e, float birthFraction, float dt_s);

  std::vector<Slot> m_slots;
  std::vector<std::uint32_t> m_free;
  int m_live = 0;
  std::uint64_t m_seed;
  std::uint64_t m_created = 0;
  Eigen::Vector3f m_gravity{0, -9.81f, 0};
};

}  // namespace tumble::particles
