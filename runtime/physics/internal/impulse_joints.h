#pragma once
// ImpulseJoints: the impulse joint solver, the joints of a JointSystem
// solved as velocity constraints inside the World's substep loop (the
// ConstraintSolver hook), by sequential impulses with soft position
// correction and warm starting. The derivation is at the top of
// joints/impulse_solver.cpp; each joint type's rows are in its own file
// (joints/ball_joint.cpp, ...).
#include <cstdint>
#include <vector>

#include "core/byte_stream.h"
#include "core/result.h"
#include "physics/constraint_solver.h"
#include "physics/internal/contact_solver.h"
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
  void solvePushout(SolverVelocity* pseudo) override;
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
  /// Between steps: the warm-start impulses and the last step's outputs as
  /// exact bits (joint snapshots, joints/joint_state.cpp); restore refuses
  /// damaged bytes and entries for more than slotCount joint slots.
  void saveState(ByteWriter& w) const;
  Status restoreState(ByteReader& r, std::size_t slotCount);

  /// Accumulated impulses, kept between steps for warm starting (per joint
  /// slot). 4-wide like the solver's velocities (w = 0).
  struct Accum {
    std::uint32_t generation = 0;
    Vec4r linear = Vec4r::Zero();   ///< point rows, on B (N s per substep), world
    Vec4r angular = Vec4r::Zero();  ///< alignment / orientation rows, on B (N m s per substep), world
    Real lower = 0, upper = 0;      ///< hinge angle or twist limits (N m s per substep)
    Real swing = 0, motor = 0;      ///< swing cone, hinge motor (N m s per substep)
  };

  /// One joint's rows. The first block is set once per step (prepare); the
  /// rest is the geometry of the current solve phase (refreshGeometry: once
  /// before the solve sweeps of a substep, once before its relax sweeps),
  /// precomputed so that a sweep is a few packed multiply-adds per row and
  /// never touches the JointDef or a quaternion.
  struct Joint {
    // ---- per step --------------------------------------------------------
    const JointDef* def = nullptr;
    std::uint32_t slot = 0;
    std::uint32_t a = 0, b = 0;  ///< body / velocity indices (b unused when world)
    JointType type = JointType::Ball;
    bool world = false;          ///< B is the world (anchor and frame in world coordinates)
    bool movesA = false, movesB = false;
    bool soft = false;           ///< spring joint (JointDef stiffness > 0)
    bool angularFree = false;    ///< soft joint without angular spring: no angular rows
    bool motor = false;          ///< hinge motor row
    bool stops = false;          ///< the two angle stops about the limit axis (hinge limits, twist)
    bool swingRow = false;       ///< the swing cone row (cone-twist)
    Real mA = 0, mB = 0;         ///< inverse masses, 1/kg
    Mat3 iA = Mat3::Zero(), iB = Mat3::Zero();  ///< inverse world inertia at the start of the step
    Real gammaLin = 0, betaLin = 0, gammaAng = 0, betaAng = 0;  ///< spring gains, per substep
    Real lower_rad = 0, upper_rad = 0;  ///< hinge angle or twist limits
    Real swingLimit_rad = 0;
    Real cosHalfSwing = 1;       ///< cos(swingLimit / 2): the swing row is solved beyond half the cone
    Real motorSpeed_radps = 0, maxMotorImpulse = 0;  ///< hinge motor; impulse bound per substep, N m s
    // ---- per solve phase -------------------------------------------------
    /// Poses the geometry below was computed from (refreshGeometry skips a
    /// joint whose bodies have not moved since by more than
    /// kGeometryTolerance; invalid until the first refresh of the step).
    bool geometryValid = false;
    Vec3 refPositionA_m = Vec3::Zero(), refPositionB_m = Vec3::Zero();
    Quat refOrientationA = Quat::Identity(), refOrientationB = Quat::Identity();
    /// [rA]x, [rB]x of the anchor offsets from the centres (world, m): the
    /// point rows' Cdot = vB - vA + [rA]x wA - [rB]x wB (a packed product
    /// each; Eigen's cross3 went through the stack and stalled).
    Mat4r SA = Mat4r::Zero(), SB = Mat4r::Zero();
    Vec4r C = Vec4r::Zero();          ///< pB - pA, m
    Mat4r pointKinv = Mat4r::Zero();  ///< (K + gamma)^-1 of the point rows (3x3, padded)
    Mat4r MA = Mat4r::Zero(), MB = Mat4r::Zero();  ///< IA^-1 [rA]x, IB^-1 [rB]x: angular change per point impulse
    bool pointOk = false;
    // Angular equality rows (hinge 2, fixed 3): axes, IA^-1 axis, IB^-1 axis
    // (setAngularAxis), (K + gamma)^-1 of the block, position error per row.
    int angularRows = 0;
    Vec4r ax[3], axA[3], axB[3];
    Mat4r angKinv = Mat4r::Zero();
    Vec4r angC = Vec4r::Zero();
    // Limit rows (hinge angle and motor, or twist): one axis (setLimitAxis).
    Vec4r limitAxis = Vec4r::Zero(), limitA = Vec4r::Zero(), limitB = Vec4r::Zero();
    Real limitK = 0;  ///< limitAxis.(IA^-1 + IB^-1) limitAxis
    Real angle = 0;   ///< hinge angle or twist angle, rad
    // Swing row (cone-twist).
    Vec4r swingAxis = Vec4r::Zero(), swingA = Vec4r::Zero(), swingB = Vec4r::Zero();
    Real swingK = 0, swingAngle = 0;
    bool swingActive = false;  ///< near enough to the cone for its row
    bool swingAxisOk = false;  ///< the two twist axes are not parallel (swingAxis defined)
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

/// Angular equality row k along `axis` (world), with IA^-1 axis and IB^-1 axis.
inline void setAngularAxis(ImpulseJoints::Joint& j, int k, const Vec3& axis) {
  j.ax[k] = wide(axis);
  j.axA[k] = wide(Vec3(j.iA * axis));
  j.axB[k] = wide(Vec3(j.iB * axis));
}

/// The limit rows' axis n (world), IA^-1 n, IB^-1 n and n.(IA^-1 + IB^-1) n.
inline void setLimitAxis(ImpulseJoints::Joint& j, const Vec3& n) {
  const Vec3 nA = j.iA * n, nB = j.iB * n;
  j.limitAxis = wide(n);
  j.limitA = wide(nA);
  j.limitB = wide(nB);
  j.limitK = n.dot(nA + nB);
}

// ---- the point block every joint type has (ball_joint.cpp derives it) ----------

// timesCross and crossTimes stay calls and impulsePointRows is inlined into
// refreshGeometry, as the compiler had them when the three were part of the
// impulse solver's file: inlined into an out-of-line impulsePointRows they
// made a hanging chain of 1000 ball joints step 8 % slower (tumble_bench_joints).

/// I [r]x, column by column ([r]x e_k = r x e_k has two non-zero entries):
/// 18 multiplies instead of a 3x3 product's 27.
[[gnu::noinline]] inline Mat3 timesCross(const Mat3& I, const Vec3& r) {
  Mat3 m;
  m.col(0) = r.z() * I.col(1) - r.y() * I.col(2);
  m.col(1) = r.x() * I.col(2) - r.z() * I.col(0);
  m.col(2) = r.y() * I.col(0) - r.x() * I.col(1);
  return m;
}

/// [r]x M, column by column (r x each column).
[[gnu::noinline]] inline Mat3 crossTimes(const Vec3& r, const Mat3& M) {
  Mat3 m;
  for (int k = 0; k < 3; ++k) m.col(k) = r.cross(M.col(k));
  return m;
}

/// The point block from the anchor offsets rA, rB and anchor points pA, pB
/// (world): (K + gamma)^-1, IA^-1 [rA]x, IB^-1 [rB]x, the cross matrices and
/// the error C = pB - pA.
[[gnu::always_inline]] inline void impulsePointRows(ImpulseJoints::Joint& j, const Vec3& rA, const Vec3& rB,
                                                    const Vec3& pA, const Vec3& pB) {
  // K = (mA + mB) 1 - [rA] IA^-1 [rA] - [rB] IB^-1 [rB].
  const Mat3 MA = timesCross(j.iA, rA), MB = timesCross(j.iB, rB);
  Mat3 K = (j.mA + j.mB) * Mat3::Identity() - crossTimes(rA, MA) - crossTimes(rB, MB);
  if (j.soft) K.diagonal().array() += j.gammaLin;
  const Mat3 Kinv = K.inverse();
  j.pointOk = Kinv.allFinite();
  j.pointKinv = wide(Kinv);
  j.MA = wide(MA);
  j.MB = wide(MB);
  j.SA = wide(skew(rA));
  j.SB = wide(skew(rB));
  j.C = wide(Vec3(pB - pA));
}

}  // namespace tumble::physics
