#pragma once
// The rigid-body world: bodies, collision, the contact solver and stepping.
// README.md beside this file says which file holds which part.
//
// One step of length dt (world_step.cpp; the choices are explained where
// each part is):
//   broad phase (sweep and prune) -> narrow phase (contact manifolds, once per
//   step, speculative so fast bodies do not tunnel) -> K substeps of
//   { integrate velocities (gravity, forces, applied springs; translation
//     by WorldSettings::integrator, integrate.h), warm start, solve contacts
//     with soft constraints, integrate positions (rotation torque-free with
//     the angular momentum kept, which carries the gyroscopic term),
//     relax contacts without bias, restitution and impact friction for the
//     points that first pushed in this substep } -> sleep.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "physics/body.h"
#include "physics/height_field.h"
#include "physics/integrate.h"
#include "physics/mesh_shape.h"

namespace tumble::physics {

struct WorldSettings;
/// Refuses settings a step cannot run with: substeps or iterations outside
/// 1..1000 (relax and restitution iterations 0..1000), a negative pair cap,
/// an integrator that does not exist, non-finite or negative values where a
/// positive one is needed. The message names the field.
Status validateWorldSettings(const WorldSettings& s);

struct WorldSettings {
  Vec3 gravity_mps2 = Vec3(0, -kStandardGravity, 0);
  int substeps = 8;            ///< solver substeps per step (>= 1); see contact_solver.cpp
  int velocityIterations = 4;  ///< solve iterations per substep (at most; see solverTolerance)
  int relaxIterations = 2;     ///< bias-free iterations per substep
  /// Early exit of the solve iterations of a substep: once a sweep changes
  /// the contact impulses by at most this fraction (RMS, relative to the
  /// normal impulses), the remaining sweeps of that substep are skipped, as
  /// Bullet does with its residual threshold. 0 runs every iteration. A
  /// resting scene converges in one sweep per substep; a disturbed one still
  /// gets all of them. See contact_solver.cpp for the measurements.
  Real solverTolerance = Real(1e-4);
  /// Approach speed (m/s) below which contacts do not bounce, so resting
  /// bodies do not jitter.
  Real restitutionThreshold_mps = 1;
  /// Overlap removal. Default: split impulses, pseudo-velocities that remove
  /// baumgarte * depth / h of the overlap per substep (at most
  /// maxPushoutSpeed) and never enter the real velocities, so correction
  /// never turns into bounce. Soft: a mass-normalised spring-damper
  /// (contactHertz, damping ratio); smoother, but a light body under a heavy
  /// one sinks by F / (m w^2). contact_solver.cpp has the measurements.
  bool softContacts = false;
  Real baumgarte = Real(0.2);
  /// Contact stiffness of the soft model (Hz) and its damping ratio.
  Real contactHertz = 30;
  Real contactDampingRatio = 10;
  /// Largest speed (m/s) at which overlapping bodies are pushed apart.
  Real maxPushoutSpeed_mps = 3;
  /// Contacts are kept up to this separation (m) ahead of touching, plus the
  /// distance the bodies can close in one step (speculative contacts / CCD).
  Real speculativeDistance_m = Real(0.02);
  /// Allowed overlap (m) that is not corrected, so resting contacts persist.
  Real linearSlop_m = Real(0.005);
  /// Gauss-Seidel passes of Newton's restitution law in the substep of an
  /// impact (several bouncing contacts on one body need more than one).
  int restitutionIterations = 1;
  /// Continuous collision against static bodies: after the step, a body that
  /// moved more than half its inner radius is swept from where it started
  /// to where it ended against every static shape; if it would end deep
  /// inside or beyond one it stops at the time of impact, keeping its
  /// velocity (the next step's contact bounces it). Catches bodies deflected
  /// by a collision towards a wall they had no speculative contact with.
  bool continuousStatic = true;
  /// Static triangle meshes: walk their object tree (covering and tight
  /// boxes skip subtrees and nodes a body's box misses). false tests every
  /// triangle's box instead: only for benchmarks that show what the tree saves.
  bool meshTree = true;
  bool enableSleep = true;
  Real sleepLinearSpeed_mps = Real(0.05);
  Real sleepAngularSpeed_radps = Real(0.1);
  Real timeToSleep_s = Real(0.5);
  /// Cost cap of a step's collisions: at most this many body pairs per body
  /// in the world (static ones and planes included) are collided, counted
  /// separately for pairs of two dynamic bodies and pairs with a body that
  /// does not move under contact, so the ground keeps its contacts. Bodies
  /// that touch stay well below it: a box in a pile of equal boxes has at
  /// most 26 neighbours, 13 pairs per body (a 10 x 10 x 10 block of boxes
  /// measures 10.5); the most among the base scenes is 19, in `overlap`,
  /// whose bodies start inside each other. What reaches it is bodies
  /// created inside each other by the hundred: 1000 boxes at one point are
  /// 500 000 pairs, 5-10 s a step uncapped; capped, 0.45 s at first and
  /// 46 ms a step (median) over the 6 s in which the heap spreads. Pairs
  /// past the cap (in sweep order) get no contact in that step and are
  /// counted in ErrorStats::contactPairsSkipped. 0: no cap.
  int maxContactPairsPerBody = 32;
  /// The gyroscopic term: bodies turn with their angular momentum kept
  /// (world_step.cpp). false: w stays fixed in the world between impulses.
  bool gyroscopic = true;
  /// How bodies move between contact solves (integrate.h; --integrator).
  BodyIntegrator integrator = BodyIntegrator::SymplecticEuler;
  /// Threads that share a step's contact passes (1..64; the caller is one of
  /// them). Every result is the same, bit for bit, for any count: the sweeps
  /// keep their sequential order ("Threads" in contact_solver.cpp). 1: no
  /// thread is started.
  int threads = 1;
};

/// A contact event for scripts: reported once when a pair first touches,
/// with the normal impulse of that step.
struct ContactEvent {
  BodyId a, b;  ///< b is null (isNull()) for a contact with the height field
  Vec3 point_m = Vec3::Zero();
  Vec3 normal = Vec3::Zero();  ///< from a to b
  Real impulse_Ns = 0;
};

struct RayHit {
  BodyId body;  ///< null (isNull()) when the ray hit the height field
  Real distance_m = 0;  ///< along the ray from its origin
  Vec3 point_m = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
};

/// First hit of a shape swept along a line (World::shapeCast).
struct ShapeCastHit {
  BodyId body;               ///< null (isNull()) when the shape hit the height field
  Real distance_m = 0;       ///< how far the shape's centre travelled along the unit direction
  Vec3 point_m = Vec3::Zero();  ///< contact point, world
  Vec3 normal = Vec3::Zero();   ///< unit surface normal of what was hit, pointing back at the cast shape
};

/// Error figures gathered while stepping (filled into the run report).
struct ErrorStats {
  Real penetrationMax_m = 0;     ///< deepest overlap seen by the narrow phase
  Real energyRelDriftMax = 0;    ///< largest relative energy gain, see diagnostics.cpp
  Real momentumRelDriftMax = 0;  ///< largest unexplained change of momentum, relative
  int nanEvents = 0;             ///< bodies frozen because their state became non-finite
  int contactsMax = 0;           ///< most contact points in one step
  /// Overlapping body pairs the cost cap left out (WorldSettings::
  /// maxContactPairsPerBody), summed over the steps.
  long contactPairsSkipped = 0;
};

class DebugDraw {
 public:
  virtual ~DebugDraw() = default;
  virtual void line(const Vec3& a, const Vec3& b, const Vec3& color) = 0;
};

struct Manifold;
class BroadPhase;
class ConstraintSolver;
struct SolverSettings;
struct StepScratch;

class World {
 public:
  explicit World(const WorldSettings& settings = {});
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  WorldSettings& settings() { return m_settings; }
  const WorldSettings& settings() const { return m_settings; }

  /// Creates a body; refuses bad definitions (negative mass, zero size, NaN)
  /// with a message naming the field.
  Result<BodyId> createBody(const BodyDef& def);
  /// Removes a body; returns false for a stale or null handle.
  bool destroyBody(BodyId id);
  bool isValid(BodyId id) const;
  /// Read access; asserts on a stale handle (check isValid first).
  const Body& body(BodyId id) const;
  int bodyCount() const { return m_bodyCount; }
  /// Body slots, live or free (every BodyId's index is below it).
  std::size_t bodySlotCount() const { return m_bodies.size(); }
  BodyId idOf(std::uint32_t index) const;

  /// Setters wake the body's island and restart its sleep timer; wake =
  /// false does neither (for small corrections that must not keep a body
  /// awake, like the joints' post-stabilization projection).
  void setPosition(BodyId id, const Vec3& p_m, bool wake = true);
  void setOrientation(BodyId id, const Quat& q, bool wake = true);
  void setLinearVelocity(BodyId id, const Vec3& v_mps, bool wake = true);
  void setAngularVelocity(BodyId id, const Vec3& w_radps, bool wake = true);
  void setMaterial(BodyId id, Real friction, Real restitution);
  /// Body::soundMaterial (heard, not simulated: no wake, no effect on the step).
  void setSoundMaterial(BodyId id, std::uint8_t material);
  /// Force (N) at a world point (m), applied over the next step. wake =
  /// false leaves a sleeping body (and its island) asleep and the force
  /// unused: for forces that only hold a body where it is, like joint
  /// constraint forces (waking on them kept jointed bodies awake forever).
  void applyForce(BodyId id, const Vec3& force_N, const Vec3& point_m, bool wake = true);
  void applyTorque(BodyId id, const Vec3& torque_Nm, bool wake = true);
  /// Impulse (N s) at a world point, applied at once.
  void applyImpulse(BodyId id, const Vec3& impulse_Ns, const Vec3& point_m);
  void wake(BodyId id);

  /// Collision filter: the pair no longer collides (e.g. the two parts of a
  /// joint). Idempotent; the pair is dropped when either body is destroyed.
  void disableCollision(BodyId a, BodyId b);
  void enableCollision(BodyId a, BodyId b);
  bool collisionDisabled(BodyId a, BodyId b) const;

  /// Island links: pairs of bodies that sleep and wake together, as if they
  /// touched (joints: a jointed group falls asleep as one and a touch on any
  /// part wakes all of it). Replaces the previous set; pairs with a stale
  /// handle are ignored; links are dropped when a body is destroyed.
  void setIslandLinks(const std::vector<std::pair<BodyId, BodyId>>& links);
  int islandLinkCount() const { return int(m_islandLinks.size()); }

  void step(Real dt_s);

  /// Per-substep hooks (vehicles: suspension, tyres, wheel spin). Each hook
  /// runs in every substep after gravity and forces are integrated into the
  /// velocities and before the contacts are solved, with the substep length
  /// h (s); body positions are those of the substep. Inside a hook read
  /// velocities with currentLinearVelocity / currentAngularVelocity and
  /// change them with applyImpulseNow (World::applyImpulse would be
  /// overwritten at the end of the step). Hooks run in the order added.
  using SubstepHook = std::function<void(World& world, Real h_s)>;
  int addSubstepHook(SubstepHook hook);  ///< returns an id for removeSubstepHook
  void removeSubstepHook(int id);
  /// Velocity of a body now: inside a step the solver's working copy,
  /// outside it the stored one (m/s, rad/s).
  Vec3 currentLinearVelocity(BodyId id) const;
  Vec3 currentAngularVelocity(BodyId id) const;
  /// Impulse (N s) at a world point applied to the current velocities at
  /// once; inside a hook it acts in this substep. Counted as external work
  /// and momentum in the error figures. Does nothing to a body that is not
  /// dynamic or is asleep (wake it first, outside the step).
  void applyImpulseNow(BodyId id, const Vec3& impulse_Ns, const Vec3& point_m);
  /// Ray against one body's shape (dir need not be unit); false if missed.
  bool rayCastBody(BodyId id, const Vec3& origin_m, const Vec3& dir, Real maxDistance_m, RayHit* hit) const;
  /// Constraints solved inside the substep loop with the contacts (the
  /// impulse joints; see constraint_solver.h), or null. Not owned: the
  /// caller keeps it alive while set and resets it to null before it dies.
  void setConstraintSolver(ConstraintSolver* solver) { m_constraintSolver = solver; }
  ConstraintSolver* constraintSolver() const { return m_constraintSolver; }
  /// Applied springs between centres of mass (integrate.h). A negative
  /// rest length means "the current distance". Refuses bad definitions and
  /// stale bodies with a message naming the field.
  Result<SpringId> addSpring(SpringDef def);
  bool removeSpring(SpringId id);
  const BodyIntegration& integration() const { return *m_integration; }

  /// Replaces a dynamic body's principal moments of inertia (kg m^2, along
  /// its body axes), e.g. from a visual mesh instead of its collision shape.
  /// Refused (message says why) for a body that is not dynamic or moments
  /// that are not finite and > 0 or break the triangle inequality.
  Status setPrincipalInertia(BodyId id, const Vec3& moments_kgm2);

  /// Static terrain the bodies collide with (see height_field.h), or null.
  /// Owned by the caller and must outlive the world or be reset to null;
  /// the world keeps only the pointer (no terrain memory in physics).
  /// Every shape collides with it, with friction sqrt(body * frictionAt),
  /// continuous collision, and rayCast / rayCastAll report hits on it.
  void setHeightField(const HeightField* field);
  const HeightField* heightField() const { return m_heightField; }

  /// Contacts that began during the last step.
  const std::vector<ContactEvent>& contactEvents() const { return m_events; }
  int contactPointCount() const { return m_lastContactPoints; }
  /// Steps whose contact passes were shared between WorldSettings::threads
  /// threads (a step with fewer than about a hundred contact manifolds runs
  /// on the caller alone: waking the threads would cost more).
  std::uint64_t stepsOnThreads() const { return m_stepsOnThreads; }
  /// Wall time of the last step's parts, measured only while
  /// setPhaseTiming(true) (tools/compare; a clock read costs about 20 ns,
  /// some 80 per step, too much for a step of one body).
  struct PhaseTimes {
    double collide_ms = 0;       ///< broad and narrow phase, manifolds
    double contactSolver_ms = 0; ///< every pass of the contact solver over the step's substeps, prepare and store
  };
  void setPhaseTiming(bool on) { m_phaseTiming = on; }
  const PhaseTimes& lastPhaseTimes() const { return m_phaseTimes; }
  /// Overlapping pairs the cost cap left out of the last step's collisions
  /// (WorldSettings::maxContactPairsPerBody).
  long contactPairsSkippedLastStep() const { return m_lastContactPairsSkipped; }

  /// Closest hit along origin + t*dir, t in [0, maxDistance]; dir need not be unit.
  bool rayCast(const Vec3& origin_m, const Vec3& dir, Real maxDistance_m, RayHit* hit) const;
  /// Every hit, nearest first.
  std::vector<RayHit> rayCastAll(const Vec3& origin_m, const Vec3& dir, Real maxDistance_m) const;

  /// Bodies (not the height field) whose shape overlaps `shape` placed at
  /// (position, orientation), in body-index order; touching within
  /// kQueryTolerance_m counts. A shape that fails validateShape, a plane or a
  /// non-finite pose overlaps nothing.
  std::vector<BodyId> overlapShape(const Shape& shape, const Vec3& position_m, const Quat& orientation) const;
  /// Sweeps `shape` from (position, orientation) along dir (need not be
  /// unit) for up to maxDistance_m without turning; the first body or
  /// height-field triangle it touches (within kQueryTolerance_m) is the hit.
  /// `ignore` is skipped (e.g. the car casting its wheels). A shape already
  /// overlapping something hits it at distance 0. Conservative advancement
  /// (see queries/shape_cast.cpp): never reports a hit later than the true one.
  bool shapeCast(const Shape& shape, const Vec3& position_m, const Quat& orientation, const Vec3& dir,
                 Real maxDistance_m, ShapeCastHit* hit, BodyId ignore = {}) const;
  static constexpr Real kQueryTolerance_m = Real(1e-3);

  /// Kinetic + gravitational potential energy of dynamic bodies (J).
  double totalEnergy() const;
  /// Total linear momentum of dynamic bodies (kg m/s).
  Eigen::Vector3d totalMomentum() const;
  /// Hash of every live body's position, orientation and velocities (exact bits).
  std::uint64_t stateHash() const;
  /// The world's whole simulated state as exact bits (world_state.cpp): every
  /// body's pose, velocities, mass, material and sleep state, the contact
  /// cache with its warm-start impulses, the broad phase's order, sleep
  /// islands, the collision filter, island links, springs and settings.
  /// Shapes: the primitive ones' sizes, and hulls, compounds and triangle
  /// meshes whole: restoreState puts the state back into a world with the
  /// same bodies (as the same scenario makes them); a body it lacks is made
  /// again, one the saved world lacks is removed, and damaged bytes are
  /// refused with a message (the world is then unchanged).
  std::string saveState() const;
  Status restoreState(const std::string& bytes);
  const ErrorStats& errorStats() const { return m_error; }
  /// What the world counts as external since resetErrorStats (diagnostics.cpp):
  /// the work (J) of forces, torques and impulses scripts applied, and the
  /// impulse (N s) of gravity, those forces and impulses, damping and contacts
  /// with static, kinematic or sleeping bodies and the height field.
  double externalWork_J() const { return m_externalWork; }
  const Eigen::Vector3d& externalImpulse_Ns() const { return m_externalImpulse; }
  /// Work of the narrow phase against static triangle meshes since the
  /// world was made or resetMeshStats (nodes the tree skipped, triangles tested).
  const MeshStats& meshStats() const { return m_meshStats; }
  void resetMeshStats() { m_meshStats = MeshStats{}; }
  /// Starts energy / momentum bookkeeping from the current state.
  void resetErrorStats();

  void debugDraw(DebugDraw& draw) const;

  /// Calls f(id, body) for every live body.
  template <typename F>
  void forEachBody(F&& f) const {
    for (std::uint32_t i = 0; i < m_bodies.size(); ++i)
      if (m_bodies[i].alive) f(idOf(i), m_bodies[i]);
  }

 private:
  Body& mutableBody(BodyId id);
  void updateInertia(Body& b);
  // The step (world_step.cpp).
  void gatherVelocities();
  void substep(const SolverSettings& ss, ConstraintSolver* joints);
  void integrateVelocities(Real h);
  void integratePositions(Real h);
  void scatterVelocities();
  void collectContactEvents();
  void freezeNonFinite();
  void freezeBody(std::uint32_t index);
  // The collision pipeline (collision_pipeline.cpp).
  void collide(Real dt);
  void bucketOldManifolds();
  void buildSweptBoxes(Real dt);
  void findCandidatePairs();
  void collideBodyPair(std::uint32_t ia, std::uint32_t ib, Real dt, int& points);
  void finishPairManifold(Manifold& m, Real dt);
  void collideHeightField(Real dt, int& points);
  void inheritImpulses(const Manifold& previous, Manifold& m) const;
  bool pairFiltered(std::uint32_t a, std::uint32_t b) const;
  void clampToStatic();  ///< continuous collision (ccd.cpp)
  void updateSleep(Real dt);  ///< sleep.cpp
  void wakeIsland(std::uint32_t index);
  void trackErrors(Real dt);  ///< diagnostics.cpp

  /// A body pair by index (a < b) and generations: the collision filter and
  /// the island links, kept sorted by (a, b) for binary search.
  struct BodyPair {
    std::uint32_t a = 0, b = 0, genA = 0, genB = 0;
    bool operator<(const BodyPair& o) const { return a != o.a ? a < o.a : b < o.b; }
    bool operator==(const BodyPair& o) const { return a == o.a && b == o.b; }
  };
  static BodyPair makePair(BodyId x, BodyId y);

  WorldSettings m_settings;
  const HeightField* m_heightField = nullptr;
  ConstraintSolver* m_constraintSolver = nullptr;  ///< see setConstraintSolver
  std::vector<Body> m_bodies;
  std::vector<std::uint32_t> m_freeList;
  int m_bodyCount = 0;
  std::unique_ptr<BroadPhase> m_broad;
  std::vector<Manifold> m_manifolds;
  std::vector<ContactEvent> m_events;
  std::vector<Vec3> m_stepStartPosition;
  std::vector<Quat> m_stepStartOrientation;
  std::unique_ptr<BodyIntegration> m_integration;  ///< integrator strategy and springs (integrate.h)
  std::unique_ptr<StepScratch> m_scratch;  ///< solver arrays kept between steps (no allocation per step)
  std::vector<std::uint32_t> m_sleepIsland;  ///< per body: island it fell asleep with (0 = none)
  std::uint32_t m_nextIsland = 1;
  std::vector<BodyPair> m_noCollide;    ///< sorted; see disableCollision
  std::vector<BodyPair> m_islandLinks;  ///< sorted; see setIslandLinks
  int m_lastContactPoints = 0;
  std::uint64_t m_stepsOnThreads = 0;
  bool m_phaseTiming = false;
  PhaseTimes m_phaseTimes;
  long m_lastContactPairsSkipped = 0;
  ErrorStats m_error;
  mutable MeshStats m_meshStats;  ///< see meshStats (rays, which are const, count too)
  // Energy / momentum bookkeeping (double: sums over many bodies).
  double m_energy0 = 0, m_energyScale = 0, m_externalWork = 0;
  Eigen::Vector3d m_momentum0 = Eigen::Vector3d::Zero(), m_externalImpulse = Eigen::Vector3d::Zero();
  double m_momentumScale = 0;
  bool m_trackingStarted = false;
  bool m_inStep = false;  ///< between gather and scatter: velocities live in m_scratch->vel
  std::vector<std::pair<int, SubstepHook>> m_substepHooks;
  int m_nextHookId = 1;
};

}  // namespace tumble::physics
