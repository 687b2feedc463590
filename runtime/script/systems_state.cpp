#include "script/systems_state.h"

#include "particles/particle_system.h"
#include "physics/deformable.h"
#include "physics/joints/joint_system.h"
#include "vehicle/vehicle_system.h"

namespace tumble::script {

SystemsState saveSystems(SceneSystems& scene) {
  SystemsState s;
  s.jointSolver = physics::jointSolverName(scene.jointSolver());
  s.world = scene.world().saveState();
  if (const physics::JointSystem* j = scene.jointsIfAny()) s.joints = j->saveState();
  if (const vehicle::VehicleSystem* v = scene.vehiclesIfAny()) s.vehicles = v->saveState();
  if (const physics::DeformableSystem* d = scene.deformablesIfAny()) s.ropesAndCloth = d->saveState();
  if (const particles::ParticleSystem* p = scene.particlesIfAny()) s.particles = p->saveState();
  return s;
}

Status restoreSystems(SceneSystems& scene, const SystemsState& saved,
                      const std::function<bool(const std::string&)>& fileInMods, std::string* failedPart) {
  auto part = [&](const char* name, Status st) -> Status {
    if (st) return Ok{};
    if (failedPart) {
      *failedPart = name;
      return st;
    }
    return makeError(std::string(name) + ": " + st.error());
  };
  auto none = [&](const char* name, const char* what, int made) {
    return part(name, makeError(std::string("the snapshot holds no ") + what + ", but the scene has " +
                                std::to_string(made) + " (not the run it was saved from)"));
  };
  physics::JointSolverKind kind;
  if (!physics::parseJointSolver(saved.jointSolver, &kind))
    return part("joint_solver", makeError("\"" + saved.jointSolver + "\"; expected \"lagrange\" or \"impulse\""));
  if (Status st = part("world", scene.world().restoreState(saved.world)); !st) return st;
  scene.setJointSolver(kind);
  if (!saved.joints.empty()) {
    if (Status st = part("joints", scene.joints().restoreState(saved.joints)); !st) return st;
  } else if (scene.jointsIfAny() && scene.jointsIfAny()->jointCount() > 0) {
    return none("joints", "joints", scene.jointsIfAny()->jointCount());
  }
  // Vehicles spawned, re-tuned or removed since are made again from their
  // stored definitions, or removed (vehicle_state.cpp); with none saved,
  // every vehicle here was spawned since.
  if (!saved.vehicles.empty() || (scene.vehiclesIfAny() && scene.vehiclesIfAny()->count() > 0)) {
    const std::string bytes = saved.vehicles.empty() ? vehicle::VehicleSystem::emptyState() : saved.vehicles;
    if (Status st = part("vehicles", scene.vehicles().restoreState(bytes, fileInMods)); !st) return st;
  }
  if (!saved.ropesAndCloth.empty()) {
    if (Status st = part("ropes_and_cloth",
                         scene.deformables().restoreState(saved.ropesAndCloth, scene.world().bodySlotCount()));
        !st)
      return st;
  } else if (scene.deformablesIfAny() && scene.deformablesIfAny()->count() > 0) {
    return none("ropes_and_cloth", "ropes or cloth", scene.deformablesIfAny()->count());
  }
  // Emitters are plain data: the saved ones replace the scene's.
  if (!saved.particles.empty()) {
    if (Status st = part("particles", scene.particles().restoreState(saved.particles)); !st) return st;
  } else if (scene.particlesIfAny() && scene.particlesIfAny()->emitterCount() > 0) {
    return none("particles", "particle emitters", scene.particlesIfAny()->emitterCount());
  }
  return Ok{};
}

}  // namespace tumble::script
