#include "app/fixed_step.h"

#include "app/scene.h"
#include "app/scene_audio.h"
#include "core/process_stats.h"
#include "particles/particle_system.h"
#include "physics/deformable.h"
#include "physics/joints/joint_system.h"
#include "vehicle/vehicle_system.h"

namespace tumble::app {

namespace {

// Attached emitters take their body's pose and velocity, then every pool
// steps. Nothing at all when the scenario never spawned an emitter.
void stepParticles(Scene& scene, particles::ParticleSystem& ps, float dt_s) {
  const physics::World& world = scene.world();
  ps.forEachAnchored([&](particles::EmitterId id, std::uint64_t anchor) {
    const physics::BodyId body = script::bodyOfEmitterAnchor(anchor);
    if (!world.isValid(body)) {
      ps.anchorLost(id);  // the body was removed: stop, let the particles finish
      return;
    }
    const physics::Body& b = world.body(body);
    ps.setAnchorState(id, b.position_m.cast<float>(), b.orientation.cast<float>(),
                      b.linearVelocity_mps.cast<float>(), b.angularVelocity_radps.cast<float>());
  });
  ps.setGravity(world.settings().gravity_mps2.cast<float>());
  ps.step(dt_s);
}

}  // namespace

void stepScene(Scene& scene, const StepTime& at, RunTimings& t) {
  Stopwatch clock;
  // The step's length can change while running (world.set_dt): read it once, here.
  const double dt = scene.dt_s();
  script::ScenarioHost& script = scene.host();

  // 1. Input: the actions every script reads in this step.
  scene.input().step();

  // 2. Lua: the scenario's on_update (vehicle controllers run in it).
  const std::size_t staticModels = script.presentation().statics.size();
  script.update(at.start_s, dt, at.index);
  // Static models placed during play go into the terrain's tree too.
  if (script.presentation().statics.size() != staticModels) scene.registerStaticObjects();
  const double scriptDone_s = clock.seconds();
  const bool simulate = !scene.options().freezePhysics;  // run --freeze: the world never steps

  if (simulate) scene.errorAudit().beforePhysics(scene);

  // 3. Joints, last before the physics so every force of the step (scripts'
  //    included) is in the Lagrange solver's Q.
  if (physics::JointSystem* joints = scene.jointsIfAny(); joints && simulate) joints->beforeWorldStep();

  // 4. Vehicles: controls, engine and gearbox; the wheels act in every substep.
  if (vehicle::VehicleSystem* vehicles = scene.vehiclesIfAny(); vehicles && simulate) vehicles->beforeStep(Real(dt));

  // 5. Physics: the world's substeps (forces, contacts, integration).
  if (simulate) {
    scene.world().step(Real(dt));
    scene.errorAudit().afterPhysics(scene, dt);
    scene.warnOnceOfCostCaps();
  }

  // 6. Ropes and cloth, against the bodies' new positions.
  if (physics::DeformableSystem* deformables = scene.deformablesIfAny(); deformables && simulate) {
    physics::DeformableEnvironment env;
    env.gravity_mps2 = scene.world().settings().gravity_mps2;
    env.world = &scene.world();
    env.heightField = scene.world().heightField();
    deformables->step(Real(dt), env);
  }
  const double physicsDone_s = clock.seconds();

  // 7. After-step callbacks: on_contact, trigger volumes, due timers.
  script.afterStep(at.start_s + dt, at.index);
  const double stepDone_s = clock.seconds();

  // 8. Particles, after on_contact (which may spawn sparks).
  if (particles::ParticleSystem* ps = scene.particlesIfAny()) {
    stepParticles(scene, *ps, float(dt));
    t.particles_s += clock.seconds() - stepDone_s;
  }

  // 9. Audio: vehicles, the step's impacts, thunder, sounds on bodies; the audio
  //    clock advances one step (offline output renders it). Nothing without audio.
  stepAudio(scene, at.start_s, dt);

  t.script_s += scriptDone_s + (stepDone_s - physicsDone_s);
  t.physics_s += physicsDone_s - scriptDone_s;
  t.stepMs.push_back(stepDone_s * 1000.0);
}

}  // namespace tumble::app
