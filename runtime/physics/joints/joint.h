#pragma once
// Joint definitions, shared by both joint solvers of joint_system.h: the
// Lagrange-multiplier solver (lagrange_solver.cpp) and the impulse solver
// inside the contact loop (impulse_solver.cpp). Each type's rows are in
// its own file (ball_joint.cpp, hinge_joint.cpp, cone_twist_joint.cpp,
// fixed_joint.cpp).
//
// Every joint has a point-to-point (ball) part: an anchor fixed in body A and
// one fixed in body B must coincide. The types add angular rows on top:
//
//   Ball       3 rows   the anchors coincide; free rotation.
//   Hinge      5 rows   ball + 2 rows keeping the hinge axes aligned; optional
//                       angle limits (one inequality row, active when violated)
//                       and a motor (target rate, torque bound).
//   ConeTwist  3 rows   ball + swing-cone and twist limits (inequality rows,
//                       active when violated). Shoulders, hips, neck, spine.
//   Fixed      6 rows   ball + 3 rows locking the relative orientation.
//
// Frames. Each joint has a frame in each body, given in the body's local frame
// (origin = anchor, rotation = localFrameA/B). The frame's +X axis is the
// hinge axis (Hinge) or the twist axis (ConeTwist); +Y is the reference for
// the hinge angle and the twist angle. At the rest pose the two frames
// coincide in the world; the hinge angle and twist angle are then zero.
// makeJointDef() fills the frames from the bodies' current poses.
//
// A joint to the world: leave bodyB null; localAnchorB_m and localFrameB are
// then in world coordinates (a static anchor).
#include <cstdint>

#include "core/handle.h"
#include "core/math.h"
#include "core/result.h"
#include "physics/body.h"

namespace tumble::physics {

class World;

struct JointTag;
using JointId = Handle<JointTag>;

enum class JointType { Ball, Hinge, ConeTwist, Fixed };

const char* jointTypeName(JointType type);

/// Everything needed to create a joint. Every field has a usable default
/// except the bodies and anchors (use makeJointDef for those).
struct JointDef {
  JointType type = JointType::Ball;
  BodyId bodyA;  ///< must be a live body (dynamic, or kinematic/static if bodyB is dynamic)
  BodyId bodyB;  ///< null: the joint holds bodyA to the world
  Vec3 localAnchorA_m = Vec3::Zero();  ///< anchor in A's body frame (from A's centre of mass), m
  Vec3 localAnchorB_m = Vec3::Zero();  ///< anchor in B's body frame, m; world point if bodyB is null
  Quat localFrameA = Quat::Identity();  ///< joint frame in A's body frame (+X = hinge / twist axis)
  Quat localFrameB = Quat::Identity();  ///< joint frame in B's body frame; world frame if bodyB is null

  // ---- limits (inequality rows; only active while violated) ----------------
  /// Hinge: limit the hinge angle (rotation of B's frame relative to A's
  /// about +X, right-handed) to [lowerAngle_rad, upperAngle_rad].
  bool enableLimit = false;
  Real lowerAngle_rad = -kPi / 2;  ///< Hinge, rad, in (-pi, upperAngle_rad]
  Real upperAngle_rad = kPi / 2;   ///< Hinge, rad, in [lowerAngle_rad, pi)
  /// ConeTwist: largest angle (rad) between the two frames' +X axes, in
  /// (0, pi). Pitfall: near pi the cone row loses its direction; keep < 170 deg.
  Real swingLimit_rad = kPi / 4;
  Real twistLower_rad = -kPi / 4;  ///< ConeTwist: twist about +X, rad, in (-pi, 0]
  Real twistUpper_rad = kPi / 4;   ///< ConeTwist: twist about +X, rad, in [0, pi)

  // ---- motor (Hinge) ----------------------------------------------------------
  /// Drives the hinge angle's rate (B relative to A about +X) towards
  /// motorSpeed_radps with a torque of at most maxMotorTorque_Nm. Impulse
  /// solver: a velocity row clamped to +-maxMotorTorque_Nm * h. Lagrange
  /// solver: an explicit servo torque (see hinge_joint.cpp).
  bool enableMotor = false;
  Real motorSpeed_radps = 0;   ///< rad/s
  Real maxMotorTorque_Nm = 0;  ///< N m, >= 0

  // ---- soft (spring) joints ------------------------------------------------
  /// > 0: the equality rows become springs instead of hard rows: the
  /// point-to-point rows give the force -k x - c v on the anchors (N), the
  /// angular rows (Hinge, Fixed) -k_a e - c_a de/dt (N m, e ~ angle error in
  /// rad). Springs are explicit forces added to Q, not solved for. Limits of
  /// a soft joint stay hard.
  Real linearStiffness_Npm = 0;
  Real linearDamping_Nspm = 0;        ///< N s / m; used when linearStiffness_Npm > 0
  Real angularStiffness_Nmprad = 0;   ///< N m / rad; used when linearStiffness_Npm > 0
  Real angularDamping_Nmsprad = 0;    ///< N m s / rad; used when linearStiffness_Npm > 0

  // ---- breakable joints ----------------------------------------------------
  /// > 0: the joint is removed (and reported by JointSystem::brokenJoints())
  /// when the constraint force on its anchor exceeds this many N. 0: never.
  Real breakForce_N = 0;
  /// > 0: likewise for the constraint torque of the angular rows and limits (N m).
  Real breakTorque_Nm = 0;

  std::uint64_t userData = 0;  ///< free for the application
};

/// A joint of the given type between a and b (b may be null: the world) that
/// holds the bodies in their current poses: the anchor is the world point
/// anchor_m, the joint's +X axis is axis (unit or not; hinge / twist axis)
/// and +Y is any vector perpendicular to it (the zero of the angles).
/// Asserts on stale handles (check World::isValid first).
JointDef makeJointDef(const World& world, JointType type, BodyId a, BodyId b, const Vec3& anchor_m,
                      const Vec3& axis = Vec3::UnitX());

/// A grab: a soft ball joint from localPoint_m (body frame, from the centre
/// of mass) of a dynamic body to the world point target_m, whose stiffness
/// follows the body's mass (k = m (2 pi hertz)^2, damping c = m 2 pi hertz,
/// see joint.cpp), so every body follows at the same rate. Move the target
/// with JointSystem::setWorldAnchor. What dragging with the mouse makes.
JointDef makeGrabDef(const World& world, BodyId body, const Vec3& localPoint_m, const Vec3& target_m,
                     Real hertz = 4);

/// Refuses definitions that cannot work: stale bodies, A == B, both bodies
/// without mass, limits out of range, negative stiffness. The message names
/// the field and what would be valid.
Status validateJointDef(const World& world, const JointDef& def);

/// The rotation that maps +X to axis (any such rotation; used for frames).
Quat frameFromAxis(const Vec3& axis);

}  // namespace tumble::physics
