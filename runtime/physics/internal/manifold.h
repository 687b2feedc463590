#pragma once
// Contact manifolds shared by the narrow phase and the contact solver.
#include <cstdint>

#include "core/math.h"

namespace tumble::physics {

constexpr int kMaxManifoldPoints = 4;

struct ContactPoint {
  // From the narrow phase:
  Vec3 point_m = Vec3::Zero();  ///< world, midway between the two surfaces
  Real separation_m = 0;        ///< negative when overlapping
  std::uint32_t id = 0;         ///< feature id, stable while the same features touch
  // Solver data (world frame, fixed during a step):
  Vec3 rA = Vec3::Zero(), rB = Vec3::Zero();  ///< from each centre of mass to the point
  Real baseSeparation_m = 0;  ///< separation minus n.(rB - rA), so that current separation = base + n.(d)
  Real normalMass = 0, tangentMass[2] = {0, 0};
  Real normalImpulse = 0, tangentImpulse[2] = {0, 0};  ///< accumulated (N s), warm started
  Real maxNormalImpulse = 0;
  Real pseudoImpulse = 0;
  Real currentSeparation_m = 0;  ///< separation at the last solve, updated per substep  ///< split-impulse position correction, per substep
  Real relativeVelocity_mps = 0;  ///< normal velocity before the step (restitution)
};

struct Manifold {
  std::uint32_t a = 0, b = 0;   ///< body indices
  Vec3 normal = Vec3::UnitY();  ///< from a to b
  Vec3 tangent[2] = {Vec3::UnitX(), Vec3::UnitZ()};
  int count = 0;
  ContactPoint points[kMaxManifoldPoints];
  Real friction = 0, restitution = 0;
  /// Rolling resistance as a lever arm (m): coefficient times the rolling
  /// radius. The rolling torque is at most this times the normal force.
  Real rollingArm_m = 0;
  Real rollingImpulse[3] = {0, 0, 0};  ///< angular about tangent 0, 1 and the normal, N m s, per substep
  Real rollingMass[3] = {0, 0, 0};
  bool touchedBefore = false;
  /// Round shapes (spheres, capsules): the contact point slides over the
  /// surface instead of turning with the body, so substep separation
  /// updates must not rotate its anchor (a rolling ball would otherwise look
  /// lifted off the ground and lose its normal force, friction and rolling
  /// resistance).
  bool roundA = false, roundB = false;
  /// Sum of impulses applied this step on the moving set by a static,
  /// kinematic or sleeping body of the pair (momentum bookkeeping), N s.
  Eigen::Vector3d externalImpulse_Ns = Eigen::Vector3d::Zero();  ///< had points last step (for begin-contact events)
};

/// Pair key, order independent.
inline std::uint64_t pairKey(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(a) << 32) | b;
}

}  // namespace tumble::physics
