#pragma once
// What scripts reach of a scene. Script declares this interface; app
// implements it (app/scene.h) and owns every system behind it
// (ARCHITECTURE.md "Modules and who may include whom"). Script never owns
// or steps a simulation system: bindings create and change bodies, joints,
// vehicles, emitters, ropes and cloth through it, and the app's fixed step
// (app/fixed_step.cpp) is the only place that steps them.
//
// Systems are created on first use (the `x()` accessors) so a scene pays
// only for what its scenario uses; `xIfAny()` never creates one.
#include <cstdint>
#include <string>

#include "core/math.h"
#include "core/result.h"
#include "physics/body.h"
#include "physics/shape.h"
#include "script/presentation.h"

namespace tumble::physics {
class World;
class JointSystem;
class DeformableSystem;
enum class JointSolverKind;
}  // namespace tumble::physics
namespace tumble::vehicle {
class VehicleSystem;
}
namespace tumble::particles {
class ParticleSystem;
}
namespace tumble::input {
class InputSystem;
}
namespace tumble::audio {
class AudioSystem;
}

namespace tumble::script {

class SceneSystems {
 public:
  virtual physics::World& world() = 0;
  /// The actions scripts read (input.value, ...).
  virtual input::InputSystem& input() = 0;

  virtual physics::JointSystem& joints() = 0;
  virtual physics::JointSystem* jointsIfAny() = 0;
  virtual vehicle::VehicleSystem& vehicles() = 0;
  virtual vehicle::VehicleSystem* vehiclesIfAny() = 0;
  virtual particles::ParticleSystem& particles() = 0;
  virtual particles::ParticleSystem* particlesIfAny() = 0;
  /// Ropes and cloth.
  virtual physics::DeformableSystem& deformables() = 0;
  virtual physics::DeformableSystem* deformablesIfAny() = 0;

  /// The scene's sound (created on first use; silent, with no device, in
  /// headless runs and with --mute), and a playing sound that follows a
  /// body (the app moves it every step and stops it when the body goes).
  virtual audio::AudioSystem& audio() = 0;
  virtual void attachSound(std::uint64_t sound, physics::BodyId body) = 0;

  /// The joint solver the scene's joints use (world.set_joint_solver may
  /// switch it while running; existing joints switch too).
  virtual physics::JointSolverKind jointSolver() const = 0;
  virtual void setJointSolver(physics::JointSolverKind kind) = 0;
  /// The fixed step (s) now; world.set_dt asks for another from the next step on.
  virtual double dt_s() const = 0;
  virtual void requestDt(double dt_s) = 0;

  /// Model files (absolute paths inside a mod), loaded once and cached by
  /// the app: bounds before scale (world.add_static_model's collision box,
  /// body:set_model's check), every triangle (mass properties), and the
  /// mesh collision shape at a placement's scale, shared between placements.
  /// Errors name the file and what is wrong with it.
  virtual Result<ModelBox> modelBounds(const std::string& file) = 0;
  virtual Result<ModelTriangles> modelTriangles(const std::string& file) = 0;
  virtual Result<physics::Shape> modelMeshShape(const std::string& file, const Vec3& scale) = 0;

 protected:
  ~SceneSystems() = default;
};

/// Emitters attached to bodies carry the body as an opaque anchor number
/// (particles never sees physics); the app turns it back into a BodyId.
inline std::uint64_t emitterAnchorOf(physics::BodyId id) {
  return (std::uint64_t(id.generation) << 32) | id.index;  // generation >= 1: never kNoAnchor
}
inline physics::BodyId bodyOfEmitterAnchor(std::uint64_t anchor) {
  return physics::BodyId{std::uint32_t(anchor & 0xffffffffu), std::uint32_t(anchor >> 32)};
}

}  // namespace tumble::script
