#pragma once
// ImpulseJoints: formulation B of issue 4, the joints of a JointSystem solved
// as velocity constraints inside the World's substep loop (the
// ConstraintSolver hook), by sequential impulses with soft position
// correction and warm starting. The derivation is at the top of
// joints/impulse_joints.cpp.
#include <cstdint>
#include <vector>

#include "physics/constraint_solver.h"
#include "physics/joints/joint.h"

namespace tumble::physics {

class JointSystem;

class ImpulseJoints final : public ConstraintSolver {
 public:
  /// hertz, dampingRatio: softness of the hard rows' position correction.
  ImpulseJoints(const JointSystem& joints, double hertz, double dampingRatio);

  void prepare(const World& world, Real dt_s, int substeps) override;
  void warmStart(SolverVelocity* vel, const Body* bodies) override;
  Real solve(SolverVelocity* vel, const Body* bodies, bool useBias) override;
  void finish(const World& world) override;

  /// What the last step measured for one joint slot.
  struct Output {
    std::uint32_t generation = 0;  ///< of the joint the figures belong to
    Vec3 force_N = Vec3::Zero();   ///< on body B at the anchor (A gets the opposite), world
    Vec3 torque_Nm = Vec3::Zero(); ///< angular rows, limits and motor, on B, world
    bool broken = false;           ///< exceeded breakForce_N / breakTorque_Nm in the last step
  };
  /// Indexed by joint slot; entries of joints the last step did not solve
  /// keep their generation from before (compare with the JointId).
  const std::vector<Output>& outputs() const { return m_out; }
  /// Clears the broken flags (after the JointSystem removed those joints).
  void clearBroken();

  /// Current pose of one joint side.
  struct Side {
    Vec3 r = Vec3::Zero();      ///< anchor offset from the centre (world)
    Vec3 p = Vec3::Zero();      ///< anchor point
    Mat3 F = Mat3::Identity();  ///< joint frame axes (columns), world
    Quat q = Quat::Identity();  ///< joint frame, world
  };

  /// Accumulated impulses, kept between steps for warm starting; and the
  /// per-step data of one joint.
  struct Accum {
    std::uint32_t generation = 0;
    Vec3 linear = Vec3::Zero();   ///< point rows, on B (N s per substep)
    Vec3 angular = Vec3::Zero();  ///< alignment / orientation rows, on B (world)
    Real lower = 0, upper = 0;    ///< hinge angle or twist limits
    Real swing = 0, motor = 0;
  };

  struct Joint {
    const JointDef* def = nullptr;
    std::uint32_t slot = 0;
    std::uint32_t a = 0, b = 0;  ///< body / velocity indices (b unused when world)
    bool world = false;          ///< B is the world (anchor and frame in world coordinates)
    bool movesA = false, movesB = false;
    Real mA = 0, mB = 0;
    Mat3 iA = Mat3::Zero(), iB = Mat3::Zero();
    // Spring gains (soft joints), per substep.
    bool soft = false;
    Real gammaLin = 0, betaLin = 0, gammaAng = 0, betaAng = 0;
    bool angularFree = false;  ///< soft joint without angular spring: no angular rows
    // Geometry of the current solve phase (refreshGeometry).
    Side sa, sb;
    Mat3 pointKinv = Mat3::Zero();  ///< (K + gamma)^-1 of the point rows
    bool pointOk = false;
    Real angle = 0;         ///< hinge angle or twist angle, rad
    Real limitK = 0;        ///< limitAxis.(IA^-1 + IB^-1) limitAxis
    Real swingAngle = 0, swingK = 0;
    bool swingActive = false;  ///< near enough to the cone for its row
    // Axes of the last sweep (for the torque report).
    Vec3 limitAxis = Vec3::Zero(), swingAxis = Vec3::Zero();
  };

 private:
  /// Anchors, frames and the point rows' inverse mass from the poses now.
  void refreshGeometry(const Body* bodies);

  const JointSystem& m_system;
  bool m_relaxing = false;  ///< in the relax sweeps (geometry refreshed after the positions moved)
  double m_hertz, m_zeta;
  Real m_h = 0, m_invH = 0;
  Real m_biasRate = 0, m_massScale = 1, m_impulseScale = 0;
  std::vector<Joint> m_joints;
  std::vector<std::uint32_t> m_order;  ///< joint slots, JointSystem::solveOrder
  std::vector<Accum> m_accum;  ///< per joint slot
  std::vector<Output> m_out;   ///< per joint slot
};

}  // namespace tumble::physics
