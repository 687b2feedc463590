#pragma once
// JointSystem: joints, solved by Lagrange multipliers (the `lagrange` joint
// solver, after Baraff 1996) or by impulses (the `impulse` joint solver).
// Both run inside the World's substeps through its ConstraintSolver hook.
// joint_system.cpp lists which file holds which part; the derivations and
// the design choices are at the top of lagrange_solver.cpp,
// lagrange_substeps.cpp and impulse_solver.cpp.
//
// Use:
//   JointSystem joints(world);
//   joints.createJoint(makeJointDef(world, JointType::Hinge, a, b, anchor, axis));
//   each frame: joints.step(dt)   // = beforeWorldStep(); world.step(dt); collect forces, breaks, errors
//
// The Lagrange solver solves J W J^T lambda = -J' q' - J W Q - k_s C - k_d C'
// once per World substep, at the substep's state, with everything else that
// changed the velocities since the joints' last solve (gravity, applied
// forces, the integrator's free motion, the contacts) as the known Q; it
// then re-projects the joint velocities between the contact solver's sweeps,
// so joints and contacts settle together (lagrange_substeps.cpp, "Time stepping").
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "physics/joints/joint.h"
#include "physics/world.h"

namespace tumble::physics {

/// Which solver solves the joints (JointSettings::solver; the scenario's
/// physics.joint_solver).
enum class JointSolverKind {
  /// "lagrange": Lagrange multipliers (Baraff), one sparse LDL^T
  /// factorization per World substep, re-used between the contact solver's
  /// sweeps (lagrange_solver.cpp, lagrange_substeps.cpp).
  Lagrange,
  /// "impulse": velocity-level impulses solved with the contacts in the
  /// World's substep loop (sequential impulses, soft constraints, warm
  /// starting; impulse_solver.cpp), through World::setConstraintSolver.
  Impulse,
};
const char* jointSolverName(JointSolverKind kind);
/// "lagrange" or "impulse"; false for anything else.
bool parseJointSolver(const std::string& text, JointSolverKind* out);

struct JointSettings {
  /// The impulse solver by default. Measured on every base scene with
  /// joints under both (`tumble run base:SCENE --set physics.joint_solver=...
  /// --report`, error.joint_error_max_m and the median step), 2026-11-28:
  /// the impulse solver costs 1.6 to 10 times less CPU in all seven and
  /// holds the joints closer in three (ragdoll_stairs 1.25 cm against 1.38,
  /// crash_test 1.9 against 2.3, at 20 m/s 3.25 against 3.29); the Lagrange
  /// solver in four (the chain 0.29 mm against 0.70, the rag-doll pile 2.0
  /// mm against 1.6 cm, ragdoll_hit 1.2 against 2.6 cm, at 16 m/s 3.9
  /// against 7.8, where the impulse solver fails "joints hold"), and keeps
  /// long hanging chains far tighter (1000 links: 1.1 mm against 6.6 cm).
  /// README "Joints and rag-dolls" has the table and why the cost decides.
  JointSolverKind solver = JointSolverKind::Impulse;
  /// Impulse solver: stiffness (Hz) and damping ratio of the soft position
  /// correction of the hard rows (Box2D v3 uses 60 Hz, 2; we use 120 Hz,
  /// measured in impulse_solver.cpp), capped at a quarter of the substep
  /// rate. Springs (JointDef stiffness) use their own k and c instead.
  double impulseHertz = 120;
  double impulseDampingRatio = 2;
  /// Baumgarte feedback C'' = -k_s C - k_d C' against drift: position gain
  /// k_s (1/s^2) and velocity gain k_d (1/s). Critically damped at
  /// k_d = 2 sqrt(k_s). Defaults measured for a 60 Hz step: see the
  /// stability table at the top of free_integration.cpp (larger gains correct
  /// drift faster but need a smaller dt). In the World's substeps the
  /// feedback is discretized implicitly (lagrange_substeps.cpp, "Time stepping").
  double stiffness_per_s2 = 400;
  double damping_per_s = 40;
  /// Gyroscopic term -w x (I w) in Q (the applied generalized force) of
  /// integrateFree; in the World's substeps the change of w from the World's
  /// torque-free turn (applied at the next substep's start, world_step.cpp)
  /// is part of the known Q.
  bool gyroscopic = true;
  /// Solves per call when limit rows enter or leave the active set, and when
  /// joints break (each re-solve is one sparse factorization).
  int maxActiveSetIterations = 4;
  /// Lagrange, in the World's substeps: compliance of the hard rows
  /// (dimensionless fraction; 0 = rigid). Bounds the impulses when contacts
  /// and joints ask for things that cannot both hold (a limb pinned in a
  /// pile): rigid, the two raise each other without limit. Rows of an
  /// assembly (bodies connected by joints) that a contact moved in the last
  /// second get this fraction of their own J W J^T diagonal; all others this
  /// fraction of the whole system's inverse effective mass along the row,
  /// 1 / (J W J^T)^-1_ii, so a long hanging chain does not sag
  /// (tumble_bench_joints, 10 / 100 / 1000 links: 12 um / 49 um / 1.1 mm;
  /// own diagonal everywhere: 43 um / 7.7 mm / 13 cm). See "Robustness" at
  /// the top of lagrange_substeps.cpp.
  double compliance = 0.01;
  /// Lagrange: when a joint was created or removed, or a jointed body is new
  /// to the solver (created, woken), beforeWorldStep projects the velocities
  /// and positions back onto the joints first: v += W J^T mu with
  /// J W J^T mu = -J v, x += W J^T nu with J W J^T nu = -C (post-
  /// stabilization, Cline and Pai 2003; the same sparse matrix). A link
  /// added at rest below a swinging chain, or velocities set before the
  /// first step, start consistent (measured: the added link's joint opened
  /// 13.7 cm without, 8 mm with). Not at every step: with the contacts
  /// pushing back into the projected parts a rag-doll's head jittered on the
  /// stairs. Limit rows that are violated take part as inelastic stops.
  /// integrateFree never projects (it is the paper's scheme as published).
  bool postStabilize = true;
  /// Whether that projection also moves positions (else velocities only;
  /// the scenario host uses velocities only, so a new joint between bodies
  /// lying on the ground does not push them into it).
  bool projectPositions = true;
  /// Cost cap of the Lagrange solver, per solved row: one sparse
  /// factorization of J W J^T may take at most this many multiply-adds
  /// (JointSolveStats::factorWork) per row, so the solve's cost grows
  /// linearly with the joints. Measured (per row): chains 26, the base
  /// rag-doll scenes 46-72; but a body carrying k ball joints couples all 3k
  /// rows (about 2.8 k^2 per row: 10 joints 257, 20 joints 1112, 50 joints
  /// 7277, 117 ms a step here), and a lattice of loops fills the factor in
  /// (5 x 5 bodies 1248, 10 x 10 23 000: 1.5 s a step). Past the cap the
  /// impulse solver (linear in the rows) solves the joints until the joint
  /// set changes, and JointSystem::stepsOverCostCap() counts those steps.
  double lagrangeMaxFactorWorkPerRow = 500;
};

/// Reported once, in the step in which a breakable joint broke.
struct JointBreakEvent {
  JointId id;
  BodyId a, b;  ///< b null: the joint held a to the world
  double force_N = 0;    ///< constraint force on the anchor that broke it
  double torque_Nm = 0;  ///< constraint torque of the angular rows
  std::uint64_t userData = 0;
};

/// Figures of the last sparse solve (for the scaling measurements).
struct JointSolveStats {
  int rows = 0;            ///< size of J W J^T (active rows)
  long nonZerosA = 0;      ///< stored non-zeros of the lower triangle of J W J^T
  long nonZerosL = 0;      ///< non-zeros of the factor L (strictly lower part)
  long fillIn = 0;         ///< entries of L where A's lower triangle had none (0 for trees)
  int factorizations = 0;  ///< sparse factorizations in the last World step (or integrateFree call)
  int patternAnalyses = 0; ///< symbolic analyses among them (only when the sparsity pattern changed)
  /// Multiply-adds of one factorization, about (sum over L's columns of
  /// (entries + 1)^2); when over the cost cap before the symbolic analysis,
  /// the lower bound that tripped it (A's entries).
  double factorWork = 0;
  double solveMs = 0;      ///< wall time of the Lagrange solver in the last step: gather, assemble, factorize, solve, project (ms)
};

/// Integration of the joint-only mode (integrateFree): the rigid-body state
/// (x, q, v, w) of the jointed bodies, no contacts.
enum class JointIntegrator {
  ExplicitEuler,      ///< y += h f(y)
  Trapezoid,          ///< explicit trapezoid (Heun): y += h/2 (f(y) + f(y + h f(y)))
  SemiImplicitEuler,  ///< v += h a(y); x += h v (the World's scheme)
  Rk4,                ///< classical Runge-Kutta
};

const char* jointIntegratorName(JointIntegrator m);

class ImpulseJoints;
class ConstraintSolver;
struct SolverVelocity;
struct Body;

class JointSystem {
 public:
  explicit JointSystem(World& world, const JointSettings& settings = {});
  ~JointSystem();
  JointSystem(const JointSystem&) = delete;
  JointSystem& operator=(const JointSystem&) = delete;

  /// Changing settings().solver directly has no effect: use setSolver.
  JointSettings& settings() { return m_settings; }
  const JointSettings& settings() const { return m_settings; }
  /// Switches the joint solver (also while running; the impulse solver
  /// registers itself with World::setConstraintSolver, so one JointSystem
  /// per World). Warm-start impulses start from zero after a switch.
  void setSolver(JointSolverKind kind);
  /// The solver asked for (setSolver). The one running differs only past
  /// the Lagrange cost cap: see runningSolver.
  JointSolverKind solver() const { return m_settings.solver; }
  /// The solver that solves the joints now: the impulse solver stands in for
  /// the Lagrange solver while its factorization is over
  /// JointSettings::lagrangeMaxFactorWorkPerRow.
  JointSolverKind runningSolver() const { return m_impulse ? JointSolverKind::Impulse : JointSolverKind::Lagrange; }
  /// Steps the impulse solver stood in for the Lagrange solver (cost cap),
  /// and the factorization work per row that sent it there last.
  long stepsOverCostCap() const { return m_stepsOverCostCap; }
  double overCostCapWorkPerRow() const { return m_overCostCapWorkPerRow; }

  /// Creates a joint; refuses bad definitions with a message naming the field.
  Result<JointId> createJoint(const JointDef& def);
  /// Removes a joint; false for a stale or null handle.
  bool destroyJoint(JointId id);
  bool isValid(JointId id) const;
  /// Generation of a live slot (with solveOrder: the slot's JointId).
  std::uint32_t generationOf(std::uint32_t slot) const { return m_slots[slot].generation; }
  int jointCount() const { return m_jointCount; }
  /// The definition the joint was created with. Asserts on a stale handle.
  const JointDef& jointDef(JointId id) const;
  /// Hinge motor: target rate (rad/s) and torque bound (N m, >= 0; 0 turns
  /// the motor off). False for a stale handle or a bad value.
  bool setMotor(JointId id, Real speed_radps, Real maxTorque_Nm);
  /// Joints to the world (bodyB null): moves the world anchor (m), e.g. a
  /// grab spring's target. False for a stale handle, a two-body joint or a
  /// non-finite point.
  bool setWorldAnchor(JointId id, const Vec3& anchor_m);
  /// Anchor force (N, world) and angular-row torque (N m, world) on body A
  /// in the last solve. Asserts on a stale handle.
  Vec3 lastForce_N(JointId id) const;
  Vec3 lastTorque_Nm(JointId id) const;
  /// Hinge angle or ConeTwist twist angle (rad) now, 0 for other types.
  double jointAngle_rad(JointId id) const;
  /// ConeTwist swing angle (rad) now: angle between the frames' +X axes.
  double swingAngle_rad(JointId id) const;

  /// What step() does before World::step: the joints broken in the last
  /// World::step are removed and reported, joints of bodies removed from the
  /// World dropped (reported as broken with zero force), jointed sleepers
  /// next to fast bodies woken; Lagrange: the post-stabilization projection
  /// (JointSettings::postStabilize). The solve itself happens inside
  /// World::step (both solvers). For callers that step the World
  /// themselves (the scenario host): call it right before World::step.
  void beforeWorldStep();
  /// beforeWorldStep(); world.step(dt); then collects forces and breaks and
  /// records the anchor error.
  void step(Real dt_s);

  /// Joint-only stepping for the paper's integrator comparison: integrates
  /// the jointed bodies (no contacts, no World::step, no forces other than
  /// gravity, the gyroscopic term and the joints) by one step of dt with the
  /// given scheme, in double, and writes the state back to the World.
  void integrateFree(JointIntegrator method, double dt_s);

  /// Largest anchor separation (m) over all joints now. includeSprings =
  /// false leaves out soft joints (grabs among them), which stretch by design.
  double anchorError_m(bool includeSprings = true) const;
  /// Largest anchor separation (m) of the hard joints (not springs) seen
  /// since creation or resetErrorStats()
  /// (measured at every beforeWorldStep, step and integrateFree). This
  /// is the run report's joint_error_max_m.
  double maxAnchorError_m() const { return m_maxAnchorError_m; }
  void resetErrorStats() { m_maxAnchorError_m = 0; }

  /// Joints that broke during the last step (or beforeWorldStep + World::step).
  const std::vector<JointBreakEvent>& brokenJoints() const { return m_broken; }
  const JointSolveStats& lastSolve() const { return m_stats; }

  /// Pairs of bodies joined by a joint (both non-null): the pairs whose
  /// collisions should be filtered. The JointSystem also hands them to
  /// World::setIslandLinks whenever the joint set changes (so one
  /// JointSystem per World: a second one would replace the first's links).
  std::vector<std::pair<BodyId, BodyId>> connectedPairs() const;

  /// Calls f(id, def) for every live joint.
  template <typename F>
  void forEachJoint(F&& f) const {
    for (std::uint32_t i = 0; i < m_slots.size(); ++i)
      if (m_slots[i].alive) f(JointId{i, m_slots[i].generation}, m_slots[i].def);
  }

  /// The joints' whole state between steps, as exact bits, for snapshots of
  /// a running scene (app/scene_state.h): every joint slot (definition with
  /// its motor and anchor as changed since, generation, last forces), the
  /// joint order, the solver asked for and the one running, both solvers'
  /// memory (Lagrange: each body's last joint velocities and contact time,
  /// the pending results and breaks; impulse: warm-start impulses), the
  /// error and cost-cap figures. Joints hold no shapes, so the saved joints
  /// replace whatever joints this system has; restore refuses damaged bytes
  /// and joints on bodies the World does not have (restore the World first).
  std::string saveState() const;
  Status restoreState(const std::string& bytes);

  /// Live joint slots in the Lagrange solver's elimination order (post-order of
  /// the body tree: leaves first), or in slot order when the joint set
  /// changed since the last step. The impulse solver sweeps in this order,
  /// so one sweep carries a load from the leaves to the root.
  void solveOrder(std::vector<std::uint32_t>& out) const;

  struct Impl;  ///< the Lagrange solver's data (internal/lagrange_solver.h)

 private:
  friend class LagrangeSubsteps;  ///< the Lagrange solver's ConstraintSolver (lagrange_substeps.cpp)
  struct Slot {
    JointDef def;
    std::uint32_t generation = 0;  ///< odd while alive
    bool alive = false;
    Vec3 force_N = Vec3::Zero();
    Vec3 torque_Nm = Vec3::Zero();
  };
  void measureError();
  void refreshLinks();       ///< joint order and island links when the joint set changed
  void wakeJointedSleepers();
  void collectImpulseResults();  ///< impulse solver: forces of the last step, breaks
  void collectLagrangeResults(); ///< Lagrange solver: forces of the last step, breaks
  bool allJointedBodiesKnown() const;  ///< Lagrange: every moving jointed body was solved in the last step
  // The Lagrange solver inside World::step (lagrange_substeps.cpp; LagrangeSubsteps calls these).
  void substepPrepare(double h_s);
  void substepSolve(SolverVelocity* vel, const Body* bodies);
  double substepProject(SolverVelocity* vel, bool useBias);
  void substepProjectPushout(SolverVelocity* pseudo);
  void substepFinish();
  void postStabilize();  ///< lagrange_solver.cpp
  void prepare();  ///< joint order (when dirty), body states, evaluation lists (lagrange_solver.cpp)
  void recordForces();
  void finishBreaks(std::vector<JointBreakEvent>& events);
  bool dropJointsOfDeadBodies();  ///< false when no joint is left
  void runSolver(JointSolverKind kind);  ///< makes kind the running solver (setSolver without the request)
  bool lagrangeFitsCostCap();  ///< the joints as they are now: the factorization within the cap? (lagrange_solver.cpp)

  World& m_world;
  JointSettings m_settings;
  std::vector<Slot> m_slots;
  std::vector<std::uint32_t> m_freeList;
  int m_jointCount = 0;
  bool m_orderDirty = true;
  std::vector<JointBreakEvent> m_broken;
  JointSolveStats m_stats;
  double m_maxAnchorError_m = 0;
  long m_stepsOverCostCap = 0;
  double m_overCostCapWorkPerRow = 0;
  std::unique_ptr<Impl> m_impl;
  std::unique_ptr<ImpulseJoints> m_impulse;  ///< the impulse solver, registered with the World while set
  std::unique_ptr<ConstraintSolver> m_lagrange;  ///< the Lagrange solver's hook, registered with the World while set
};

}  // namespace tumble::physics
