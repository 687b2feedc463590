// Joint constraint forces by Lagrange multipliers (issue 4, formulation A).
//
// ---- Derivation (Baraff, "Linear-time dynamics using Lagrange multipliers",
//      SIGGRAPH 1996) --------------------------------------------------------
// Stack the bodies' velocities q' = (v_1, w_1, ..., v_n, w_n) (centre-of-mass
// velocity and world angular velocity, 6 per body). Newton-Euler reads
//   M q'' = Q + J^T lambda,
// M = diag(m_i 1, I_i) (I_i = R_i I_local R_i^T), W = M^-1, Q the applied
// generalized forces: gravity m g and other forces F on the centre, torques
// tau minus the gyroscopic term w x (I w). J^T lambda is the constraint force,
// one multiplier per constraint row. A joint is a set of rows C(x) = 0 with
// C' = J q'. Differentiating once more, C'' = J q'' + J' q'. Demanding
// C'' = 0 lets errors drift; Baumgarte's feedback asks instead for
//   C'' = -k_s C - k_d C'      (a critically damped spring on the error),
// and substituting q'' = W (Q + J^T lambda):
//   J W J^T lambda = -J' q' - J W Q - k_s C - k_d C'.
// J W J^T is symmetric positive definite when the rows are independent, so
// it is factorized by Cholesky (LDL^T).
//
// Rows (r_a = R_a * localAnchorA, the anchor's offset from A's centre; p_a =
// x_a + r_a; likewise for B; for a world anchor v_b = w_b = 0):
//   ball (Baraff's point-to-point rows, 3):  C = p_a - p_b,
//     J_a = [ 1  -[r_a]x ],  J_b = [ -1  [r_b]x ],
//     J' q' = w_a x (w_a x r_a) - w_b x (w_b x r_b).
//   angular "dot" row, u fixed in A, w fixed in B (1): C = u.w - c0,
//     J_a = [ 0  (u x w)^T ],  J_b = [ 0  -(u x w)^T ],
//     J' q' = (w_a x (w_a x u)).w + 2 (w_a x u).(w_b x w) + u.(w_b x (w_b x w)).
//     Cone: a1.b1 - cos(swingLimit) >= 0 (a_i, b_i the joint frames' axes
//     in A and B). Only for that limit: the row's J = u x w vanishes where
//     u.w is extreme (see "Angular rows" below).
//   angular "axis" row, n a unit axis fixed in A (1): C = an angle error
//     about n, J_a = [ 0  n^T ],  J_b = [ 0  -n^T ],  J' q' = (w_a x n).(w_a - w_b).
//     Hinge (the +X axes stay aligned): n = -a3, C = a2.b1 and n = a2,
//     C = a3.b1. Fixed: n = a_i, C = -phi.a_i, phi the rotation vector of
//     B's frame relative to A's (from their relative quaternion).
//   angle limit row (1): hinge angle theta = atan2(b2.a3, b2.a2) about a1
//     (twist: the twist part of the relative rotation, about n = the bisector
//     of a1 and b1); C = theta - lower >= 0 or upper - theta >= 0,
//     theta' = n.(w_b - w_a), J' q' ~ (w_m x n).(w_b - w_a), w_m = w_a for
//     the hinge, (w_a + w_b)/2 for the twist (approximate: a limit row only
//     has to push back, Baumgarte absorbs the rest).
// Inequality rows (limits) use a simple active set: a limit row is added
// when its C < 0 (violated); after the solve, rows whose lambda < 0 (they
// would pull the joint into the limit) are dropped and the system solved
// again (at most JointSettings::maxActiveSetIterations times).
//
// Hinge motors are not rows here: an explicit servo torque tau = clamp(
// I_axial k_d (speed - rate), +-maxTorque) about the hinge axis joins Q (the
// rate reaches the target with the Baumgarte time constant 1/k_d unless the
// torque saturates). A bounded row would need a second active set; the
// impulse solver (formulation B) does have the exact bounded row.
//
// Soft joints: the equality rows of a joint with a stiffness are not solved
// for; their lambda = -k C - c C' is an explicit spring force, added to Q
// before the hard rows are solved (so hard rows see the springs).
//
// ---- Linear time --------------------------------------------------------------
// (J W J^T)_{rs} = sum over bodies b shared by rows r and s of J_rb W_b J_sb^T.
// It is non-zero only where two joints share a dynamic body: for a chain it
// is block tridiagonal, for a tree of bodies it is the "line graph" of the
// tree, a chordal graph whose perfect elimination order is: joints in a
// post-order walk of the body tree (a body's child joints before the joint
// to its parent). Eliminating in that order creates no fill-in, so LDL^T with
// that (natural) ordering costs O(sum of squared body degrees) = O(links) for
// bounded degree. We order the joints that way whenever the joint set changes
// (joints closing a loop go last; loops cause some fill, as they must) and
// factorize with Eigen::SimplicialLDLT under NaturalOrdering. lastSolve()
// reports the fill-in measured from the factor (0 for chains and trees).
// Baraff factorizes the larger but always tree-structured system
// [M -J^T; -J 0] instead; J W J^T is smaller and for the trees we build (no
// body with more than 5 joints) equally sparse, so we kept the textbook form.
// Rejected: a dense LLT (cubic: 1000 links = 3000 rows, ~1 s per step) and
// Eigen's AMD ordering (finds a zero-fill order too, but costs a symbolic
// analysis that our post-order gives for free).
//
// ---- Time stepping ------------------------------------------------------------
// With the World (JointSystem::step, or beforeWorldStep + World::step): the
// multipliers are solved in every World substep, through the World's
// ConstraintSolver hook (LagrangeSubsteps below), at the substep's state:
// poses as integrated so far, after the World's free step (gravity, applied
// forces, springs, gyroscopic term, by whichever integrator it runs) and the
// contacts' warm start. Let q'_J be the velocity the joints left at their
// last solve (a per-body memo) and v_k the velocity handed over now.
// Everything that changed v since, v_k - q'_J, is the known force: h W Q.
// With C' = J q'_J, the paper's equation times h is
//   J W J^T (h lambda) = target - J v_k,
//   target = (C' - h (J'q'_J + k_s C)) / (1 + h k_d + h^2 k_s),
// and v = v_k + W J^T (h lambda). The target is Baumgarte's C'' = -k_s C -
// k_d C' over the substep, with C and C' taken at the end of the substep
// (backward Euler on the error dynamics). Taken at its start, (1 - h k_d) C'
// - h (J'q' + k_s C), a 10-link chain released horizontally gained 6.6 % of
// its m g L in 10 s and blew up with 4 substeps; implicit, it never gains
// and holds with 1 substep. Limit rows carry max(C', 0): they stop the
// approach inelastically. One factorization per substep (8 per step); the
// pattern is analysed once and reused while the rows stay the same. The
// projections between and after the contact sweeps (see "Robustness")
// reuse that factorization: one back-substitution each.
// What changed, and why. Before, lambda was solved once per step and held
// as a force through the 8 substeps: a free chain whose links do not touch
// blew up (base:chain, WILL_FAIL), and the contacts were not in Q (10.3 cm
// on ragdoll_pile). Now the contacts' impulses of the substep before (their
// warm start, in v_k) are known forces, W comes from the substep's poses,
// and: chain 3.7 mm, 100 links 2.2 cm, ragdoll_pile 2.6 cm, asleep.
// Measured and rejected (ragdoll_pile, stairs, hit, 10 piled dolls):
//   - the joints solved once per substep only, before the contact sweeps
//     (the version before "Robustness" below): see there;
//   - the joints re-projected between the contact sweeps with W taken as
//     the contact rows take it (step start): a
//     chain link spun to 130 rad/s by a grab got joint impulses that do work;
//   - q' after the contacts instead of q'_J (so that the contacts' impulse
//     is a velocity, not a force): the pile and the hit blew up;
//   - the post-stabilization projection at every step: the contacts then
//     push back into the projected parts (a head jittering on the stairs);
//     it now runs only when a joint or a jointed body is new to the solver
//     (a link added to a swinging chain: 13.7 cm without, 8 mm with);
//   - larger gains (k_s, k_d): smaller errors on chains (100 links 2.2 cm
//     -> 1.4 cm at (1600, 80), 0.8 cm at (14400, 240); a grabbed chain 8.8
//     -> 2.2 cm), but (1600, 80) blew up 6 piled dolls and a 20 m/s
//     ragdoll_hit, (3600, 120) that hit too, and (14400, 240) opened the
//     stairs doll by 7.3 cm. The defaults (400, 40), those of the stability
//     table, blew up none of these scenes.
//
// ---- Robustness (piles of rag-dolls) ------------------------------------------------
// Symptom: 10 dolls piled (ragdoll_pile --set count=10) blew up (NaN, anchor
// error 1e8 m) or ended at 16.6 cm depending only on the rounding of the
// World's gyroscopic step (LU or closed-form 3x3 inverse); 12 dolls, dt 1/30
// or 4 substeps blew up as well. Traced body by body, two causes:
//  1. The hinge and fixed joints' angular rows were "dot" rows, C = u.w
//     with J = u x w. |J| = sin of the angle between u and w: where the
//     joint is twisted so that u.w nears +-1 the row loses rank. In the pile
//     elbows were bent 60-90 degrees off their axis (|J| down to 0.045); a
//     row that cannot pull the joint back asks, through Baumgarte, for
//     velocities ~ 1/|J|: a forearm spun to 46 rad/s at rest, then 275 rad/s,
//     then NaN (t = 6.05 s). Fix: "axis" rows, J = an axis fixed in A (never
//     zero), C = the same angle error (sin, or the relative rotation vector
//     for the fixed joint). The cone limit keeps its dot row (u.w there is
//     cos(swingLimit), far from +-1).
//  2. The contacts, solved after the joints in each substep, had the last
//     word on the velocities the positions move with, and the joints saw
//     their impulses one substep late. A contact treats a part as free: a
//     forearm's axial inertia is 0.95 g m^2, so friction at its surface spun
//     it by 200-1000 rad/s in one substep (up to 1 rad of twist before the
//     joints could answer). The joints then cancelled that as a known force,
//     the contacts pushed harder: hard rows against hard contacts raise each
//     other without limit, and the J'q' term, quadratic in w, turned the
//     growth super-exponential (157, 561, 1.9e3, 4e4, 6e6 rad/s). Hinges
//     ended 50-120 degrees off axis even where nothing blew up. Fix, three
//     parts, each measured:
//     - joints and contacts take turns between the contact sweeps (block
//       Gauss-Seidel, substepProject; before, only when a joint's own two
//       bodies collided), and the joints have the last word before the
//       positions are integrated (ConstraintSolver::beforeIntegrate): 10
//       dolls' hinges stay within 0.5 degree at rest (were 50-120);
//     - the relax sweeps target J v = 0 (limits: no approach), like the
//       contacts' relax: the Baumgarte velocity that moved the positions
//       does not stay in the velocity (coupled with the Baumgarte target
//       in the relax sweeps too: the stairs doll stuck on a step, its
//       'tumbled down' expectation failed);
//     - a compliance on the rows' diagonal (JointSettings::compliance,
//       1 %): where contacts and joints cannot both hold, the impulses stay
//       bounded (without it: 12 dolls 10 cm, with 6.8 cm; ragdoll_stairs
//       not at rest, 0.19 m/s). Scaled how, measured (tumble_bench_joints,
//       hanging chains of 10 / 100 / 1000 links; 12 um / 55 um / 21 um
//       rigid):
//       * 1 % of each row's own J W J^T diagonal everywhere (the first
//         version): 43 um / 7.7 mm / 13 cm. The own diagonal is the links'
//         mass, but the top joint of a chain carries the whole chain: the
//         error a compliance eps lets through is eps * lambda per substep,
//         and lambda grows with the load;
//       * only in substeps where contacts touched a jointed body, rigid
//         otherwise: chains back to rigid, but then the dolls of a pile
//         fall rigid and land with the compliance switching on mid-impact:
//         elbows up to 87-155 degrees off their axis during the impacts
//         (the 10-doll and the perturbation tests failed), and the stairs
//         doll missed "at rest" (the earlier measurement);
//       * relative to the whole system along the row: eps_i = 1 % of
//         1 / (A^-1)_ii, the inverse effective mass row i sees with all the
//         other rows holding (for a chain's top joint the whole chain).
//         eps * lambda no longer grows with the load. (A^-1)_ii comes from
//         the factor by Takahashi's recurrence on L's pattern
//         (inverseDiagonal; linear for trees like the factorization), then
//         A + eps is factorized again: one more numeric factorization per
//         substep (1000 links: solve 11.1 ms per step, 8.6 ms before, 6.9
//         rigid). Alone, this is too stiff for piles (10 dolls: elbows 42
//         degrees off axis during the impacts, test bound 30);
//       * kept: both. Rows of an assembly (bodies connected by joints) that
//         a contact moved in the last second (kContactMemory_s; detected
//         as a velocity that is not what the joints wrote before the
//         contact sweep) keep 1 % of their own diagonal, switched on at the
//         first contact sweep that touches them (not the next substep);
//         all other rows get 1 % of the system's. Chains 12 um / 49 um /
//         1.1 mm; 10 dolls 4.3 cm, elbows 17 degrees at most, 0.1 at the
//         end; ragdoll_stairs 4.7 cm and at rest at dt 1/60 (with one
//         step of memory instead of 1 s: 10.5 cm, not at rest: the doll
//         switched at every bounce). A chain whose links collide with each
//         other counts as touched and sags as before (7.7 mm at 100
//         links): disable collision between jointed neighbours.
//     The gyroscopic step was not the cause (it only picked which run blew
//     up): the closed-form inverse stays. Clamping the J'q' term (its exact
//     change over a substep, bounded in w) removed NaN but doubled the errors
//     (13-26 cm); rejected. Coupling without the last word made the pile
//     finite but left the hinges twisted and the stairs doll stuck.
//   Measured (tumble run base:ragdoll_pile --set physics.joint_solver=
//   lagrange --seconds 8, joint_error_max_m, closed-form / LU gyroscopic
//   step): count 3..12: 1.2/1.2, 2.5/2.5, 3.2/3.2, 4.5/3.7, 5.7/5.3,
//   7.3/5.3, 5.0/3.4, 6.4/4.9, 7.1/4.4, 6.8/5.4 cm; 10 dolls at dt 1/30
//   15.6/10.8 cm, dt 1/120 6.2/5.3, 4 substeps 5.0/6.2, 16 substeps
//   6.8/9.0; no NaN anywhere (before: 10, 12, dt 1/30 blew up).
//   With the compliance kept above (closed-form gyroscopic step, same
//   command): count 3..12: 1.2, 2.5, 3.2, 4.8, 4.4, 6.2, 4.7, 7.8, 4.5,
//   5.3 cm; 10 dolls at dt 1/30 9.2 cm, dt 1/120 7.3, 4 substeps 6.0, 16
//   substeps 9.2; no NaN (main before this change, same machine: 1.2, 2.5,
//   3.2, 4.5, 5.7, 7.3, 5.0, 6.4, 7.1, 6.8; 9.2, 16.4, 5.0, 6.8).
// Known limit: in piles of 7 or more dolls a part can still move at 0.1-0.5
// m/s after 8 s (16 s too): a head hanging over the pile's edge swings on its
// frictionless neck as a conical pendulum along the swing limit (no contact;
// the limit row stops approach but nothing damps the motion along it; B's
// soft rows damp it). Joint friction would be the fix.
//
// Alone (integrateFree): explicit Euler, the explicit trapezoid rule (Heun),
// semi-implicit Euler or RK4 on the full state (x, q, v, w) with the
// constraint forces re-solved at every stage, no projection: the paper's
// scheme, for its stability claim. Largest stable dt (5-link chain released
// at 45 degrees, 5 s; stable = finite, anchor error < 5 cm, |E - E0| < m g L;
// printed by tests/physics_joints):
//      k_s    k_d   explicit Euler  trapezoid  semi-implicit  RK4
//        0      0       0.002         0.015       0.001       0.06
//       25     10       0.002         0.0225      0.0275      0.08
//      100     20       0.002         0.0225      0.03        0.08
//      400     40       0.002         0.0175      0.03        0.08   (defaults)
//      900     60       0.002         0.0175      0.0225      0.06
//     2500    100       0.002         0.0275      0.015       0.04
// Explicit Euler is limited by the chain's own undamped pendulum modes (its
// amplification |1 + i w h| > 1 gains energy at any dt), not by the gains;
// the trapezoid rule reaches the paper's ~0.02-0.03 s and, like the
// semi-implicit scheme, depends on (k_s, k_d): large k_d h or k_s h^2 costs
// stability. The defaults k_s = 400 /s^2, k_d = 40 /s (critically damped,
// 20 rad/s) are stable up to dt = 0.03 s with the semi-implicit scheme the
// World uses (60 Hz has a margin of 1.8).
#include "physics/joints/joint_system.h"

#include "physics/constraint_solver.h"
#include "physics/internal/contact_solver.h"
#include "physics/internal/impulse_joints.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace tumble::physics {

using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;
using Qd = Eigen::Quaterniond;
using V6 = Eigen::Matrix<double, 6, 1>;

const char* jointSolverName(JointSolverKind kind) {
  return kind == JointSolverKind::Impulse ? "impulse" : "lagrange";
}

bool parseJointSolver(const std::string& text, JointSolverKind* out) {
  if (text == "lagrange") *out = JointSolverKind::Lagrange;
  else if (text == "impulse") *out = JointSolverKind::Impulse;
  else return false;
  return true;
}

const char* jointIntegratorName(JointIntegrator m) {
  switch (m) {
    case JointIntegrator::ExplicitEuler: return "explicit_euler";
    case JointIntegrator::Trapezoid: return "trapezoid";
    case JointIntegrator::SemiImplicitEuler: return "semi_implicit_euler";
    case JointIntegrator::Rk4: return "rk4";
  }
  return "?";
}

namespace {

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

V3 wide3(const Vec3& v) { return v.cast<double>(); }

/// One joint's frame and anchor in world coordinates.
struct JointPose {
  V3 r = V3::Zero(), p = V3::Zero();  ///< anchor offset from the centre, anchor point
  M3 F = M3::Identity();              ///< joint frame axes (columns) in the world
  V3 w = V3::Zero(), v = V3::Zero();  ///< body velocities (zero for the world)
};

}  // namespace

/// Everything one evaluation of the constraint forces needs.
struct Evaluation {
  std::vector<JointDef*> defs;
  std::vector<std::uint32_t> slots;         ///< joint slot per evaluation joint
  std::vector<std::uint32_t> generations;   ///< its generation (the slot may be reused later)
  std::vector<std::pair<int, int>> bodies;  ///< state index of A and B per joint (-1 = world)
};

struct JointSystem::Impl {
  std::vector<std::uint32_t> order;  ///< joint slots in elimination order
  Evaluation ev;
  std::vector<V3> jointForce, jointTorque;  ///< per evaluation joint: on body A (last solve)
  std::vector<int> slotOf;           ///< World body index -> state index
  std::vector<BodyState> states;
  std::vector<Row> rows;
  std::vector<std::vector<int>> bodyRows;  ///< per state: solved rows touching it
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs, lambda;
  /// J W J^T and its factorization. The sparsity pattern it was last
  /// analysed for is kept: while it stays the same (same joints, same active
  /// limits) only the numeric factorization runs.
  struct Factor {
    Eigen::SparseMatrix<double> A;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt;
    std::vector<int> patternOuter, patternInner;
  };
  Factor factor;
  std::vector<double> inverseDiagonal, inverseValues;  ///< (A^-1)_ii and A^-1 on L's pattern (compliance)

  // ---- formulation A inside World::step (see "Time stepping") ----
  double h = 0;             ///< substep length, s
  bool inStep = false;      ///< prepared for the World step in progress
  std::uint64_t serial = 0; ///< World steps prepared so far
  double time_s = 0;        ///< simulated time of the substeps solved so far (the contacts' memory)
  std::vector<V3> vk, wk;   ///< per state: the velocity as the World hands it over (v_k)
  std::vector<V3> dv, dw;   ///< per state: velocity change of a projection (substepProject)
  std::vector<double> rowImpulse;  ///< per row: impulse of a projection
  /// Per World body slot: the velocity right after the joints last changed
  /// it, and in which World step (q' of the last solve; see "Time stepping").
  struct Memo {
    std::uint32_t generation = 0;
    std::uint64_t serial = 0;
    V3 v = V3::Zero(), w = V3::Zero();
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

JointSystem::JointSystem(World& world, const JointSettings& settings)
    : m_world(world), m_settings(settings), m_impl(std::make_unique<Impl>()) {
  const JointSolverKind kind = m_settings.solver;
  m_settings.solver = JointSolverKind::Lagrange;
  setSolver(kind);
}

/// Formulation A as the World's ConstraintSolver (constraint_solver.h): the
/// acceleration-level solve once per substep (warmStart), the projection
/// before each contact sweep (solve). See "Time stepping" above.
class LagrangeSubsteps final : public ConstraintSolver {
 public:
  explicit LagrangeSubsteps(JointSystem& joints) : m_joints(joints) {}
  void prepare(const World&, Real dt_s, int substeps) override {
    m_joints.substepPrepare(double(dt_s) / std::max(1, substeps));
  }
  void warmStart(SolverVelocity* vel, const Body* bodies) override { m_joints.substepSolve(vel, bodies); }
  Real solve(SolverVelocity* vel, const Body*, bool useBias) override {
    return Real(m_joints.substepProject(vel, useBias));
  }
  void beforeIntegrate(SolverVelocity* vel, const Body*) override { m_joints.substepProject(vel, true); }
  void finish(const World&) override { m_joints.substepFinish(); }

 private:
  JointSystem& m_joints;
};

JointSystem::~JointSystem() {
  if (m_impulse && m_world.constraintSolver() == m_impulse.get()) m_world.setConstraintSolver(nullptr);
  if (m_lagrange && m_world.constraintSolver() == m_lagrange.get()) m_world.setConstraintSolver(nullptr);
}

void JointSystem::setSolver(JointSolverKind kind) {
  m_settings.solver = kind;
  if (kind == JointSolverKind::Impulse && !m_impulse) {
    if (m_lagrange && m_world.constraintSolver() == m_lagrange.get()) m_world.setConstraintSolver(nullptr);
    m_lagrange.reset();
    m_impl->inStep = false;
    m_impl->resultsPending = false;
    m_impl->pendingBreaks.clear();
    m_impulse = std::make_unique<ImpulseJoints>(*this, m_settings.impulseHertz, m_settings.impulseDampingRatio);
    m_world.setConstraintSolver(m_impulse.get());
  } else if (kind == JointSolverKind::Lagrange && !m_lagrange) {
    if (m_impulse && m_world.constraintSolver() == m_impulse.get()) m_world.setConstraintSolver(nullptr);
    m_impulse.reset();
    m_lagrange = std::make_unique<LagrangeSubsteps>(*this);
    m_world.setConstraintSolver(m_lagrange.get());
  }
}

// ---- joint bookkeeping -------------------------------------------------------------

Result<JointId> JointSystem::createJoint(const JointDef& def) {
  if (auto s = validateJointDef(m_world, def); !s) return makeError(s.error());
  std::uint32_t index;
  if (!m_freeList.empty()) {
    index = m_freeList.back();
    m_freeList.pop_back();
  } else {
    index = std::uint32_t(m_slots.size());
    m_slots.emplace_back();
  }
  Slot& s = m_slots[index];
  const std::uint32_t generation = s.generation + 1;  // odd while alive; the zero handle is null
  s = Slot{};
  s.def = def;
  s.def.localFrameA.normalize();
  s.def.localFrameB.normalize();
  s.generation = generation;
  s.alive = true;
  ++m_jointCount;
  m_orderDirty = true;
  return JointId{index, generation};
}

bool JointSystem::isValid(JointId id) const {
  return !id.isNull() && id.index < m_slots.size() && m_slots[id.index].alive &&
         m_slots[id.index].generation == id.generation;
}

bool JointSystem::destroyJoint(JointId id) {
  if (!isValid(id)) return false;
  Slot& s = m_slots[id.index];
  s.alive = false;
  ++s.generation;
  m_freeList.push_back(id.index);
  --m_jointCount;
  m_orderDirty = true;
  return true;
}

const JointDef& JointSystem::jointDef(JointId id) const {
  TUMBLE_ASSERT(isValid(id), "stale or null JointId; check JointSystem::isValid first");
  return m_slots[id.index].def;
}
bool JointSystem::setMotor(JointId id, Real speed_radps, Real maxTorque_Nm) {
  if (!isValid(id) || !std::isfinite(speed_radps) || !std::isfinite(maxTorque_Nm) || maxTorque_Nm < 0) return false;
  JointDef& d = m_slots[id.index].def;
  d.enableMotor = maxTorque_Nm > 0;
  d.motorSpeed_radps = speed_radps;
  d.maxMotorTorque_Nm = maxTorque_Nm;
  if (m_world.isValid(d.bodyA)) m_world.wake(d.bodyA);
  return true;
}

bool JointSystem::setWorldAnchor(JointId id, const Vec3& anchor_m) {
  if (!isValid(id) || !anchor_m.allFinite()) return false;
  JointDef& d = m_slots[id.index].def;
  if (!d.bodyB.isNull()) return false;
  d.localAnchorB_m = anchor_m;
  if (m_world.isValid(d.bodyA)) m_world.wake(d.bodyA);
  return true;
}

Vec3 JointSystem::lastForce_N(JointId id) const {
  TUMBLE_ASSERT(isValid(id), "stale or null JointId; check JointSystem::isValid first");
  return m_slots[id.index].force_N;
}
Vec3 JointSystem::lastTorque_Nm(JointId id) const {
  TUMBLE_ASSERT(isValid(id), "stale or null JointId; check JointSystem::isValid first");
  return m_slots[id.index].torque_Nm;
}

std::vector<std::pair<BodyId, BodyId>> JointSystem::connectedPairs() const {
  std::vector<std::pair<BodyId, BodyId>> pairs;
  for (const Slot& s : m_slots)
    if (s.alive && !s.def.bodyB.isNull()) pairs.emplace_back(s.def.bodyA, s.def.bodyB);
  return pairs;
}

// ---- geometry of one joint (shared by the rows and the queries) --------------------

static JointPose poseOf(const Vec3& localAnchor, const Quat& localFrame, const BodyState* b) {
  JointPose p;
  if (!b) {  // world: the local values are world values
    p.p = wide3(localAnchor);
    p.F = localFrame.cast<double>().toRotationMatrix();
    return p;
  }
  p.r = b->R * wide3(localAnchor);
  p.p = b->x + p.r;
  p.F = b->R * localFrame.cast<double>().toRotationMatrix();
  p.w = b->w;
  p.v = b->v;
  return p;
}

/// Hinge angle / twist angle of frame B relative to frame A about A's +X.
static double hingeAngle(const M3& FA, const M3& FB) {
  return std::atan2(FB.col(1).dot(FA.col(2)), FB.col(1).dot(FA.col(1)));
}
static double twistAngle(const M3& FA, const M3& FB) {
  const Qd rel(FA.transpose() * FB);  // B's frame in A's frame
  double t = 2 * std::atan2(rel.x(), rel.w());
  if (t > M_PI) t -= 2 * M_PI;
  if (t < -M_PI) t += 2 * M_PI;
  return t;
}

static BodyState stateFromWorld(const World& world, BodyId id) {
  BodyState s;
  const Body& b = world.body(id);
  s.id = id;
  s.dynamic = b.isDynamic() && b.awake;
  s.mass = b.mass_kg;
  s.invMass = s.dynamic ? double(b.invMass_per_kg) : 0;
  s.inertiaLocal = wide3(b.inertiaLocal_kgm2);
  s.x = wide3(b.position_m);
  s.q = b.orientation.cast<double>().normalized();
  s.v = wide3(b.linearVelocity_mps);
  s.w = wide3(b.angularVelocity_radps);
  s.extForce = wide3(b.force_N);
  s.extTorque = wide3(b.torque_Nm);
  return s;
}

double JointSystem::jointAngle_rad(JointId id) const {
  const JointDef& d = jointDef(id);
  BodyState a = stateFromWorld(m_world, d.bodyA);
  a.R = a.q.toRotationMatrix();
  BodyState b;
  if (!d.bodyB.isNull()) {
    b = stateFromWorld(m_world, d.bodyB);
    b.R = b.q.toRotationMatrix();
  }
  const JointPose pa = poseOf(d.localAnchorA_m, d.localFrameA, &a);
  const JointPose pb = poseOf(d.localAnchorB_m, d.localFrameB, d.bodyB.isNull() ? nullptr : &b);
  if (d.type == JointType::Hinge) return hingeAngle(pa.F, pb.F);
  if (d.type == JointType::ConeTwist) return twistAngle(pa.F, pb.F);
  return 0;
}

double JointSystem::swingAngle_rad(JointId id) const {
  const JointDef& d = jointDef(id);
  const Quat qa = m_world.body(d.bodyA).orientation * d.localFrameA;
  const Quat qb = d.bodyB.isNull() ? d.localFrameB : m_world.body(d.bodyB).orientation * d.localFrameB;
  const double c = std::clamp<double>((qa * Vec3::UnitX()).cast<double>().dot((qb * Vec3::UnitX()).cast<double>()), -1, 1);
  return std::acos(c);
}

double JointSystem::anchorError_m(bool includeSprings) const {
  double worst = 0;
  for (const Slot& s : m_slots) {
    if (!s.alive || !m_world.isValid(s.def.bodyA) || (!includeSprings && s.def.linearStiffness_Npm > 0)) continue;
    const Body& a = m_world.body(s.def.bodyA);
    V3 pa = wide3(a.position_m) + (a.orientation * s.def.localAnchorA_m).cast<double>();
    V3 pb = wide3(s.def.localAnchorB_m);
    if (!s.def.bodyB.isNull()) {
      if (!m_world.isValid(s.def.bodyB)) continue;
      const Body& b = m_world.body(s.def.bodyB);
      pb = wide3(b.position_m) + (b.orientation * s.def.localAnchorB_m).cast<double>();
    }
    worst = std::max(worst, (pa - pb).norm());
  }
  return worst;
}

// Springs (grabs among them) stretch by design: not an error.
void JointSystem::measureError() { m_maxAnchorError_m = std::max(m_maxAnchorError_m, anchorError_m(false)); }

// ---- elimination order ---------------------------------------------------------------

// Post-order walk of the body tree (see the top of the file): on finishing a
// body, emit its world/static joints, then the joint to its parent. Joints
// that close loops go last.
static std::vector<std::uint32_t> eliminationOrder(const World& world, const std::vector<JointDef>& defs,
                                                   const std::vector<std::uint32_t>& slotIds) {
  const std::size_t nj = defs.size();
  std::uint32_t maxBody = 0;
  for (const JointDef& d : defs) {
    maxBody = std::max(maxBody, d.bodyA.index);
    if (!d.bodyB.isNull()) maxBody = std::max(maxBody, d.bodyB.index);
  }
  auto dyn = [&](BodyId id) { return !id.isNull() && world.isValid(id) && world.body(id).isDynamic(); };
  std::vector<std::vector<int>> incident(maxBody + 1);  // joints at each body (dynamic ends only)
  std::vector<char> isTwoBody(nj, 0);
  for (std::size_t j = 0; j < nj; ++j) {
    const bool da = dyn(defs[j].bodyA), db = dyn(defs[j].bodyB);
    if (da) incident[defs[j].bodyA.index].push_back(int(j));
    if (db) incident[defs[j].bodyB.index].push_back(int(j));
    isTwoBody[j] = da && db;
  }
  std::vector<char> visited(maxBody + 1, 0), emitted(nj, 0);
  std::vector<std::uint32_t> out;
  out.reserve(nj);
  auto other = [&](int j, std::uint32_t body) {
    return defs[j].bodyA.index == body ? defs[j].bodyB.index : defs[j].bodyA.index;
  };
  auto emitAnchors = [&](std::uint32_t body) {
    for (int j : incident[body])
      if (!isTwoBody[j] && !emitted[j]) emitted[j] = 1, out.push_back(slotIds[j]);
  };
  // Roots: bodies with a world/static joint first (a hanging chain is then
  // rooted at its anchor), then any other.
  std::vector<std::uint32_t> roots;
  for (std::uint32_t b = 0; b <= maxBody; ++b)
    for (int j : incident[b])
      if (!isTwoBody[j]) {
        roots.push_back(b);
        break;
      }
  for (std::uint32_t b = 0; b <= maxBody; ++b)
    if (!incident[b].empty()) roots.push_back(b);
  struct Frame {
    std::uint32_t body;
    int viaJoint;     ///< joint to the parent (-1 at the root)
    std::size_t next;  ///< next incident joint to look at
  };
  std::vector<Frame> stack;
  std::vector<char> treeJoint(nj, 0);
  for (std::uint32_t root : roots) {
    if (visited[root]) continue;
    visited[root] = 1;
    stack.push_back({root, -1, 0});
    while (!stack.empty()) {
      Frame& f = stack.back();
      if (f.next < incident[f.body].size()) {
        const int j = incident[f.body][f.next++];
        if (!isTwoBody[j] || treeJoint[j]) continue;
        const std::uint32_t o = other(j, f.body);
        if (visited[o]) continue;  // closes a loop: emitted at the end
        visited[o] = 1;
        treeJoint[j] = 1;
        stack.push_back({o, j, 0});
        continue;
      }
      emitAnchors(f.body);
      if (f.viaJoint >= 0) emitted[f.viaJoint] = 1, out.push_back(slotIds[f.viaJoint]);
      stack.pop_back();
    }
  }
  for (std::size_t j = 0; j < nj; ++j)
    if (!emitted[j]) out.push_back(slotIds[j]);  // loops (and joints without dynamic bodies)
  return out;
}

// ---- rows ------------------------------------------------------------------------------

namespace {

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
  void ball(const JointPose& pa, const JointPose& pb) {
    const V3 c = pa.p - pb.p;
    const V3 jdq = wa().cross(wa().cross(pa.r)) - wb().cross(wb().cross(pb.r));
    const M3 sa = -skew3(pa.r), sb = skew3(pb.r);
    for (int i = 0; i < 3; ++i) {
      Row& r = add();
      r.ja.head<3>() = V3::Unit(i);
      r.ja.tail<3>() = sa.row(i).transpose();
      r.jb.head<3>() = -V3::Unit(i);
      r.jb.tail<3>() = sb.row(i).transpose();
      r.c = c[i];
      r.jdq = jdq[i];
    }
  }
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
  /// vanishes, however far the joint is twisted out of line (see "Angular
  /// rows" at the top of the file).
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

}  // namespace

// Builds every row of every joint (in elimination order) for the current
// states; soft equality rows are marked soft, limits only when violated.
static void buildRows(const std::vector<JointDef*>& defs, const std::vector<std::uint32_t>& slots,
                      const std::vector<std::pair<int, int>>& bodies, std::vector<BodyState>& states,
                      std::vector<Row>& rows) {
  rows.clear();
  for (std::size_t k = 0; k < defs.size(); ++k) {
    const JointDef& d = *defs[k];
    const auto [ia, ib] = bodies[k];
    const BodyState* A = ia >= 0 ? &states[ia] : nullptr;
    const BodyState* B = ib >= 0 ? &states[ib] : nullptr;
    RowBuilder rb{rows, slots[k], ia, ib, A, B};
    const JointPose pa = poseOf(d.localAnchorA_m, d.localFrameA, A);
    const JointPose pb = poseOf(d.localAnchorB_m, d.localFrameB, B);
    const std::size_t first = rows.size();
    rb.ball(pa, pb);
    const V3 a1 = pa.F.col(0), a2 = pa.F.col(1), a3 = pa.F.col(2);
    const V3 b1 = pb.F.col(0);
    switch (d.type) {
      case JointType::Ball: break;
      case JointType::Hinge: rb.axis(-a3, a2.dot(b1)), rb.axis(a2, a3.dot(b1)); break;
      case JointType::Fixed: {
        // phi: the rotation vector of B's frame relative to A's (in A's
        // frame, the shorter way round); C = -phi along each axis.
        Qd rel(pa.F.transpose() * pb.F);
        if (rel.w() < 0) rel.coeffs() = -rel.coeffs();
        const V3 phi = 2 * rel.vec();
        rb.axis(a1, -phi.x()), rb.axis(a2, -phi.y()), rb.axis(a3, -phi.z());
        break;
      }
      case JointType::ConeTwist: break;
    }
    const bool soft = d.linearStiffness_Npm > 0;
    for (std::size_t r = first; r < rows.size(); ++r) {
      rows[r].soft = soft;
      rows[r].k = rows[r].angular ? d.angularStiffness_Nmprad : d.linearStiffness_Npm;
      rows[r].d = rows[r].angular ? d.angularDamping_Nmsprad : d.linearDamping_Nspm;
    }
    if (d.type == JointType::Hinge && d.enableLimit) {
      const double theta = hingeAngle(pa.F, pb.F);
      if (theta < d.lowerAngle_rad) rb.angleLimit(a1, theta - d.lowerAngle_rad, +1, rb.wa());
      if (theta > d.upperAngle_rad) rb.angleLimit(a1, d.upperAngle_rad - theta, -1, rb.wa());
    }
    if (d.type == JointType::ConeTwist) {
      const double cosLimit = std::cos(double(d.swingLimit_rad));
      if (a1.dot(b1) < cosLimit) rb.dot(a1, b1, cosLimit).limit = true;
      const double t = twistAngle(pa.F, pb.F);
      V3 n = a1 + b1;
      n = n.squaredNorm() > 1e-12 ? V3(n.normalized()) : a1;
      const V3 wm = (rb.wa() + rb.wb()) / 2;
      if (t < d.twistLower_rad) rb.angleLimit(n, t - d.twistLower_rad, +1, wm);
      if (t > d.twistUpper_rad) rb.angleLimit(n, d.twistUpper_rad - t, -1, wm);
    }
  }
  for (Row& r : rows) {
    V6 qa = V6::Zero(), qb = V6::Zero();
    if (r.a >= 0) qa << states[r.a].v, states[r.a].w;
    if (r.b >= 0) qb << states[r.b].v, states[r.b].w;
    r.cdot = r.ja.dot(qa) + r.jb.dot(qb);
  }
}

// ---- the solve ---------------------------------------------------------------------------

/// Adds J_b^T lambda of a row to its bodies' force/torque arrays.
template <typename FA>
static void scatterRow(const Row& r, double lambda, FA&& add) {
  if (r.a >= 0) add(r.a, r.ja * lambda);
  if (r.b >= 0) add(r.b, r.jb * lambda);
}

/// Numbers the rows that pred accepts and that touch a dynamic body (their
/// position in the system) and lists them per body. Returns their count.
template <typename Pred>
static int numberRows(JointSystem::Impl& im, Pred&& pred) {
  const std::vector<BodyState>& st = im.states;
  int m = 0;
  im.bodyRows.assign(st.size(), {});
  for (std::size_t r = 0; r < im.rows.size(); ++r) {
    Row& row = im.rows[r];
    row.index = -1;
    if (!pred(row)) continue;
    const bool da = row.a >= 0 && st[row.a].dynamic, db = row.b >= 0 && st[row.b].dynamic;
    if (!da && !db) continue;
    row.index = m++;
    if (da) im.bodyRows[row.a].push_back(int(r));
    if (db) im.bodyRows[row.b].push_back(int(r));
  }
  return m;
}

/// The diagonal of A^-1 from A's factor L D L^T (Takahashi's recurrence,
/// Z = A^-1 = D^-1 L^-1 + (I - L^T) Z, evaluated only on the pattern of L:
/// for a chordal pattern, as ours are, every Z_jk it needs is on it). From
/// the last column back: Z_ji = -sum_k L_ki Z_jk, Z_ii = 1 / D_i - sum_k
/// L_ki Z_ki, k over column i of L. Cost O(sum of squared column counts):
/// linear in the links for chains and trees, like the factorization.
static void inverseDiagonal(const JointSystem::Impl::Factor& f, int m, std::vector<double>& zdiag,
                            std::vector<double>& zval) {
  const auto& L = f.ldlt.matrixL().nestedExpression();  // strictly lower, column-major, rows sorted
  const auto& D = f.ldlt.vectorD();
  const int* Lp = L.outerIndexPtr();
  const int* Li = L.innerIndexPtr();
  const double* Lx = L.valuePtr();
  zdiag.assign(std::size_t(m), 0);
  zval.assign(std::size_t(Lp[m]), 0);
  auto z = [&](int j, int k) {
    if (j == k) return zdiag[std::size_t(j)];
    const int col = std::min(j, k), row = std::max(j, k);
    const int* end = Li + Lp[col + 1];
    const int* it = std::lower_bound(Li + Lp[col], end, row);
    return it != end && *it == row ? zval[std::size_t(it - Li)] : 0.0;
  };
  for (int i = m - 1; i >= 0; --i) {
    double diag = 1 / D[i];
    for (int p = Lp[i]; p < Lp[i + 1]; ++p) {
      double sum = 0;
      for (int q = Lp[i]; q < Lp[i + 1]; ++q) sum += Lx[q] * z(Li[p], Li[q]);
      zval[std::size_t(p)] = -sum;
    }
    for (int p = Lp[i]; p < Lp[i + 1]; ++p) diag -= Lx[p] * zval[std::size_t(p)];
    zdiag[std::size_t(i)] = diag;
  }
}

/// A = J W J^T over the numbered rows (lower triangle: for every body, every
/// pair of its rows), then its LDL^T factorization.
static void assembleAndFactorize(JointSystem::Impl& im, int m, JointSolveStats& stats, double compliance = 0) {
  JointSystem::Impl::Factor& f = im.factor;
  const std::vector<BodyState>& st = im.states;
  const std::vector<Row>& rows = im.rows;
  im.triplets.clear();
  for (std::size_t b = 0; b < st.size(); ++b) {
    const BodyState& s = st[b];
    const std::vector<int>& list = im.bodyRows[b];
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Row& ri = rows[list[i]];
      const V6& Ji = ri.a == int(b) ? ri.ja : ri.jb;
      V6 WJi;
      WJi << s.invMass * Ji.head<3>(), s.invI * Ji.tail<3>();
      for (std::size_t k = 0; k <= i; ++k) {
        const Row& rk = rows[list[k]];
        const V6& Jk = rk.a == int(b) ? rk.ja : rk.jb;
        im.triplets.emplace_back(std::max(ri.index, rk.index), std::min(ri.index, rk.index), Jk.dot(WJi));
      }
    }
  }
  f.A.resize(m, m);
  f.A.setFromTriplets(im.triplets.begin(), im.triplets.end());
  // The symbolic analysis (elimination tree, column counts) depends only on
  // the pattern: redone only when the rows changed (joints, active limits).
  const int* outer = f.A.outerIndexPtr();
  const int* inner = f.A.innerIndexPtr();
  const bool samePattern = f.patternOuter.size() == std::size_t(m) + 1 &&
                           std::equal(outer, outer + m + 1, f.patternOuter.begin()) &&
                           f.patternInner.size() == std::size_t(outer[m]) &&
                           std::equal(inner, inner + outer[m], f.patternInner.begin());
  if (!samePattern) {
    f.ldlt.analyzePattern(f.A);
    f.patternOuter.assign(outer, outer + m + 1);
    f.patternInner.assign(inner, inner + outer[m]);
    ++stats.patternAnalyses;
  }
  f.ldlt.factorize(f.A);
  ++stats.factorizations;
  if (f.ldlt.info() != Eigen::Success) {
    // Redundant rows (a loop of joints, two joints on one pair): a tiny
    // compliance on the diagonal makes the system definite again (the
    // diagonal is stored, so the pattern does not change).
    double trace = 0;
    for (int i = 0; i < m; ++i) trace += f.A.coeff(i, i);
    for (int i = 0; i < m; ++i) f.A.coeffRef(i, i) += 1e-9 * trace / m;
    f.ldlt.factorize(f.A);
    ++stats.factorizations;
  }
  if (compliance > 0) {
    // Compliance relative to the whole system along each row: row i's
    // diagonal grows by compliance / (A^-1)_ii, where 1 / (A^-1)_ii is the
    // inverse effective mass the row sees with every other row holding (the
    // Schur complement). For the top link of a hanging chain that is the
    // whole chain's mass, not the link's: see "Robustness" at the top.
    std::vector<double>& zdiag = im.inverseDiagonal;
    inverseDiagonal(f, m, zdiag, im.inverseValues);
    for (const Row& r : im.rows) {
      if (r.index < 0) continue;
      const int i = r.index;
      const double aii = f.A.coeff(i, i);
      const double own = compliance * aii;
      const double system = zdiag[i] > 0 && std::isfinite(zdiag[i]) ? std::min(compliance / zdiag[i], own) : own;
      f.A.coeffRef(i, i) = aii + (r.touched ? own : system);  // the diagonal is stored: same pattern
    }
    f.ldlt.factorize(f.A);
    ++stats.factorizations;
  }
  stats.nonZerosA = long(f.A.nonZeros()) - m;
  stats.nonZerosL = long(f.ldlt.matrixL().nestedExpression().nonZeros());
  // Fill-in: entries of L beyond those of A's strictly lower triangle.
  stats.fillIn = std::max(0L, stats.nonZerosL - stats.nonZerosA);
}

/// Fills the derived quantities of the states (rotation, inverse inertia,
/// applied forces Q) and clears the constraint forces.
static void deriveStates(std::vector<BodyState>& states, const JointSettings& js, const V3& gravity,
                         bool includeExternal) {
  for (BodyState& s : states) {
    s.R = s.q.toRotationMatrix();
    const M3 I = s.R * s.inertiaLocal.asDiagonal() * s.R.transpose();
    s.invI = s.dynamic ? M3(s.R * s.inertiaLocal.cwiseInverse().asDiagonal() * s.R.transpose()) : M3::Zero();
    s.Qf = s.mass * gravity;
    s.Qt = js.gyroscopic ? V3(-s.w.cross(I * s.w)) : V3::Zero();
    if (includeExternal) s.Qf += s.extForce, s.Qt += s.extTorque;
    s.Fc.setZero();
    s.Tc.setZero();
    s.Tm.setZero();
  }
}

// Hinge motors: an explicit servo torque added to Q (see the top of the
// file): tau = clamp(I_axial k_d (speed - rate), +-maxMotorTorque) about the
// hinge axis, on B (and -tau on A), I_axial = 1 / (a1.(IA^-1 + IB^-1) a1).
static void addMotorTorques(const Evaluation& ev, std::vector<BodyState>& st, const JointSettings& js) {
  for (std::size_t k = 0; k < ev.defs.size(); ++k) {
    const JointDef& d = *ev.defs[k];
    if (d.type != JointType::Hinge || !d.enableMotor) continue;
    const auto [ia, ib] = ev.bodies[k];
    BodyState* A = ia >= 0 ? &st[ia] : nullptr;
    BodyState* B = ib >= 0 ? &st[ib] : nullptr;
    const V3 a1 = poseOf(d.localAnchorA_m, d.localFrameA, A).F.col(0);
    const V3 wA = A ? A->w : V3::Zero(), wB = B ? B->w : V3::Zero();
    const double kinv = a1.dot(((A ? A->invI : M3::Zero()) + (B ? B->invI : M3::Zero())) * a1);
    if (!(kinv > 0)) continue;
    const double maxT = d.maxMotorTorque_Nm;
    const double tau = std::clamp((d.motorSpeed_radps - (wB - wA).dot(a1)) / kinv * js.damping_per_s, -maxT, maxT);
    // In Q (the rows see it; integrateFree integrates Q) and in Tm, which
    // applyConstraintForces applies with the constraint torque.
    if (A && A->dynamic) A->Qt -= tau * a1, A->Tm -= tau * a1;
    if (B && B->dynamic) B->Qt += tau * a1, B->Tm += tau * a1;
  }
}

// Computes the constraint forces (states[i].Fc, Tc) for the given states.
// Returns the joints (slot indices) that broke, with their force and torque.
static std::vector<JointBreakEvent> solveConstraints(JointSystem::Impl& im, const JointSettings& js,
                                                     const V3& gravity, bool includeExternal,
                                                     JointSolveStats& stats) {
  const Evaluation& ev = im.ev;
  std::vector<BodyState>& st = im.states;
  deriveStates(st, js, gravity, includeExternal);
  buildRows(ev.defs, ev.slots, ev.bodies, st, im.rows);
  std::vector<Row>& rows = im.rows;
  addMotorTorques(ev, st, js);
  std::vector<char> broken(ev.defs.size(), 0);  // per evaluation joint
  std::vector<JointBreakEvent> events;
  std::vector<int> jointOf(rows.size());
  {
    // rows are grouped by joint in evaluation order
    std::size_t k = 0;
    for (std::size_t r = 0; r < rows.size(); ++r) {
      while (ev.slots[k] != rows[r].joint) ++k;
      jointOf[r] = int(k);
    }
  }
  const std::vector<V3> baseQf = [&] {
    std::vector<V3> q(st.size());
    for (std::size_t i = 0; i < st.size(); ++i) q[i] = st[i].Qf;
    return q;
  }();
  const std::vector<V3> baseQt = [&] {
    std::vector<V3> q(st.size());
    for (std::size_t i = 0; i < st.size(); ++i) q[i] = st[i].Qt;
    return q;
  }();
  stats.factorizations = 0;
  for (int iter = 0; iter <= std::max(0, js.maxActiveSetIterations) + int(ev.defs.size()); ++iter) {
    // Springs (soft rows) go into Q.
    for (std::size_t i = 0; i < st.size(); ++i) st[i].Qf = baseQf[i], st[i].Qt = baseQt[i];
    for (Row& r : rows) {
      if (!r.soft || !r.active) continue;
      r.lambda = -(r.k * r.c + r.d * r.cdot);
      scatterRow(r, r.lambda, [&](int b, const V6& f) {
        st[b].Qf += f.head<3>();
        st[b].Qt += f.tail<3>();
      });
    }
    const int m = numberRows(im, [](const Row& r) { return !r.soft && r.active; });
    stats.rows = m;
    if (m > 0) {
      // rhs = -J'q' - J W Q - k_s C - k_d C'.
      im.rhs.resize(m);
      for (const Row& r : rows)
        if (r.index >= 0) im.rhs[r.index] = -r.jdq - js.stiffness_per_s2 * r.c - js.damping_per_s * r.cdot;
      for (std::size_t b = 0; b < st.size(); ++b) {
        const BodyState& s = st[b];
        V6 WQ;
        WQ << s.invMass * s.Qf, s.invI * s.Qt;
        for (int r : im.bodyRows[b]) {
          const Row& row = rows[r];
          im.rhs[row.index] -= (row.a == int(b) ? row.ja : row.jb).dot(WQ);
        }
      }
      assembleAndFactorize(im, m, stats);
      im.lambda = im.factor.ldlt.solve(im.rhs);
      for (Row& r : rows)
        if (r.index >= 0) r.lambda = im.lambda[r.index];
    }
    // Active set: drop limit rows that pull.
    bool changed = false;
    if (iter < js.maxActiveSetIterations)
      for (Row& r : rows)
        if (r.limit && r.index >= 0 && r.lambda < 0) r.active = false, changed = true;
    if (changed) continue;
    // Breakable joints.
    std::vector<V3>& force = im.jointForce;
    std::vector<V3>& torque = im.jointTorque;
    force.assign(ev.defs.size(), V3::Zero());
    torque.assign(ev.defs.size(), V3::Zero());
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const Row& row = rows[r];
      if (!row.active || (row.index < 0 && !row.soft)) continue;
      if (row.angular) torque[jointOf[r]] += row.lambda * row.ja.tail<3>();
      else force[jointOf[r]] += row.lambda * row.ja.head<3>();
    }
    bool anyBroken = false;
    for (std::size_t k = 0; k < ev.defs.size(); ++k) {
      const JointDef& d = *ev.defs[k];
      if (broken[k]) continue;
      const double f = force[k].norm(), t = torque[k].norm();
      if ((d.breakForce_N > 0 && f > d.breakForce_N) || (d.breakTorque_Nm > 0 && t > d.breakTorque_Nm)) {
        broken[k] = 1;
        anyBroken = true;
        JointBreakEvent e;
        e.id.index = ev.slots[k];
        e.a = d.bodyA;
        e.b = d.bodyB;
        e.force_N = f;
        e.torque_Nm = t;
        e.userData = d.userData;
        events.push_back(e);
      }
    }
    if (anyBroken) {
      for (std::size_t r = 0; r < rows.size(); ++r)
        if (broken[jointOf[r]]) rows[r].active = false;
      continue;
    }
    break;
  }
  // Constraint forces: soft and hard rows.
  for (const Row& r : rows) {
    if (!r.active || (r.index < 0 && !r.soft)) continue;
    scatterRow(r, r.lambda, [&](int b, const V6& f) {
      if (!st[b].dynamic) return;
      st[b].Fc += f.head<3>();
      st[b].Tc += f.tail<3>();
    });
  }
  return events;
}

// ---- the public steps ----------------------------------------------------------------------

void JointSystem::refreshLinks() {
  if (!m_orderDirty) return;
  Impl& im = *m_impl;
  std::vector<JointDef> defs;
  std::vector<std::uint32_t> ids;
  for (std::uint32_t i = 0; i < m_slots.size(); ++i)
    if (m_slots[i].alive) defs.push_back(m_slots[i].def), ids.push_back(i);
  im.order = eliminationOrder(m_world, defs, ids);
  // Jointed bodies sleep and wake as one island (World::setIslandLinks).
  m_world.setIslandLinks(connectedPairs());
  m_orderDirty = false;
}

void JointSystem::solveOrder(std::vector<std::uint32_t>& out) const {
  out.clear();
  if (!m_orderDirty) {
    for (std::uint32_t i : m_impl->order)
      if (m_slots[i].alive) out.push_back(i);
    return;
  }
  for (std::uint32_t i = 0; i < m_slots.size(); ++i)
    if (m_slots[i].alive) out.push_back(i);
}

void JointSystem::prepare() {
  Impl& im = *m_impl;
  refreshLinks();
  Evaluation& ev = im.ev;
  ev.defs.clear();
  ev.slots.clear();
  ev.generations.clear();
  ev.bodies.clear();
  for (BodyState& s : im.states)
    if (s.id.index < im.slotOf.size()) im.slotOf[s.id.index] = -1;
  im.states.clear();
  auto stateOf = [&](BodyId id) -> int {
    if (id.isNull()) return -1;
    if (id.index >= im.slotOf.size()) im.slotOf.resize(id.index + 1, -1);
    int& k = im.slotOf[id.index];
    if (k < 0) {
      k = int(im.states.size());
      im.states.push_back(stateFromWorld(m_world, id));
    }
    return k;
  };
  for (std::uint32_t slot : im.order) {
    Slot& s = m_slots[slot];
    ev.defs.push_back(&s.def);
    ev.slots.push_back(slot);
    ev.generations.push_back(s.generation);
    ev.bodies.emplace_back(stateOf(s.def.bodyA), stateOf(s.def.bodyB));
  }
}

void JointSystem::recordForces() {
  const Impl& im = *m_impl;
  for (std::size_t k = 0; k < im.ev.slots.size() && k < im.jointForce.size(); ++k) {
    Slot& s = m_slots[im.ev.slots[k]];
    if (!s.alive || s.generation != im.ev.generations[k]) continue;  // destroyed since
    s.force_N = im.jointForce[k].cast<Real>();
    s.torque_Nm = im.jointTorque[k].cast<Real>();
  }
}

void JointSystem::finishBreaks(std::vector<JointBreakEvent>& events) {
  for (JointBreakEvent& e : events) {
    if (e.id.index >= m_slots.size() || !m_slots[e.id.index].alive) continue;  // reported already
    if (e.id.generation != 0 && e.id.generation != m_slots[e.id.index].generation) continue;  // slot reused since
    e.id.generation = m_slots[e.id.index].generation;
    destroyJoint(e.id);
    m_broken.push_back(e);
  }
}

bool JointSystem::dropJointsOfDeadBodies() {
  for (std::uint32_t i = 0; i < m_slots.size(); ++i) {
    Slot& s = m_slots[i];
    if (!s.alive) continue;
    if (!m_world.isValid(s.def.bodyA) || (!s.def.bodyB.isNull() && !m_world.isValid(s.def.bodyB))) {
      JointBreakEvent e{JointId{i, s.generation}, s.def.bodyA, s.def.bodyB, 0, 0, s.def.userData};
      destroyJoint(e.id);
      m_broken.push_back(e);
    }
  }
  return m_jointCount > 0;
}

void JointSystem::wakeJointedSleepers() {
  // Sleeping bodies: a sleeping body jointed to a body that moves faster
  // than the sleep thresholds is woken (the World's islands know only
  // contacts); otherwise it is held as fixed for this step and gets no force.
  const WorldSettings& ws = m_world.settings();
  auto fast = [&](const Body& b) {
    return b.isDynamic() && b.awake &&
           (b.linearVelocity_mps.norm() > ws.sleepLinearSpeed_mps ||
            b.angularVelocity_radps.norm() > ws.sleepAngularSpeed_radps);
  };
  for (const Slot& s : m_slots) {
    if (!s.alive || s.def.bodyB.isNull()) continue;
    const Body& a = m_world.body(s.def.bodyA);
    const Body& b = m_world.body(s.def.bodyB);
    if (!a.awake && a.isDynamic() && fast(b)) m_world.wake(s.def.bodyA);
    if (!b.awake && b.isDynamic() && fast(a)) m_world.wake(s.def.bodyB);
  }
}

void JointSystem::step(Real dt_s) {
  // The projection runs at the start of the step rather than at the end of
  // the previous one: for free chains that is the same cycle, but with
  // contacts the World's contact solver then has the last word on the
  // velocities (projecting after it pushed resting parts back into the
  // ground: a rag-doll never fell asleep, measured 0.3 m/s forever).
  beforeWorldStep();
  m_world.step(dt_s);
  if (m_impulse) collectImpulseResults();
  else collectLagrangeResults();
  measureError();
}

void JointSystem::beforeWorldStep() {
  // Both formulations solve inside World::step (ImpulseJoints,
  // LagrangeSubsteps); here: the results of the last step, dead bodies,
  // sleepers, the joint order.
  m_broken.clear();
  if (m_impulse) collectImpulseResults();
  else collectLagrangeResults();
  if (dropJointsOfDeadBodies()) wakeJointedSleepers();
  const bool fresh = m_orderDirty || !allJointedBodiesKnown();
  refreshLinks();
  if (!m_impulse && m_settings.postStabilize && fresh) postStabilize();
  measureError();
}

bool JointSystem::allJointedBodiesKnown() const {
  // Known: solved in the last World step (a valid memo, see substepSolve).
  const Impl& im = *m_impl;
  auto known = [&](BodyId id) {
    if (id.isNull() || !m_world.isValid(id)) return true;
    const Body& b = m_world.body(id);
    if (!b.isDynamic() || !b.awake) return true;
    if (id.index >= im.memo.size()) return false;
    const Impl::Memo& memo = im.memo[id.index];
    return memo.generation == id.generation && memo.serial >= im.serial;
  };
  for (const Slot& s : m_slots)
    if (s.alive && (!known(s.def.bodyA) || !known(s.def.bodyB))) return false;
  return true;
}

void JointSystem::collectLagrangeResults() {
  Impl& im = *m_impl;
  if (!im.resultsPending) return;
  im.resultsPending = false;
  recordForces();
  finishBreaks(im.pendingBreaks);
  im.pendingBreaks.clear();
}

// ---- formulation A inside World::step -------------------------------------------------

void JointSystem::substepPrepare(double h) {
  const auto t0 = std::chrono::steady_clock::now();
  Impl& im = *m_impl;
  im.inStep = false;
  m_stats = JointSolveStats{};
  if (m_jointCount == 0 || !dropJointsOfDeadBodies()) return;
  prepare();  // joints (in elimination order) and their bodies, as of now
  if (im.ev.defs.empty() || !(h > 0)) return;
  im.h = h;
  ++im.serial;
  im.inStep = true;
  im.resultsPending = true;
  im.pendingBreaks.clear();
  im.vk.resize(im.states.size());
  im.wk.resize(im.states.size());
  if (im.memo.size() < im.slotOf.size()) im.memo.resize(im.slotOf.size());
  m_stats.solveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// How long an assembly keeps the compliance of contact after a contact
/// last moved one of its bodies (s). One step (the first version) let a
/// rag-doll tumbling down stairs switch at every bounce: 10.5 cm of joint
/// error and the doll not at rest; 1 s: 4.7 cm, at rest (ragdoll_stairs).
constexpr double kContactMemory_s = 1.0;

/// Marks the rows of every jointed assembly (bodies connected by joints)
/// one of whose bodies a contact moved in the last kContactMemory_s (see
/// JointSettings::compliance). Returns whether a solved row became touched.
static bool markTouchedRows(JointSystem::Impl& im) {
  const std::vector<BodyState>& st = im.states;
  std::vector<int>& root = im.assembly;
  root.resize(st.size());
  for (std::size_t i = 0; i < st.size(); ++i) root[i] = int(i);
  auto find = [&](int i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  for (const std::pair<int, int>& ab : im.ev.bodies)
    if (ab.first >= 0 && ab.second >= 0 && st[ab.first].dynamic && st[ab.second].dynamic)
      root[find(ab.first)] = find(ab.second);
  std::vector<char>& touched = im.assemblyTouched;
  touched.assign(st.size(), 0);
  for (std::size_t i = 0; i < st.size(); ++i) {
    if (!st[i].dynamic) continue;
    const JointSystem::Impl::Memo& memo = im.memo[st[i].id.index];
    if (memo.generation == st[i].id.generation && im.time_s - memo.contactTime_s <= kContactMemory_s)
      touched[find(int(i))] = 1;
  }
  bool newly = false;
  for (Row& r : im.rows) {
    const bool t = (r.a >= 0 && st[r.a].dynamic && touched[find(r.a)]) ||
                   (r.b >= 0 && st[r.b].dynamic && touched[find(r.b)]);
    if (t && !r.touched && r.index >= 0) newly = true;
    r.touched = t;
  }
  return newly;
}

/// J q' of one row for the velocities v, w (per state; -1 = the world, at rest).
static double rowVelocity(const Row& r, const std::vector<V3>& v, const std::vector<V3>& w) {
  double c = 0;
  if (r.a >= 0) c += r.ja.head<3>().dot(v[r.a]) + r.ja.tail<3>().dot(w[r.a]);
  if (r.b >= 0) c += r.jb.head<3>().dot(v[r.b]) + r.jb.tail<3>().dot(w[r.b]);
  return c;
}

void JointSystem::substepSolve(SolverVelocity* vel, const Body* bodies) {
  Impl& im = *m_impl;
  if (!im.inStep) return;
  const auto t0 = std::chrono::steady_clock::now();
  const double h = im.h;
  im.time_s += h;
  const V3 g = wide3(m_world.settings().gravity_mps2);
  std::vector<BodyState>& st = im.states;
  // The state of the substep: poses as integrated so far; q' = the velocity
  // the joints left at their last update (the memo), so that everything that
  // changed the velocities since (the free step's gravity, forces and
  // gyroscopic term, the contacts' impulses, scripts) is the known force Q,
  // not a velocity the joints have to live with. See "Time stepping".
  for (std::size_t i = 0; i < st.size(); ++i) {
    BodyState& s = st[i];
    const Body& b = bodies[s.id.index];
    s.x = wide3(b.position_m);
    s.q = b.orientation.cast<double>().normalized();
    const bool moves = b.moves();
    im.vk[i] = moves ? V3(narrow(vel[s.id.index].linear).cast<double>()) : V3::Zero();
    im.wk[i] = moves ? V3(narrow(vel[s.id.index].angular).cast<double>()) : V3::Zero();
    s.v = im.vk[i];
    s.w = im.wk[i];
    if (!s.dynamic) continue;
    const Impl::Memo& memo = im.memo[s.id.index];
    if (memo.generation == s.id.generation && memo.serial + 1 >= im.serial) {
      s.v = memo.v;
      s.w = memo.w;
    } else {
      // Not seen last step (new, just woken): the velocity before this
      // substep's free step, gravity and the applied force and torque taken out.
      s.v = im.vk[i] - h * (g + s.invMass * wide3(b.force_N));
      s.w = im.wk[i] - h * (b.invInertiaWorld.cast<double>() * wide3(b.torque_Nm));
    }
  }
  deriveStates(st, m_settings, V3::Zero(), false);  // R, W at the substep's poses
  buildRows(im.ev.defs, im.ev.slots, im.ev.bodies, st, im.rows);  // C, J, J'q', C' = J q'
  addMotorTorques(im.ev, st, m_settings);
  // The parts of Q the World does not apply: springs (soft rows, lambda =
  // -k C - c C') and hinge motors, as impulses over the substep.
  auto kick = [&](int b, const V6& p) {
    if (!st[b].dynamic) return;
    im.vk[b] += st[b].invMass * p.head<3>();
    im.wk[b] += st[b].invI * p.tail<3>();
  };
  for (Row& r : im.rows)
    if (r.soft) {
      r.lambda = -(r.k * r.c + r.d * r.cdot);
      scatterRow(r, h * r.lambda, kick);
    }
  for (std::size_t i = 0; i < st.size(); ++i)
    if (st[i].dynamic) im.wk[i] += h * (st[i].invI * st[i].Tm);
  // Hard rows. Baumgarte's C'' = -k_s C - k_d C' over the substep, with C
  // and C' at its end (implicit), asks for the row's target
  //   J v_end = (C' - h (J'q' + k_s C)) / (1 + h k_d + h^2 k_s),
  // and J W J^T (h lambda) = target - J v_k is the paper's equation times h
  // (J v_k - C' = h J W Q). A limit row stops the approach inelastically
  // (C' < 0 is not carried on) and pushes out with k_s.
  const double ks = m_settings.stiffness_per_s2, kd = m_settings.damping_per_s;
  for (Row& r : im.rows) {
    const double carried = r.limit ? std::max(r.cdot, 0.0) : r.cdot;
    r.target = (carried - h * (r.jdq + ks * r.c)) / (1 + h * kd + h * h * ks);
    if (!r.soft) r.lambda = 0;
  }
  markTouchedRows(im);
  const int maxIter = std::max(0, m_settings.maxActiveSetIterations);
  for (int iter = 0;; ++iter) {
    const int m = numberRows(im, [](const Row& r) { return !r.soft && r.active; });
    m_stats.rows = m;
    if (m == 0) break;
    assembleAndFactorize(im, m, m_stats, std::max(0.0, m_settings.compliance));
    im.rhs.resize(m);
    for (const Row& r : im.rows)
      if (r.index >= 0) im.rhs[r.index] = r.target - rowVelocity(r, im.vk, im.wk);
    im.lambda = im.factor.ldlt.solve(im.rhs);  // impulses h lambda (N s, N m s)
    // Active set: a limit row that would pull leaves and the rest is solved again.
    bool changed = false;
    if (iter < maxIter)
      for (Row& r : im.rows)
        if (r.limit && r.index >= 0 && im.lambda[r.index] < 0) r.active = false, changed = true;
    if (!changed) break;
  }
  for (Row& r : im.rows)
    if (r.index >= 0) {
      r.lambda = im.lambda[r.index] / h;
      scatterRow(r, im.lambda[r.index], kick);
    }
  for (std::size_t i = 0; i < st.size(); ++i) {
    const BodyState& s = st[i];
    if (!s.dynamic) continue;
    vel[s.id.index].linear = wide(Vec3(im.vk[i].cast<Real>()));
    vel[s.id.index].angular = wide(Vec3(im.wk[i].cast<Real>()));
    Impl::Memo& mem = im.memo[s.id.index];
    mem = Impl::Memo{s.id.generation, im.serial, im.vk[i], im.wk[i],
                     mem.generation == s.id.generation ? mem.contactTime_s : -std::numeric_limits<double>::infinity()};
  }
  m_stats.solveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double JointSystem::substepProject(SolverVelocity* vel, bool useBias) {
  Impl& im = *m_impl;
  if (!im.inStep || m_stats.rows == 0) return 0;
  const auto t0 = std::chrono::steady_clock::now();
  const double h = im.h;
  std::vector<BodyState>& st = im.states;
  // Before every contact sweep and after the last one (beforeIntegrate):
  // the contacts changed the velocities since the joints' solve; with their
  // impulses in Q, the multipliers change by J W J^T dmu = target - J v (the
  // same factorization), and contacts and joints take turns (block
  // Gauss-Seidel), the joints last before the positions move. See
  // "Robustness" at the top of the file.
  // A body whose velocity is not what the joints wrote last was moved by a
  // contact sweep since.
  bool touchedNow = false;
  for (std::size_t i = 0; i < st.size(); ++i)
    if (st[i].dynamic) {
      const V3 v = narrow(vel[st[i].id.index].linear).cast<double>();
      const V3 w = narrow(vel[st[i].id.index].angular).cast<double>();
      if (v != V3(im.vk[i].cast<Real>().cast<double>()) || w != V3(im.wk[i].cast<Real>().cast<double>())) {
        Impl::Memo& memo = im.memo[st[i].id.index];
        if (memo.contactTime_s != im.time_s) touchedNow = true;
        memo.contactTime_s = im.time_s;
      }
      im.vk[i] = v;
      im.wk[i] = w;
    }
  const int m = m_stats.rows;
  // An assembly a contact touched for the first time (a doll landing) gets
  // its compliance at once, not in the next substep: the impact is where
  // joints and contacts fight hardest.
  if (touchedNow && m_settings.compliance > 0 && markTouchedRows(im))
    assembleAndFactorize(im, m, m_stats, m_settings.compliance);
  im.rhs.resize(m);
  for (const Row& r : im.rows)
    if (r.index >= 0) {
      // Relax phase: no position feedback, as for the contacts (the rows'
      // Baumgarte velocity moved the positions already and must not stay in
      // the velocity); a limit row still stops an approach.
      const double target = useBias ? r.target : r.limit ? std::max(r.target, 0.0) : 0.0;
      im.rhs[r.index] = target - rowVelocity(r, im.vk, im.wk);
    }
  const Eigen::VectorXd& dmu = im.lambda = im.factor.ldlt.solve(im.rhs);
  double changed2 = 0, total2 = 0;
  std::vector<V3>& dv = im.dv;
  std::vector<V3>& dw = im.dw;
  std::vector<double>& d = im.rowImpulse;
  dv.assign(st.size(), V3::Zero());
  dw.assign(st.size(), V3::Zero());
  d.assign(im.rows.size(), 0);
  auto kick = [&](int b, const V6& p) {
    if (!st[b].dynamic) return;
    dv[b] += st[b].invMass * p.head<3>();
    dw[b] += st[b].invI * p.tail<3>();
  };
  for (std::size_t k = 0; k < im.rows.size(); ++k) {
    const Row& r = im.rows[k];
    if (r.index < 0) continue;
    // A limit row may only push: its total impulse stays >= 0.
    d[k] = r.limit ? std::max(dmu[r.index], -h * r.lambda) : dmu[r.index];
    scatterRow(r, d[k], kick);
  }
  double size2 = 0;
  for (std::size_t i = 0; i < st.size(); ++i)
    if (st[i].dynamic) size2 += dv[i].squaredNorm() + dw[i].squaredNorm();
  if (!std::isfinite(size2)) {  // a degenerate system: leave this turn to the contacts
    m_stats.solveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return 0;
  }
  for (std::size_t k = 0; k < im.rows.size(); ++k) {
    Row& r = im.rows[k];
    if (r.index < 0) continue;
    r.lambda += d[k] / h;
    changed2 += d[k] * d[k];
    total2 += h * h * r.lambda * r.lambda;
  }
  for (std::size_t i = 0; i < st.size(); ++i) {
    const BodyState& s = st[i];
    if (!s.dynamic) continue;
    im.vk[i] += dv[i];
    im.wk[i] += dw[i];
    vel[s.id.index].linear = wide(Vec3(im.vk[i].cast<Real>()));
    vel[s.id.index].angular = wide(Vec3(im.wk[i].cast<Real>()));
    Impl::Memo& mem = im.memo[s.id.index];
    mem = Impl::Memo{s.id.generation, im.serial, im.vk[i], im.wk[i],
                     mem.generation == s.id.generation ? mem.contactTime_s : -std::numeric_limits<double>::infinity()};
  }
  m_stats.solveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return total2 > 0 ? changed2 / total2 : 0;
}

void JointSystem::substepFinish() {
  Impl& im = *m_impl;
  if (!im.inStep) return;
  im.inStep = false;
  const auto t0 = std::chrono::steady_clock::now();
  const Evaluation& ev = im.ev;
  // The constraint force of the last substep, per joint (on body A).
  im.jointForce.assign(ev.defs.size(), V3::Zero());
  im.jointTorque.assign(ev.defs.size(), V3::Zero());
  std::size_t k = 0;
  for (const Row& r : im.rows) {
    while (k < ev.slots.size() && ev.slots[k] != r.joint) ++k;  // rows are grouped by joint in evaluation order
    if (k == ev.slots.size()) break;
    if (!r.active || (r.index < 0 && !r.soft)) continue;
    if (r.angular) im.jointTorque[k] += r.lambda * r.ja.tail<3>();
    else im.jointForce[k] += r.lambda * r.ja.head<3>();
  }
  for (std::size_t j = 0; j < ev.defs.size(); ++j) {
    const JointDef& d = *ev.defs[j];
    const double f = im.jointForce[j].norm(), t = im.jointTorque[j].norm();
    if ((d.breakForce_N > 0 && f > d.breakForce_N) || (d.breakTorque_Nm > 0 && t > d.breakTorque_Nm))
      im.pendingBreaks.push_back(
          JointBreakEvent{JointId{ev.slots[j], ev.generations[j]}, d.bodyA, d.bodyB, f, t, d.userData});
  }
  m_stats.solveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void JointSystem::collectImpulseResults() {
  const std::vector<ImpulseJoints::Output>& out = m_impulse->outputs();
  std::vector<JointBreakEvent> events;
  for (std::uint32_t i = 0; i < m_slots.size() && i < out.size(); ++i) {
    Slot& s = m_slots[i];
    if (!s.alive || out[i].generation != s.generation) continue;
    // Stored as the force on A, like formulation A's lastForce_N.
    s.force_N = -out[i].force_N;
    s.torque_Nm = -out[i].torque_Nm;
    if (out[i].broken) {
      JointBreakEvent e{JointId{i, s.generation}, s.def.bodyA, s.def.bodyB, double(out[i].force_N.norm()),
                        double(out[i].torque_Nm.norm()), s.def.userData};
      events.push_back(e);
    }
  }
  m_impulse->clearBroken();
  finishBreaks(events);
}

void JointSystem::postStabilize() {
  if (m_jointCount == 0 || !dropJointsOfDeadBodies()) return;
  prepare();
  Impl& im = *m_impl;
  deriveStates(im.states, m_settings, V3::Zero(), false);
  buildRows(im.ev.defs, im.ev.slots, im.ev.bodies, im.states, im.rows);
  // Equality rows, and the limit rows that are violated (buildRows adds no
  // others): those act as inelastic stops, J dv = -min(C', 0), dC = -C; a
  // stop whose multiplier comes out negative (it would pull) is dropped and
  // the projection solved again. Springs are soft: not projected.
  JointSolveStats stats;
  Eigen::VectorXd mu, nu;
  for (int pass = 0; pass < 3; ++pass) {
    const int m = numberRows(im, [](const Row& r) { return !r.soft && r.active; });
    if (m == 0) return;
    assembleAndFactorize(im, m, stats);
    Eigen::VectorXd cdot(m), c(m);
    for (const Row& r : im.rows)
      if (r.index >= 0) cdot[r.index] = r.limit ? -std::min(r.cdot, 0.0) : -r.cdot, c[r.index] = -r.c;
    mu = im.factor.ldlt.solve(cdot);
    nu = im.factor.ldlt.solve(c);
    if (pass == 2) break;
    bool changed = false;
    for (Row& r : im.rows)
      if (r.limit && r.index >= 0 && (mu[r.index] < 0 || nu[r.index] < 0)) r.active = false, changed = true;
    if (!changed) break;
  }
  // dq = W J^T mu (velocities), W J^T nu (positions): the smallest changes in
  // the mass metric that make J v = 0 and, to first order, C = 0.
  std::vector<V6> dv(im.states.size(), V6::Zero()), dx(im.states.size(), V6::Zero());
  for (const Row& r : im.rows) {
    if (r.index < 0) continue;
    if (r.a >= 0) dv[r.a] += r.ja * mu[r.index], dx[r.a] += r.ja * nu[r.index];
    if (r.b >= 0) dv[r.b] += r.jb * mu[r.index], dx[r.b] += r.jb * nu[r.index];
  }
  for (std::size_t i = 0; i < im.states.size(); ++i) {
    const BodyState& s = im.states[i];
    if (!s.dynamic) continue;
    const V3 v = s.v + s.invMass * dv[i].head<3>(), w = s.w + s.invI * dv[i].tail<3>();
    const V3 x = s.x + s.invMass * dx[i].head<3>(), th = s.invI * dx[i].tail<3>();
    Qd q = s.q;
    q.coeffs() += 0.5 * (Qd(0, th.x(), th.y(), th.z()) * s.q).coeffs();
    // wake = false: only awake bodies are projected, and the projection
    // must not restart their sleep timers (it runs every step).
    if (m_settings.projectPositions) {
      m_world.setPosition(s.id, x.cast<Real>(), false);
      m_world.setOrientation(s.id, q.normalized().cast<Real>(), false);
    }
    m_world.setLinearVelocity(s.id, v.cast<Real>(), false);
    m_world.setAngularVelocity(s.id, w.cast<Real>(), false);
    // The projection is the joints' own update: the next substep solve
    // starts from it (the memo) rather than resisting it as a force.
    if (s.id.index >= im.memo.size()) im.memo.resize(s.id.index + 1);
    im.memo[s.id.index] = Impl::Memo{s.id.generation, im.serial, V3(v.cast<Real>().cast<double>()),
                                     V3(w.cast<Real>().cast<double>())};
  }
}

namespace {

struct Deriv {
  V3 dx = V3::Zero(), dv = V3::Zero(), dw = V3::Zero();
  Eigen::Vector4d dq = Eigen::Vector4d::Zero();
};

void advance(const std::vector<BodyState>& y, const std::vector<Deriv>& k, double h, std::vector<BodyState>& out) {
  out = y;
  for (std::size_t i = 0; i < y.size(); ++i) {
    if (!y[i].dynamic) continue;
    out[i].x += h * k[i].dx;
    out[i].v += h * k[i].dv;
    out[i].w += h * k[i].dw;
    out[i].q.coeffs() += h * k[i].dq;
    out[i].q.normalize();
  }
}

}  // namespace

void JointSystem::integrateFree(JointIntegrator method, double h) {
  m_broken.clear();
  if (!(h > 0) || !std::isfinite(h) || !dropJointsOfDeadBodies()) return;
  prepare();
  Impl& im = *m_impl;
  const V3 g = wide3(m_world.settings().gravity_mps2);
  std::vector<JointBreakEvent> events;
  // f(y): velocities and accelerations with the constraint forces solved at y.
  auto f = [&](const std::vector<BodyState>& y) {
    im.states = y;
    auto ev = solveConstraints(im, m_settings, g, false, m_stats);
    events.insert(events.end(), ev.begin(), ev.end());
    std::vector<Deriv> d(y.size());
    for (std::size_t i = 0; i < y.size(); ++i) {
      const BodyState& s = im.states[i];
      if (!s.dynamic) continue;
      d[i].dx = s.v;
      d[i].dv = s.invMass * (s.Qf + s.Fc);
      d[i].dw = s.invI * (s.Qt + s.Tc);
      const Qd wq(0, s.w.x(), s.w.y(), s.w.z());
      d[i].dq = 0.5 * (wq * s.q).coeffs();
    }
    return d;
  };
  const std::vector<BodyState> y0 = im.states;
  std::vector<BodyState> y1, tmp;
  switch (method) {
    case JointIntegrator::ExplicitEuler: advance(y0, f(y0), h, y1); break;
    case JointIntegrator::Trapezoid: {
      const std::vector<Deriv> k1 = f(y0);
      advance(y0, k1, h, tmp);
      std::vector<Deriv> k2 = f(tmp);
      for (std::size_t i = 0; i < k2.size(); ++i) {
        k2[i].dx = (k1[i].dx + k2[i].dx) / 2;
        k2[i].dv = (k1[i].dv + k2[i].dv) / 2;
        k2[i].dw = (k1[i].dw + k2[i].dw) / 2;
        k2[i].dq = (k1[i].dq + k2[i].dq) / 2;
      }
      advance(y0, k2, h, y1);
      break;
    }
    case JointIntegrator::SemiImplicitEuler: {
      std::vector<Deriv> k = f(y0);
      y1 = y0;
      for (std::size_t i = 0; i < y0.size(); ++i) {
        if (!y0[i].dynamic) continue;
        y1[i].v += h * k[i].dv;
        y1[i].w += h * k[i].dw;
        y1[i].x += h * y1[i].v;
        const Qd wq(0, y1[i].w.x(), y1[i].w.y(), y1[i].w.z());
        y1[i].q.coeffs() += 0.5 * h * (wq * y0[i].q).coeffs();
        y1[i].q.normalize();
      }
      break;
    }
    case JointIntegrator::Rk4: {
      const std::vector<Deriv> k1 = f(y0);
      advance(y0, k1, h / 2, tmp);
      const std::vector<Deriv> k2 = f(tmp);
      advance(y0, k2, h / 2, tmp);
      const std::vector<Deriv> k3 = f(tmp);
      advance(y0, k3, h, tmp);
      std::vector<Deriv> k4 = f(tmp);
      for (std::size_t i = 0; i < k4.size(); ++i) {
        k4[i].dx = (k1[i].dx + 2 * k2[i].dx + 2 * k3[i].dx + k4[i].dx) / 6;
        k4[i].dv = (k1[i].dv + 2 * k2[i].dv + 2 * k3[i].dv + k4[i].dv) / 6;
        k4[i].dw = (k1[i].dw + 2 * k2[i].dw + 2 * k3[i].dw + k4[i].dw) / 6;
        k4[i].dq = (k1[i].dq + 2 * k2[i].dq + 2 * k3[i].dq + k4[i].dq) / 6;
      }
      advance(y0, k4, h, y1);
      break;
    }
  }
  recordForces();  // the last stage's forces
  for (const BodyState& s : y1) {
    if (!s.dynamic) continue;
    m_world.setPosition(s.id, s.x.cast<Real>());
    m_world.setOrientation(s.id, s.q.cast<Real>());
    m_world.setLinearVelocity(s.id, s.v.cast<Real>());
    m_world.setAngularVelocity(s.id, s.w.cast<Real>());
  }
  finishBreaks(events);
  measureError();
}

}  // namespace tumble::physics
