#pragma once
// The Lagrange-multiplier joint solver's data (lagrange_solver.cpp derives
// it): the jointed bodies in double, the constraint rows, the sparse system
// and what the substep driver (lagrange_substeps.cpp) keeps between calls.
// Each joint type's rows are in its own file (ball_joint.cpp, ...), built
// with RowBuilder.
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "physics/constraint_solver.h"
#include "physics/joints/joint_system.h"

namespace tumble::physics {

struct SolverVelocity;

namespace lagrange {

using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;
using Qd = Eigen::Quaterniond;
using V6 = Eigen::Matrix<double, 6, 1>;

inline V3 wide3(const Vec3& v) { return v.cast<double>(); }

/// A body the joints touch, in double.
struct BodyState {
  BodyId id;
  bool dynamic = false;  ///< has mass and moves this step (awake)
  double mass = 0, invMass = 0;
  V3 inertiaLocal = V3::Zero();
  V3 x = V3::Zero(), v = V3::Zero(), w = V3::Zero();
  Qd q = Qd::Identity();
  V3 extForce = V3::Zero(), extTorque = V3::Zero();  ///< forces already applied this step
  // Derived per evaluation.
  M3 R = M3::Identity(), invI = M3::Zero();
  V3 Qf = V3::Zero(), Qt = V3::Zero();  ///< applied force / torque incl. gravity, gyroscopic, springs
  V3 Fc = V3::Zero(), Tc = V3::Zero();  ///< constraint force / torque (result)
  V3 Tm = V3::Zero();  ///< hinge motor torque (an applied torque the World does not know)
};

struct Row {
  std::uint32_t joint = 0;  ///< slot index
  int a = -1, b = -1;       ///< body states; -1 = world
  V6 ja = V6::Zero(), jb = V6::Zero();
  double c = 0, cdot = 0, jdq = 0;
  double jturn = 0;  ///< substeps: J_w alpha, the World's free turn within the substep (addFreeTurnCurvature), m/s^2 or rad/s^2
  double k = 0, d = 0;   ///< spring gains when soft
  bool limit = false;    ///< inequality row, lambda >= 0
  bool soft = false;     ///< explicit spring, not solved
  bool angular = false;  ///< counts as torque for breaking
  bool active = true;
  bool touched = false;  ///< substeps: its jointed assembly touches a contact (JointSettings::compliance)
  int index = -1;  ///< position in the solved system
  double lambda = 0;  ///< multiplier: constraint force (N) or torque (N m) of the row
  double target = 0;  ///< substeps: J v the row's velocity must end the substep with
};

/// One joint's frame and anchor in world coordinates.
struct JointPose {
  V3 r = V3::Zero(), p = V3::Zero();  ///< anchor offset from the centre, anchor point
  M3 F = M3::Identity();              ///< joint frame axes (columns) in the world
  V3 w = V3::Zero(), v = V3::Zero();  ///< body velocities (zero for the world)
};

/// Appends the rows of one joint: J_a, J_b (6 each: force then torque), the
/// error C and the velocity-product term J' q' (lagrange_solver.cpp, top).
struct RowBuilder {
  std::vector<Row>& rows;
  std::uint32_t joint;
  int a, b;
  const BodyState* A;
  const BodyState* B;
  V3 wa() const { return A ? A->w : V3::Zero(); }
  V3 wb() const { return B ? B->w : V3::Zero(); }

  Row& add() {
    Row& r = rows.emplace_back();
    r.joint = joint;
    r.a = a;
    r.b = b;
    return r;
  }
  /// Angular "dot" row, u fixed in A, w fixed in B: C = u.w - c0,
  /// J = u x w (vanishes where u.w is extreme: only for the cone limit).
  Row& dot(const V3& u, const V3& w, double c0) {
    Row& r = add();
    const V3 n = u.cross(w);
    r.ja.tail<3>() = n;
    r.jb.tail<3>() = -n;
    r.c = u.dot(w) - c0;
    const V3 wA = wa(), wB = wb();
    r.jdq = wA.cross(wA.cross(u)).dot(w) + 2 * wA.cross(u).dot(wB.cross(w)) + u.dot(wB.cross(wB.cross(w)));
    r.angular = true;
    return r;
  }
  /// Angular equality row with a fixed direction n (a unit axis of A's joint
  /// frame, turning with A) and error c: C' = n.(w_a - w_b),
  /// J' q' = (w_a x n).(w_a - w_b). Unlike dot(), its Jacobian never
  /// vanishes, however far the joint is twisted out of line (see
  /// "Robustness" in lagrange_substeps.cpp).
  void axis(const V3& n, double c) {
    Row& r = add();
    r.ja.tail<3>() = n;
    r.jb.tail<3>() = -n;
    r.c = c;
    const V3 wA = wa();
    r.jdq = wA.cross(n).dot(wA - wb());
    r.angular = true;
  }
  /// Limit on an angle theta about n with theta' = n.(w_b - w_a):
  /// sign +1: C = theta - lower >= 0; sign -1: C = upper - theta >= 0.
  void angleLimit(const V3& n, double c, double sign, const V3& wm) {
    Row& r = add();
    r.ja.tail<3>() = -sign * n;
    r.jb.tail<3>() = sign * n;
    r.c = c;
    r.jdq = sign * wm.cross(n).dot(wb() - wa());
    r.limit = true;
    r.angular = true;
  }
  static M3 skew3(const V3& v) {
    M3 m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
  }
};

/// Everything one evaluation of the constraint forces needs.
struct Evaluation {
  std::vector<JointDef*> defs;
  std::vector<std::uint32_t> slots;         ///< joint slot per evaluation joint
  std::vector<std::uint32_t> generations;   ///< its generation (the slot may be reused later)
  std::vector<std::pair<int, int>> bodies;  ///< state index of A and B per joint (-1 = world)
};

/// The joint's frame and anchor on one side (null b: the world, whose local
/// values are world values).
JointPose poseOf(const Vec3& localAnchor, const Quat& localFrame, const BodyState* b);

/// A body's state as the World has it now.
BodyState stateFromWorld(const World& world, BodyId id);

}  // namespace lagrange

struct JointSystem::Impl {
  std::vector<std::uint32_t> order;  ///< joint slots in elimination order
  lagrange::Evaluation ev;
  std::vector<lagrange::V3> jointForce, jointTorque;  ///< per evaluation joint: on body A (last solve)
  std::vector<int> slotOf;           ///< World body index -> state index
  std::vector<lagrange::BodyState> states;
  std::vector<lagrange::Row> rows;
  std::vector<std::vector<int>> bodyRows;  ///< per state: solved rows touching it
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs, lambda;
  /// J W J^T and its factorization. The sparsity pattern it was last
  /// analysed for is kept: while it stays the same (same joints, same active
  /// limits) only the numeric factorization runs.
  struct Factor {
    Eigen::SparseMatrix<double> A;
    /// Eigen's LDL^T, with the factor's column pointers readable after the
    /// symbolic analysis alone (matrixL() asserts a numeric factorization):
    /// they give the cost of the factorization before it runs.
    struct Ldlt : Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> {
      const int* analysedColumnStarts() const { return this->m_matrix.outerIndexPtr(); }
    };
    Ldlt ldlt;
    std::vector<int> patternOuter, patternInner;
    double work = 0;  ///< multiply-adds of one factorization of that pattern, about: sum over L's columns (c_j + 1)^2
  };
  Factor factor;
  std::vector<double> inverseDiagonal, inverseValues;  ///< (A^-1)_ii and A^-1 on L's pattern (compliance)

  // ---- inside World::step (lagrange_substeps.cpp, "Time stepping") ----
  double h = 0;             ///< substep length, s
  /// The World moves positions with the substep's end velocity (x += h v:
  /// symplectic or backward Euler), so the relax keeps the curvature term
  /// (lagrange_substeps.cpp, "Relax target").
  bool endVelocityMovesPositions = true;
  bool inStep = false;      ///< prepared for the World step in progress
  /// The last solve found the factorization over JointSettings::
  /// lagrangeMaxFactorWorkPerRow and solved nothing (JointSystem::step switches).
  bool overCostCap = false;
  std::uint64_t serial = 0; ///< World steps prepared so far
  double time_s = 0;        ///< simulated time of the substeps solved so far (the contacts' memory)
  std::vector<lagrange::V3> vk, wk;   ///< per state: the velocity as the World hands it over (v_k)
  std::vector<lagrange::V3> dv, dw;   ///< per state: velocity change of a projection (substepProject)
  std::vector<lagrange::V6> pushout;   ///< per state: J^T mu, the generalized impulse that changes its push-out velocity (substepProjectPushout)
  std::vector<lagrange::V3> freeTurn;  ///< per state: angular acceleration of the World's free turn, rad/s^2 (substepSolve)
  std::vector<double> rowImpulse;  ///< per row: impulse of a projection
  /// Per World body slot: the velocity right after the joints last changed
  /// it, and in which World step (q' of the last solve; see "Time stepping").
  struct Memo {
    std::uint32_t generation = 0;
    std::uint64_t serial = 0;
    lagrange::V3 v = lagrange::V3::Zero(), w = lagrange::V3::Zero();
    /// When a contact sweep last changed the body's velocity (s of the
    /// joints' substep clock, time_s; -inf: never).
    double contactTime_s = -std::numeric_limits<double>::infinity();
  };
  std::vector<Memo> memo;
  std::vector<int> assembly;          ///< per state: union-find parent over the joints (compliance)
  std::vector<char> assemblyTouched;  ///< per assembly root: a contact moved one of its bodies
  std::vector<JointBreakEvent> pendingBreaks;  ///< found in the last World step, removed before the next
  bool resultsPending = false;                 ///< forces of the last World step not yet recorded
};

namespace lagrange {

/// Fills the derived quantities of the states (rotation, inverse inertia,
/// applied forces Q) and clears the constraint forces.
void deriveStates(std::vector<BodyState>& states, const JointSettings& js, const V3& gravity, bool includeExternal);
/// Every row of every joint (in elimination order) for the current states;
/// soft equality rows are marked soft, limits only when violated.
void buildRows(const Evaluation& ev, std::vector<BodyState>& states, std::vector<Row>& rows);
/// Hinge motors' explicit servo torques into Q (and Tm).
void addMotorTorques(const Evaluation& ev, std::vector<BodyState>& st, const JointSettings& js);
/// Numbers the rows that are solved (hard, active, touching a dynamic body:
/// their position in the system) and lists them per body. Returns their count.
int numberSolvedRows(JointSystem::Impl& im);
/// A = J W J^T over the numbered rows, then its LDL^T factorization
/// (compliance: see JointSettings::compliance). False, and nothing
/// factorized, when the factorization would cost more than maxWorkPerRow
/// multiply-adds per row (JointSettings::lagrangeMaxFactorWorkPerRow;
/// stats.factorWork says how much).
bool assembleAndFactorize(JointSystem::Impl& im, int m, JointSolveStats& stats, double compliance = 0,
                          double maxWorkPerRow = std::numeric_limits<double>::infinity());
/// The first half of assembleAndFactorize: A and its symbolic analysis, and
/// whether the factorization's work fits maxWorkPerRow per row.
bool assembleWithinCost(JointSystem::Impl& im, int m, JointSolveStats& stats, double maxWorkPerRow);
/// The second half: the numeric factorization of the assembled A.
void factorizeAssembled(JointSystem::Impl& im, int m, JointSolveStats& stats, double compliance);
/// The constraint forces (states[i].Fc, Tc) for the given states at the
/// acceleration level (integrateFree). Returns the joints that broke.
std::vector<JointBreakEvent> solveConstraints(JointSystem::Impl& im, const JointSettings& js, const V3& gravity,
                                              bool includeExternal, JointSolveStats& stats);

/// The joints in elimination order (elimination_order.cpp): a post-order
/// walk of the body tree, which makes J W J^T's LDL^T free of fill-in for
/// chains and trees. defs and slotIds: the live joints; returns slot ids.
std::vector<std::uint32_t> eliminationOrder(const World& world, const std::vector<JointDef>& defs,
                                            const std::vector<std::uint32_t>& slotIds);

/// Adds J_b^T lambda of a row to its bodies' force/torque arrays.
template <typename FA>
void scatterRow(const Row& r, double lambda, FA&& add) {
  if (r.a >= 0) add(r.a, r.ja * lambda);
  if (r.b >= 0) add(r.b, r.jb * lambda);
}

}  // namespace lagrange

/// The Lagrange solver as the World's ConstraintSolver (constraint_solver.h):
/// the solve once per substep (warmStart), the projection before each
/// contact sweep (solve) and after the last one (beforeIntegrate). See "Time
/// stepping" in lagrange_substeps.cpp.
class LagrangeSubsteps final : public ConstraintSolver {
 public:
  explicit LagrangeSubsteps(JointSystem& joints) : m_joints(joints) {}
  void prepare(const World& world, Real dt_s, int substeps) override;
  void warmStart(SolverVelocity* vel, const Body* bodies) override;
  Real solve(SolverVelocity* vel, const Body* bodies, bool useBias) override;
  void beforeIntegrate(SolverVelocity* vel, const Body* bodies) override;
  void projectPushout(SolverVelocity* pseudo, const Body* bodies) override;
  void finish(const World& world) override;

 private:
  JointSystem& m_joints;
};

}  // namespace tumble::physics
