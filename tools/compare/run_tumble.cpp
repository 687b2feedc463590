// Tumble side of the comparison: the scene in a physics::World with its
// default settings (8 substeps x (4 solve + 2 relax) sweeps), gravity
// from the scene; joints in a JointSystem (the impulse solver by default).
#include <algorithm>
#include <chrono>
#include <memory>

#include "physics/joints/joint_system.h"
#include "physics/world.h"
#include "scenes.h"

namespace tumble::compare {

using physics::BodyDef;
using physics::BodyId;
using physics::BodyType;
using physics::Shape;
using physics::World;
using physics::WorldSettings;

namespace {

double kineticEnergy(const World& w, const std::vector<BodyId>& ids) {
  double e = 0;
  for (BodyId id : ids) {
    const physics::Body& b = w.body(id);
    if (!b.isDynamic()) continue;
    const Eigen::Vector3d wl = (b.orientation.conjugate() * b.angularVelocity_radps).cast<double>();
    e += 0.5 * b.mass_kg * b.linearVelocity_mps.cast<double>().squaredNorm() +
         0.5 * wl.dot(b.inertiaLocal_kgm2.cast<double>().cwiseProduct(wl));
  }
  return e;
}

}  // namespace

RunResult runTumble(const SceneSpec& scene, int steps, double dt, const TumbleConfig& config) {
  WorldSettings settings;
  settings.gravity_mps2 = scene.gravity_mps2.cast<Real>();
  settings.enableSleep = config.sleep;
  if (config.substeps > 0) settings.substeps = config.substeps;
  if (config.iterations > 0) settings.velocityIterations = config.iterations;
  if (config.tolerance >= 0) settings.solverTolerance = Real(config.tolerance);
  settings.threads = config.threads;
  World world(settings);
  std::vector<BodyId> ids;
  ids.reserve(scene.bodies.size());
  for (const BodySpec& s : scene.bodies) {
    BodyDef def;
    def.type = s.isStatic() ? BodyType::Static : BodyType::Dynamic;
    def.shape = s.shape == BodyShape::Box        ? Shape::box(s.halfExtents_m.cast<Real>())
                : s.shape == BodyShape::Sphere   ? Shape::sphere(Real(s.radius_m))
                : s.shape == BodyShape::Cylinder ? Shape::cylinder(Real(s.radius_m), Real(s.halfHeight_m))
                                                 : Shape::capsule(Real(s.radius_m), Real(s.halfHeight_m));
    def.position_m = s.position_m.cast<Real>();
    def.orientation = s.orientation.cast<Real>();
    def.linearVelocity_mps = s.velocity_mps.cast<Real>();
    def.mass_kg = Real(s.mass_kg);
    // Tumble combines sqrt(fa fb) and max(ea, eb): equal per-body values give
    // the pair value exactly.
    def.friction = Real(scene.friction);
    def.restitution = Real(scene.restitution);
    auto id = world.createBody(def);
    TUMBLE_ASSERT(id.ok(), "comparison scene body refused by Tumble");
    ids.push_back(*id);
  }

  // Joints (rag-dolls): the scene's joints in a JointSystem, as spawn_ragdoll builds them.
  physics::JointSettings js;
  js.projectPositions = false;  // as spawn_ragdoll's joints in a scenario
  physics::parseJointSolver(config.jointSolver, &js.solver);
  std::unique_ptr<physics::JointSystem> joints;
  if (!scene.joints.empty()) joints = std::make_unique<physics::JointSystem>(world, js);
  for (const JointSpec& j : scene.joints) {
    const bool hinge = j.type == JointSpec::Type::Hinge;
    physics::JointDef d = physics::makeJointDef(world, hinge ? physics::JointType::Hinge : physics::JointType::ConeTwist,
                                                ids[j.a], ids[j.b], j.anchor_m.cast<Real>(), j.axis.cast<Real>());
    d.enableLimit = hinge;
    d.lowerAngle_rad = Real(j.lower_rad);
    d.upperAngle_rad = Real(j.upper_rad);
    d.swingLimit_rad = Real(j.swingLimit_rad);
    d.twistLower_rad = Real(j.twistLower_rad);
    d.twistUpper_rad = Real(j.twistUpper_rad);
    auto id = joints->createJoint(d);
    TUMBLE_ASSERT(id.ok(), "comparison scene joint refused by Tumble");
    world.disableCollision(ids[j.a], ids[j.b]);
  }

  RunResult r;
  r.kineticEnergyStart_J = kineticEnergy(world, ids);
  world.setPhaseTiming(true);
  r.substeps = world.settings().substeps;
  r.stepMs.reserve(steps);
  r.stepCpuMs.reserve(steps);
  const Real h = Real(dt);
  // With worker threads, the CPU time of all of them (the other engines
  // are not running meanwhile); the workers' spinning between two steps
  // falls in the next step's figure.
  auto cpuMs = config.threads > 1 ? processCpuMs : threadCpuMs;
  for (int i = 0; i < steps; ++i) {
    const double c0 = cpuMs();
    auto t0 = std::chrono::steady_clock::now();
    if (joints) joints->beforeWorldStep();  // as the scenario host does (results, sleepers, the Lagrange projection)
    world.step(h);
    auto t1 = std::chrono::steady_clock::now();
    r.stepCpuMs.push_back(cpuMs() - c0);
    r.stepMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    r.collideMs.push_back(world.lastPhaseTimes().collide_ms);
    r.contactSolverMs.push_back(world.lastPhaseTimes().contactSolver_ms);
    r.contactPoints.push_back(world.contactPointCount());
    if (joints) r.jointErrorMax_m = std::max(r.jointErrorMax_m, joints->anchorError_m());
  }
  r.penetrationMax_m = world.errorStats().penetrationMax_m;
  r.nanEvents = world.errorStats().nanEvents;
  r.kineticEnergyEnd_J = kineticEnergy(world, ids);
  std::vector<V3> end;
  end.reserve(ids.size());
  for (BodyId id : ids) {
    const physics::Body& b = world.body(id);
    end.push_back(b.position_m.cast<double>());
    if (b.isDynamic() && !b.awake) ++r.sleepingAtEnd;
  }
  measureEnd(scene, end, &r);
  return r;
}

}  // namespace tumble::compare
