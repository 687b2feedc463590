#pragma once
// Rigid bodies: setup struct with defaults (after Box2D's b2BodyDef) and the
// per-body state the world stores in one contiguous array.
#include <cstdint>

#include "core/handle.h"
#include "core/math.h"
#include "core/result.h"
#include "physics/shape.h"

namespace tumble::physics {

struct BodyTag;
using BodyId = Handle<BodyTag>;

enum class BodyType {
  Static,     ///< never moves, infinite mass (ground, walls)
  Kinematic,  ///< moved by its velocity only, infinite mass, pushes dynamic bodies
  Dynamic,    ///< moved by forces, gravity and contacts
};

/// Everything needed to create a body. Every field has a usable default.
struct BodyDef {
  BodyType type = BodyType::Dynamic;
  Shape shape;
  Vec3 position_m = Vec3::Zero();           ///< centre of mass, world
  Quat orientation = Quat::Identity();      ///< body frame to world
  Vec3 linearVelocity_mps = Vec3::Zero();   ///< of the centre of mass
  Vec3 angularVelocity_radps = Vec3::Zero();  ///< world frame
  /// Mass in kg. 0 means "from density and volume". Ignored for static and
  /// kinematic bodies.
  Real mass_kg = 0;
  Real density_kgpm3 = 1000;  ///< used only when mass_kg is 0 (water = 1000)
  /// Coulomb friction coefficient (dimensionless, >= 0). A pair uses the
  /// geometric mean sqrt(fa*fb): either body at 0 makes the pair frictionless.
  Real friction = Real(0.6);
  /// Newton's restitution coefficient (0..1). A pair uses the larger of the
  /// two, so a bouncy ball bounces on any floor.
  Real restitution = 0;
  /// Rolling resistance coefficient (dimensionless, like a tyre's C_rr:
  /// 0.001 steel on steel, 0.01 tyre on asphalt, 0.05-0.3 ball on grass).
  /// The rolling torque is at most C_rr * r * N for a sphere or capsule of
  /// radius r under normal force N. A pair uses the larger coefficient. 0:
  /// a ball rolls for ever, as a perfect sphere on a perfect plane would.
  Real rollingResistance = 0;
  Real linearDamping_per_s = 0;   ///< velocity decays as 1/(1 + c dt) each step
  Real angularDamping_per_s = 0;  ///< likewise for angular velocity
  bool allowSleep = true;
  std::uint64_t userData = 0;  ///< free for the application (script handles)
};

/// Checks a BodyDef from user data; the message names the field.
Status validateBodyDef(const BodyDef& def);

/// Per-body state. Stored in World's contiguous array; read through World.
struct Body {
  BodyType type = BodyType::Dynamic;
  Shape shape;
  Vec3 position_m = Vec3::Zero();
  Quat orientation = Quat::Identity();
  Vec3 linearVelocity_mps = Vec3::Zero();
  Vec3 angularVelocity_radps = Vec3::Zero();
  Vec3 force_N = Vec3::Zero();    ///< accumulated for the next step, then cleared
  Vec3 torque_Nm = Vec3::Zero();  ///< likewise
  Real mass_kg = 0;
  Real invMass_per_kg = 0;
  Vec3 invInertiaLocal = Vec3::Zero();  ///< principal, 1/(kg m^2)
  Mat3 invInertiaWorld = Mat3::Zero();  ///< R diag(invInertiaLocal) R^T
  Vec3 inertiaLocal_kgm2 = Vec3::Zero();
  Real friction = Real(0.6);
  Real restitution = 0;
  Real rollingResistance = 0;
  Real linearDamping_per_s = 0;
  Real angularDamping_per_s = 0;
  Real sleepTime_s = 0;
  std::uint64_t userData = 0;
  /// What the body sounds like when struck: a value the audio module
  /// defines (audio::ImpactMaterial; 0 none stated). Physics never reads it.
  std::uint8_t soundMaterial = 0;
  std::uint32_t generation = 0;  ///< slot generation; odd while alive (see World)
  bool alive = false;
  bool awake = true;
  bool allowSleep = true;
  bool frozen = false;  ///< state became non-finite; held still, counted in nan_events

  bool isDynamic() const { return type == BodyType::Dynamic && !frozen; }
  /// Moves this step (awake dynamic or kinematic).
  bool moves() const { return !frozen && awake && type != BodyType::Static; }
};

}  // namespace tumble::physics
