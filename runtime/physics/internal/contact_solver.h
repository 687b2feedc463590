#pragma once
// Contact solver data: a compact copy of what the inner loop touches.
//
// prepare() turns the narrow phase's manifolds into constraints once per
// step: body indices, inverse masses, the normal and tangent Jacobian rows
// (r x n and I^-1 (r x n) for each side) and effective masses. The substeps
// then only read these rows and the bodies' velocities, which live in a
// separate array of 24-byte entries (gathered before the substeps, scattered
// after), never the large Body struct. Inverse world inertia is taken at the
// start of the step, as rA, rB and the effective masses already were.
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "physics/body.h"
#include "physics/internal/manifold.h"

namespace tumble::physics {

class WorkerPool;

struct SolverSettings {
  Real h = 0;  ///< substep length, s
  Real contactHertz = 30, contactDampingRatio = 10, maxPushout_mps = 3;
  Real restitutionThreshold_mps = 1;
  Real linearSlop_m = Real(0.005);
  bool softContacts = false;   ///< soft (spring-damper) push-out instead of split impulses
  Real baumgarte = Real(0.2);  ///< fraction of the overlap removed per substep (split impulses)
  int restitutionIterations = 1;
};

/// Solver vectors are 4-wide (w = 0) so that a Jacobian row times a velocity
/// is one packed multiply-add and one horizontal sum (SSE for float),
/// instead of three scalar dot products.
using Vec4r = Eigen::Matrix<Real, 4, 1>;
/// A 3x3 matrix padded to 4x4 (zero last row and column), so that it times
/// a Vec4r is four packed multiply-adds.
using Mat4r = Eigen::Matrix<Real, 4, 4>;
inline Mat4r wide(const Mat3& m) {
  Mat4r r = Mat4r::Zero();
  r.topLeftCorner<3, 3>() = m;
  return r;
}
inline Vec4r wide(const Vec3& v) { return Vec4r(v.x(), v.y(), v.z(), 0); }
inline Vec3 narrow(const Vec4r& v) { return v.head<3>(); }

/// Linear and angular velocity of one body (solver copy), indexed like World's bodies.
struct SolverVelocity {
  Vec4r linear = Vec4r::Zero();
  Vec4r angular = Vec4r::Zero();
};

/// Where each body is relative to the start of the step (for separations).
struct SolverPose {
  Vec3 dp = Vec3::Zero();         ///< position minus step-start position, m
  Quat dq = Quat::Identity();     ///< orientation times conjugate of step-start orientation
};

struct ConstraintPoint {
  // Jacobian rows, fixed during the step.
  Vec4r rnA, rnB;        ///< rA x n, rB x n
  Vec4r inA, inB;        ///< IA^-1 (rA x n), IB^-1 (rB x n)
  Vec4r rtA[2], rtB[2];  ///< rA x t_k, rB x t_k
  Vec4r itA[2], itB[2];  ///< I^-1 of those
  Real normalMass = 0, tangentMass[2] = {0, 0};
  Real normalImpulse = 0, tangentImpulse[2] = {0, 0};  ///< accumulated (N s), warm started
  Real impactImpulse = 0;  ///< largest normal impulse of one substep this step, restitution included (events)
};

/// A point's impact bookkeeping, apart from ConstraintPoint (its index):
/// the passes at each substep's start read whether a point has pushed yet
/// for every point, and the rows only for the few that have not.
struct PointImpact {
  Real maxNormalImpulse = 0;  ///< largest single push this step (did it touch?)
  /// Normal velocity (m/s) before this substep's forces, while the point has
  /// not pushed yet: with the velocity after them it gives the free relative
  /// acceleration along the normal (restitution, see contact_solver.cpp).
  Real freeVelocity0_mps = 0;
  Real approachAcceleration_mps2 = 0;  ///< that acceleration, in the substep of impact
  Real relativeVelocity_mps = 0;  ///< normal velocity at the instant of impact (< 0 approaching)
  bool bounced = false;    ///< restitution applied this step (once per point per step)
  bool bouncing = false;   ///< restitution being applied in this substep
};

/// What the separation updates read, per point, apart from ConstraintPoint
/// (its index): twice a substep they run over every point, and in a small
/// array of their own they read about 30 bytes a point instead of parts of
/// three cache lines of the solver's rows.
struct PointGeometry {
  Vec3 rA, rB;              ///< contact point from each centre (or the rolling centre, see roundOffsetA), m
  Real separation0_m = 0;   ///< separation at the start of the step
};

struct Constraint {
  Vec4r normal = Vec4r::UnitY();
  Vec4r tangent[2] = {Vec4r::UnitX(), Vec4r::UnitZ()};
  std::uint32_t a = 0, b = 0;  ///< body indices (velocity array)
  std::uint32_t manifold = 0;  ///< index in World's manifolds
  std::uint32_t firstPoint = 0;
  std::uint8_t count = 0;
  bool movesA = false, movesB = false;  ///< side takes impulses (awake dynamic)
  /// 1: side A is static (its velocity is zero and stays so), 2: side B is
  /// static or the height field, 0: neither. The solver then leaves the
  /// fixed side out of every row (Constraint rows of a pile on the ground
  /// are mostly one-sided: a third fewer multiply-adds per row).
  std::uint8_t fixedSide = 0;
  bool roundA = false, roundB = false;
  /// A round side that is a compound's child: its points' rA / rB hold the
  /// rolling centre (the child sphere's centre, the capsule's segment
  /// point) relative to the body's centre of mass, which the substeps turn
  /// with the body (a ball or a weeble weighted off its centre rocks on it).
  bool roundOffsetA = false, roundOffsetB = false;
  Real invMassA = 0, invMassB = 0;
  Real friction = 0, restitution = 0;
  Real rollingArm_m = 0;
  std::int32_t rolling = -1;  ///< index into the rolling rows, -1 without rolling resistance
  std::int32_t block = -1;    ///< index into the normal blocks, -1: normal rows solved one by one
};

/// A manifold's normal rows solved as one block (contact_solver.cpp,
/// "Normal blocks"): the pseudo-inverse of their effective-mass matrix K
/// (N s per m/s; K is singular for four coplanar points, rank 3) and, when
/// K has a one-dimensional null space, its unit null vector, the twist that
/// redistributes the points' impulses without changing the bodies' motion.
struct NormalBlock {
  Real invK[kMaxManifoldPoints][kMaxManifoldPoints] = {};  ///< K^+, kg
  Real twist[kMaxManifoldPoints] = {};  ///< unit null vector of K (all zero when K has none)
};

/// What a constraint with a round side off its body's centre of mass
/// (Constraint::roundOffsetA/B) needs to turn that side's lever arms with
/// the body in each substep: the lever from the centre of mass to the
/// contact swings as the body rocks, and a lever frozen for the step feeds
/// energy into a weeble by one step's lag per swing.
struct RoundOffsetRows {
  std::uint32_t constraint = 0;
  Mat3 invInertiaA = Mat3::Zero(), invInertiaB = Mat3::Zero();  ///< world, at the step's start
  Real radiusA_m = 0, radiusB_m = 0;  ///< the round child's radius, per side (0: that side is not one)
};

/// What a one-point rim contact of a cylinder (Manifold::rimA/B) needs to
/// follow the cylinder's support point in each substep ("Rim contacts" in
/// contact_solver.cpp): the cylinder's orientation and size at the step's start,
/// and both bodies' inverse inertia then, which the substeps turn with them.
struct RimRows {
  std::uint32_t constraint = 0;
  Mat3 invInertiaA = Mat3::Zero(), invInertiaB = Mat3::Zero();  ///< world, at the step's start (1/(kg m^2))
  Mat3 orientationA = Mat3::Identity(), orientationB = Mat3::Identity();  ///< a rim side's cylinder, body to world, at the step's start
  Real radiusA_m = 0, radiusB_m = 0;          ///< a rim side's cylinder radius (0: that side is not a rim)
  Real halfHeightA_m = 0, halfHeightB_m = 0;  ///< and its half height
  Real reachA0_m = 0, reachB0_m = 0;          ///< its support's height along the normal at the step's start
};

/// Angular rows of rolling / spinning resistance about t0, t1, n.
struct RollingRows {
  Vec4r iA[3], iB[3];  ///< IA^-1 axis_k, IB^-1 axis_k
  Real mass[3] = {0, 0, 0};
  Real impulse[3] = {0, 0, 0};  ///< per substep
};

class ContactSolver {
 public:
  /// Builds the constraints (warm-start impulses come from the manifolds).
  /// Manifolds against the height field (b = kHeightFieldBody) use velocity
  /// slot bodies.size(), which the caller keeps at zero.
  void prepare(const std::vector<Manifold>& manifolds, const std::vector<Body>& bodies);
  void warmStart(std::vector<SolverVelocity>& vel) const;
  /// Recomputes every point's separation from the bodies' displacements.
  void updateSeparations(const std::vector<SolverPose>& pose);
  /// One Gauss-Seidel sweep. useBias: the solve phase (speculative bias,
  /// split-impulse pseudo-velocities); otherwise the bias-free relax phase.
  /// Returns the sum of squared impulse changes: 0 means the sweep changed
  /// nothing, so every further sweep of this phase would change nothing
  /// either (same inputs, same outputs) and can be skipped without changing
  /// a single bit of the result.
  Real solve(std::vector<SolverVelocity>& vel, std::vector<SolverVelocity>& pseudo, const SolverSettings& s,
             bool useBias);
  /// Newton's law needs each point's normal velocity at the instant of
  /// impact. Before a substep's forces, points that have not pushed yet
  /// this step record their normal velocity; after the forces (and before
  /// any impulse of the substep, so a point does not see what its
  /// neighbours did in the same sweep, which inflated bounces and gained
  /// energy in clumps of fast spheres) captureApproachSpeeds turns it and
  /// the separation into the velocity at contact (contact_solver.cpp).
  void recordFreeVelocities(const std::vector<SolverVelocity>& vel);
  void captureApproachSpeeds(const std::vector<SolverVelocity>& vel, Real h);
  /// Per substep: rolling and split impulses start from zero.
  void resetSubstepImpulses();
  /// Newton's law at the end of the substep in which a point first pushed,
  /// with Coulomb friction over the whole impact impulse; iterated
  /// restitutionIterations times. Returns the impulse (N s) that non-moving
  /// bodies gave the moving ones through it.
  Eigen::Vector3d applyRestitution(std::vector<SolverVelocity>& vel, const SolverSettings& s);
  /// Impulse (N s) that non-moving bodies gave the moving ones in this
  /// substep: the accumulated impulses, summed once per substep (exact,
  /// since every impulse of a substep ends up in its accumulated value).
  Eigen::Vector3d externalImpulse() const;
  /// Accumulated impulses back to the manifolds (warm start, events).
  void store(std::vector<Manifold>& manifolds) const;

  /// Threads for the passes over the constraints (null: all on the caller).
  /// No result depends on it ("Threads" in contact_solver.cpp).
  void setPool(WorkerPool* pool) { m_pool = pool; }
  /// Levels of the last prepare()'s schedule for the pool: the longest
  /// chain of constraints that share moving bodies ("Threads" in
  /// contact_solver.cpp); 0 when the passes run on the caller alone.
  std::size_t threadedLevels() const { return m_levels; }

  std::size_t size() const { return m_constraints.size(); }
  /// Sum of squared accumulated normal impulses after the last sweep.
  Real lastMagnitude() const { return m_lastMagnitude; }

 private:
  std::vector<Constraint> m_constraints;
  std::vector<ConstraintPoint> m_points;
  std::vector<PointGeometry> m_geometry;  ///< per point, as m_points
  std::vector<Real> m_separation;         ///< per point: current separation, m (updated once per solve phase)
  std::vector<PointImpact> m_impact;      ///< per point, as m_points
  std::vector<Real> m_pseudoImpulse;      ///< per point: split-impulse accumulator (N s), per substep
  std::vector<RollingRows> m_rolling;
  std::vector<NormalBlock> m_blocks;
  /// Builds c's normal block if its rows allow one (contact_solver.cpp).
  void prepareNormalBlock(Constraint& c, const Manifold& m);
  template <int kFixedSide>
  bool solveNormalBlock(const Constraint& c, Vec4r& vA, Vec4r& wA, Vec4r& vB, Vec4r& wB, Real invH,
                        Real& residual);
  std::vector<RoundOffsetRows> m_roundOffset;
  void turnRoundOffsetLevers(const std::vector<SolverPose>& pose);
  std::vector<RimRows> m_rims;
  void turnRimRows(const std::vector<SolverPose>& pose);
  std::vector<std::uint32_t> m_external;  ///< constraints with one non-moving side
  struct SweepConstants;
  template <int kFixedSide>
  void solveConstraint(const Constraint& c, std::vector<SolverVelocity>& vel, std::vector<SolverVelocity>& pseudo,
                       const SweepConstants& k, Real& residual, Real& magnitude);
  Real m_lastMagnitude = 0;

  // Threads ("Threads" in contact_solver.cpp).
  WorkerPool* m_pool = nullptr;
  /// Whether this step's passes go to the pool (enough constraints for it).
  bool threaded() const;
  std::vector<std::uint32_t> m_level;  ///< per constraint (sequential order)
  std::vector<Vec3> m_place;           ///< per constraint: its first point, m (world)
  /// Per constraint (storage order once the schedule is built): the last
  /// earlier one moving its body a, its body b (-1: none).
  std::vector<std::array<std::int32_t, 2>> m_pred;
  std::vector<std::vector<std::uint32_t>> m_threadOrder;  ///< per thread: its constraints, in level order
  std::vector<std::int32_t> m_lastConstraint;             ///< per body slot (scratch of the schedule)
  std::vector<std::uint32_t> m_levelCount;                ///< per level (scratch of the schedule)
  std::vector<std::uint32_t> m_levelStart, m_byLevel;      ///< scratch of the schedule
  mutable std::uint32_t m_pass = 0;  ///< ordered passes so far (all steps)
  /// Per constraint (storage order): the last ordered pass that has solved it.
  std::unique_ptr<std::atomic<std::uint32_t>[]> m_done;
  std::size_t m_doneCapacity = 0;
  std::vector<std::array<Real, 2>> m_sweepSums;  ///< per constraint: the last sweep's residual and magnitude
  /// With threads the constraints are stored in the threads' order: thread
  /// t solves [m_threadStart[t], m_threadStart[t + 1]); m_logical lists
  /// them in the sequential order (empty without threads: storage is it).
  std::vector<std::uint32_t> m_threadStart, m_logical;
  std::vector<Constraint> m_permutedConstraints;      ///< scratch of the schedule
  std::vector<ConstraintPoint> m_permutedPoints;      ///< scratch of the schedule
  std::vector<PointGeometry> m_permutedGeometry;      ///< scratch of the schedule
  std::vector<Real> m_permutedSeparation;             ///< scratch of the schedule
  std::vector<PointImpact> m_permutedImpact;          ///< scratch of the schedule
  std::vector<Real> m_permutedPseudoImpulse;          ///< scratch of the schedule
  std::vector<std::array<std::int32_t, 2>> m_permutedPred;  ///< scratch of the schedule
  std::vector<std::uint32_t> m_storageOf;             ///< per constraint in the sequential order: where it is stored
  std::size_t m_levels = 0;
  void buildSchedule(std::size_t bodySlots);
  /// Calls visit(ci) for every constraint ci (storage index); two that move
  /// the same body are visited in the sequential order, the later one only
  /// once the earlier one has finished (on the same thread, or waited for).
  template <class Visit>
  void forEachOrdered(Visit&& visit) const;
  /// Calls visit(begin, end) over ranges of constraints (storage index)
  /// that together cover them all once, each thread its own share
  /// (independent work only).
  template <class Visit>
  void forEachShare(Visit&& visit) const;
};

}  // namespace tumble::physics
