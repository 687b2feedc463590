#pragma once
// Engine-neutral scene descriptions for tumble_compare.
//
// A scene is plain data (bodies with shape, pose, velocity, mass and pair
// material), built once and handed to both engines, so Tumble and Bullet
// start from bit-identical inputs. Each runner turns it into its own world
// (run_tumble.cpp, run_bullet.cpp) and measures the same figures
// (RunResult).
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace tumble::compare {

using V3 = Eigen::Vector3d;

enum class BodyShape { Box, Sphere, Capsule, Cylinder };

struct BodySpec {
  BodyShape shape = BodyShape::Box;
  V3 halfExtents_m = V3::Constant(0.5);  ///< Box
  double radius_m = 0.5;                 ///< Sphere, Capsule, Cylinder
  double halfHeight_m = 0.5;             ///< Capsule: half length of the core along local Y; Cylinder: half its height (axis local Y)
  V3 position_m = V3::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  V3 velocity_mps = V3::Zero();
  double mass_kg = 1;  ///< 0 = static
  bool isStatic() const { return mass_kg == 0; }
};

/// A joint between two bodies of the scene, as both engines' rag-doll demos
/// build them: cone-twist (Bullet btConeTwistConstraint) or hinge (Bullet
/// btHingeConstraint). Frames: +X of the joint frame is the twist / hinge
/// axis, given in the world at the start pose; the bodies are held as they
/// start, and the pair does not collide.
struct JointSpec {
  enum class Type { ConeTwist, Hinge } type = Type::ConeTwist;
  int a = 0, b = 0;  ///< body indices (a: child, b: parent)
  V3 anchor_m = V3::Zero();
  V3 axis = V3::UnitX();  ///< world, unit
  double swingLimit_rad = 0.8, twistLower_rad = -0.4, twistUpper_rad = 0.4;  ///< ConeTwist
  double lower_rad = 0, upper_rad = 0;                                      ///< Hinge
};

struct SceneSpec {
  std::string name;
  std::string description;
  V3 gravity_mps2 = V3(0, -9.81, 0);
  /// Coefficients of a contact PAIR. Every body of a scene has the same
  /// material, and each runner sets per-body values so that its own combine
  /// rule yields exactly these (Tumble: sqrt(fa fb) and max(ea, eb); Bullet:
  /// fa fb and ea eb, so Bullet bodies get sqrt of the pair value).
  double friction = 0.5;
  double restitution = 0;
  /// Fast bodies: Bullet gets CCD (motion threshold + swept sphere), as a
  /// fair peer would configure it; Tumble's speculative contacts are always on.
  bool fastBodies = false;
  /// Closed container (highspeed_1000): a dynamic body whose centre leaves
  /// |x|,|y|,|z| <= containHalf_m counts as escaped. 0 = no container.
  double containHalf_m = 0;
  int defaultSteps = 600;
  /// The quality figure `--sweep` draws its headline from (lower is better):
  /// stack_drift_m, penetration_max_m, joint_error_max_m or
  /// energy_rel_change (see sweep.cpp).
  std::string qualityMetric = "stack_drift_m";
  std::vector<BodySpec> bodies;
  std::vector<JointSpec> joints;
};

/// Names of every scene, in the order `list` prints them.
std::vector<std::string> sceneNames();
/// One-line description for `list`.
std::string sceneDescription(const std::string& name);
/// Builds a scene; false when the name is unknown.
bool buildScene(const std::string& name, SceneSpec* out);

/// What one engine measured on one scene.
struct RunResult {
  std::vector<double> stepMs;     ///< wall time of each step() call
  std::vector<double> stepCpuMs;  ///< CPU time of this thread in each step() call (robust to a shared machine)
  double penetrationMax_m = 0;    ///< deepest overlap reported by the engine's narrow phase
  int escaped = 0;                ///< dynamic bodies outside the container at the end
  double stackDrift_m = 0;        ///< largest horizontal (x, z) displacement from the start, at the end
  double kineticEnergyStart_J = 0;
  double kineticEnergyEnd_J = 0;
  int sleepingAtEnd = 0;          ///< dynamic bodies asleep / deactivated at the end
  int nanEvents = 0;              ///< Tumble only: bodies frozen for non-finite state
  double jointErrorMax_m = 0;     ///< largest anchor separation after any step (scenes with joints)
  // Tumble only (World::setPhaseTiming), per step: wall time of the
  // collision pass and of the contact solver's passes, the contact points
  // the step solved, and its substeps.
  std::vector<double> collideMs, contactSolverMs, contactPoints;
  int substeps = 0;
};

/// Bullet solver configuration for one run.
struct BulletConfig {
  int iterations = 40;
  /// Internal steps per dt: stepSimulation(dt, substeps, dt / substeps), so
  /// collision detection and the solver run once per substep.
  int substeps = 1;
  /// btContactSolverInfo::m_leastSquaresResidualThreshold: the iterations of
  /// a (sub)step stop once the largest squared velocity correction of a sweep
  /// is at most this, (m/s)^2. 0 (Bullet's default) runs every iteration.
  double residualThreshold_m2ps2 = 0;
  bool splitImpulse = true;
  bool sleep = false;  ///< Bullet's default deactivation (else DISABLE_DEACTIVATION on every body)
};

/// Tumble solver configuration for one run; the defaults are WorldSettings'.
struct TumbleConfig {
  int substeps = 0;           ///< 0: WorldSettings' default
  int iterations = 0;         ///< solve iterations per substep; 0: default
  double tolerance = -1;      ///< WorldSettings::solverTolerance; < 0: default
  bool sleep = false;
  std::string jointSolver = "impulse";  ///< "impulse" or "lagrange"
  int threads = 1;  ///< WorldSettings::threads
};

/// ODE configuration for one run (Debian's libode, double precision).
/// dWorldStep factorises each island's constraint matrix (a direct solve: no
/// iterations); dWorldQuickStep runs `iterations` SOR sweeps. Either is
/// called `substeps` times per dt, with collision each time.
struct OdeConfig {
  bool quickStep = true;
  int iterations = 20;  ///< dWorldQuickStep only (ODE's default is 20)
  int substeps = 1;
};

/// Sleeping is off by default in both engines: with it, the median step of a
/// settled scene times an idle world and the two engines' sleep policies
/// (Tumble 0.5 s, Bullet 2 s) instead of their solvers. --sleep turns each
/// engine's default sleeping on.
RunResult runTumble(const SceneSpec& scene, int steps, double dt, const TumbleConfig& config);
RunResult runBullet(const SceneSpec& scene, int steps, double dt, const BulletConfig& config);
RunResult runOde(const SceneSpec& scene, int steps, double dt, const OdeConfig& config);
/// Version of the linked ODE ("0.16.2"), from its configuration string.
std::string odeVersion();
/// "float" or "double": how the linked Bullet stores btScalar.
const char* bulletPrecision();

/// CPU time consumed by the calling thread so far, ms (CLOCK_THREAD_CPUTIME_ID).
double threadCpuMs();
/// CPU time consumed by all threads of the process so far, ms
/// (CLOCK_PROCESS_CPUTIME_ID): a run with Tumble's worker threads.
double processCpuMs();

/// Shared end-of-run measurements (start and end positions of dynamic bodies).
void measureEnd(const SceneSpec& scene, const std::vector<V3>& endPositions, RunResult* r);

}  // namespace tumble::compare
