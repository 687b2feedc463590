#pragma once
// What differs between the joint types, for both joint solvers, dispatched
// once through a table (jointTypeRows): the Lagrange solver's rows
// (lagrange_solver.h) and the impulse solver's (impulse_joints.h). Every
// type has the point rows of ball_joint.cpp; an entry adds what its type has
// on top. One file per type holds its entry and its derivation:
// ball_joint.cpp, hinge_joint.cpp, cone_twist_joint.cpp, fixed_joint.cpp.
//
// The entries run once per joint and step, substep or solve phase, never
// inside the impulse solver's sweeps: a sweep reads only what
// impulseGeometry precomputed (its rows are the same for every type, with
// flags for the limit rows a type has).
#include "physics/internal/impulse_joints.h"
#include "physics/internal/lagrange_solver.h"

namespace tumble::physics {

/// Entries marked "may be null" are left out by types without such rows.
struct JointTypeRows {
  const char* name;  ///< jointTypeName
  // ---- Lagrange multipliers (lagrange_solver.cpp) ---------------------------
  /// The equality rows after the point rows (soft when the joint is a
  /// spring); may be null.
  void (*lagrangeEquality)(lagrange::RowBuilder& rb, const lagrange::JointPose& pa, const lagrange::JointPose& pb);
  /// The limit rows that are violated now (always hard); may be null.
  void (*lagrangeLimits)(lagrange::RowBuilder& rb, const JointDef& d, const lagrange::JointPose& pa,
                         const lagrange::JointPose& pb);
  /// A motor's explicit servo torque into Q and Tm; may be null.
  void (*lagrangeMotor)(const JointDef& d, lagrange::BodyState* A, lagrange::BodyState* B, const JointSettings& js);
  /// The angle JointSystem::jointAngle_rad reports, from the two joint
  /// frames (columns = axes, world); null: 0.
  double (*angle)(const lagrange::M3& FA, const lagrange::M3& FB);
  // ---- impulses (impulse_solver.cpp) -------------------------------------------
  /// Once per step: the type's settings from the definition (h: substep, s);
  /// may be null.
  void (*impulseSetup)(ImpulseJoints::Joint& j, const JointDef& d, Real h_s);
  /// Once per solve phase: the angular rows from the joint frames qa, qb
  /// (world). angularRows false: a spring without angular stiffness (no
  /// equality rows); gamma: the angular spring's softness (0 when hard).
  /// May be null.
  void (*impulseGeometry)(ImpulseJoints::Joint& j, const Quat& qa, const Quat& qb, bool angularRows, Real gamma);
  /// The accumulated angular impulse the warm start applies (on B, world).
  Vec4r (*impulseWarmStartAngular)(const ImpulseJoints::Joint& j, const ImpulseJoints::Accum& acc);
  /// The accumulated angular impulse reported as the joint's torque (on B, world).
  Vec4r (*impulseReportedAngular)(const ImpulseJoints::Joint& j, const ImpulseJoints::Accum& acc);
};

extern const JointTypeRows kBallJointRows;
extern const JointTypeRows kHingeJointRows;
extern const JointTypeRows kConeTwistJointRows;
extern const JointTypeRows kFixedJointRows;

/// The entry of one type: a table lookup, inline (it runs per joint and phase).
inline const JointTypeRows& jointTypeRows(JointType type) {
  static constexpr const JointTypeRows* kTable[] = {&kBallJointRows, &kHingeJointRows, &kConeTwistJointRows,
                                                    &kFixedJointRows};
  static_assert(int(JointType::Ball) == 0 && int(JointType::Hinge) == 1 && int(JointType::ConeTwist) == 2 &&
                    int(JointType::Fixed) == 3,
                "kTable follows the order of JointType");
  return *kTable[int(type)];
}

// The point (ball) rows every type has (ball_joint.cpp derives them).
/// Lagrange: the three rows p_a - p_b = 0.
void lagrangePointRows(lagrange::RowBuilder& rb, const lagrange::JointPose& pa, const lagrange::JointPose& pb);
// Impulses: impulsePointRows, inline in internal/impulse_joints.h.

}  // namespace tumble::physics
