// Tumble side of the comparison: the scene in a physics::World with its
// default settings (8 substeps x (4 solve + 1 relax) iterations), gravity
// from the scene.
#include <chrono>

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

RunResult runTumble(const SceneSpec& scene, int steps, double dt, bool sleep) {
  WorldSettings settings;
  settings.gravity_mps2 = scene.gravity_mps2.cast<Real>();
  settings.enableSleep = sleep;
  World world(settings);
  std::vector<BodyId> ids;
  ids.reserve(scene.bodies.size());
  for (const BodySpec& s : scene.bodies) {
    BodyDef def;
    def.type = s.isStatic() ? BodyType::Static : BodyType::Dynamic;
    def.shape = s.shape == BodyShape::Box ? Shape::box(s.halfExtents_m.cast<Real>()) : Shape::sphere(Real(s.radius_m));
    def.position_m = s.position_m.cast<Real>();
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

  RunResult r;
  r.kineticEnergyStart_J = kineticEnergy(world, ids);
  r.stepMs.reserve(steps);
  const Real h = Real(dt);
  for (int i = 0; i < steps; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    world.step(h);
    auto t1 = std::chrono::steady_clock::now();
    r.stepMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
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
