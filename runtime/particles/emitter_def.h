#pragma once
// What an emitter is: every parameter a mod's emitters/<name>.lua can set
// (script/emitter_files.cpp reads the Lua table into this struct, field names
// in comments are the Lua names).
//
// Index
//   EmitterShape, BlendMode, SimSpace   enums
//   Curve1, Curve3                      keyframed values over normalised life
//   Burst                               a burst of particles at a time
//   EmitterDef                          the definition, with defaults
//   validate()                          checks a definition; the message names the Lua field
//
// Units: m, s, rad, m/s, m/s^2; colours linear RGB 0..1.
#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"
#include <Eigen/Core>

namespace tumble::particles {

/// Where new particles start, in the emitter's frame (origin = emitter position).
enum class EmitterShape {
  Point,   ///< at the origin
  Box,     ///< uniformly inside a box of full size `boxSize_m`
  Sphere,  ///< uniformly inside a ball of `radius_m`
  Cone,    ///< on a disc of `radius_m` across `direction`, flying out along a cone of `coneAngle_rad`
};

enum class BlendMode {
  Alpha,     ///< ordinary transparency; drawn sorted back to front
  Additive,  ///< light adds up (fire, sparks); drawn after the alpha-blended ones, order free
};

enum class SimSpace {
  World,  ///< particles stay where they were emitted; the emitter moving leaves a trail
  Local,  ///< particles live in the emitter's frame and move (and turn) with it
};

/// A number over normalised life t in [0, 1]: linear between keys, the first
/// key's value before it and the last key's after. Keys sorted by t.
struct Curve1 {
  struct Key {
    float t = 0;
    float value = 0;
  };
  std::vector<Key> keys;
  float eval(float t) const;
  static Curve1 constant(float v) { return Curve1{{{0, v}}}; }
};

/// Three numbers (an RGB colour) over normalised life; as Curve1.
struct Curve3 {
  struct Key {
    float t = 0;
    Eigen::Vector3f value = Eigen::Vector3f::Zero();
  };
  std::vector<Key> keys;
  Eigen::Vector3f eval(float t) const;
  static Curve3 constant(const Eigen::Vector3f& v) { return Curve3{{{0, v}}}; }
};

/// `bursts = {{time = 0, count = 30}, ...}`: `count` particles at once,
/// `time_s` after the emitter was spawned.
struct Burst {
  float time_s = 0;
  int count = 0;
};

struct EmitterDef {
  // --- emission ---
  float rate_per_s = 10;           ///< rate: particles per second (fraction carried between steps)
  std::vector<Burst> bursts;       ///< bursts: at times after spawn
  float duration_s = 0;            ///< duration: emits for this long, then stops (0: until stop())
  float lifetimeMin_s = 1;         ///< lifetime = {min, max} or a number, s (> 0); uniform in range
  float lifetimeMax_s = 1;
  int maxCount = 1000;             ///< max_count: live particles at most; when full new ones are dropped

  // --- where and how fast they start ---
  EmitterShape shape = EmitterShape::Point;          ///< shape: "point", "box", "sphere", "cone"
  Eigen::Vector3f boxSize_m{1, 1, 1};                ///< box_size: full size of the box shape, m
  float radius_m = 0.5f;                             ///< radius: sphere radius / cone base radius, m
  float coneAngle_rad = 0.5f;                        ///< cone_angle: cone half angle, rad (0..pi/2)
  Eigen::Vector3f direction{0, 1, 0};                ///< direction: main direction, emitter frame (normalised)
  float spread_rad = 0;                              ///< spread: half angle of random deviation, rad (0..pi)
  float speedMin_mps = 1, speedMax_mps = 1;          ///< speed = {min, max} or a number, m/s
  float inheritVelocity = 0;                         ///< inherit_velocity: share of the emitter's velocity (0..1, world space only)

  // --- motion ---
  float gravityScale = 0;                            ///< gravity: multiple of the world's gravity (1 = falls like a stone)
  Eigen::Vector3f acceleration_mps2{0, 0, 0};        ///< acceleration: extra, m/s^2 (world frame; emitter frame in local space)
  float drag_per_s = 0;                              ///< drag: velocity decays as exp(-drag t), 1/s (>= 0)
  float spinMin_radps = 0, spinMax_radps = 0;        ///< spin = {min, max} or a number: billboard turn rate, rad/s

  // --- look ---
  Curve1 size_m = Curve1::constant(0.2f);                      ///< size: billboard width, m; number or {{t, m}, ...}
  Curve3 color = Curve3::constant(Eigen::Vector3f(1, 1, 1));   ///< color: {r, g, b} or {{t, {r, g, b}}, ...}
  Curve1 alpha = Curve1::constant(1);                          ///< alpha: opacity 0..1; number or {{t, a}, ...}
  float stretch_s = 0;                                         ///< stretch: drawn stretched along the velocity by v * stretch (s): streaks for rain, sparks; 0: round
  BlendMode blend = BlendMode::Alpha;                          ///< blend: "alpha" or "additive"
  SimSpace space = SimSpace::World;                            ///< space: "world" or "local"
};

/// Largest max_count an emitter may ask for (memory: 40 bytes a particle).
inline constexpr int kMaxParticlesPerEmitter = 1'000'000;

/// Checks ranges and consistency. The message starts with the Lua field name
/// and says what is valid, e.g. "field 'lifetime': min 2 > max 1; expected
/// {min, max} seconds with 0 < min <= max".
Status validate(const EmitterDef& def);

}  // namespace tumble::particles
