#pragma once
// The simulated state of a scene's systems between two steps, as exact
// bits: the rigid-body world, the joints (with the joint solver the scene
// asks for), vehicles, ropes and cloth, and particle emitters. Saved and restored
// together by `run --save-state` / `--load-state` (app/scene_state.cpp, one
// file field per part) and by world.snapshot() / world.restore() in
// scripts (bind_world_snapshot.cpp, in memory).
#include <functional>
#include <string>

#include "core/result.h"
#include "script/scene_systems.h"

namespace tumble::script {

struct SystemsState {
  std::string jointSolver;    ///< "lagrange" or "impulse": the scene's request (world.set_joint_solver)
  std::string world;          ///< physics::World::saveState
  std::string joints;         ///< physics::JointSystem::saveState; empty: the scene has no joint system
  std::string vehicles;       ///< vehicle::VehicleSystem::saveState; empty: none
  std::string ropesAndCloth;  ///< physics::DeformableSystem::saveState; empty: none
  std::string particles;      ///< particles::ParticleSystem::saveState; empty: none
};

/// Everything above.
SystemsState saveSystems(SceneSystems& scene);
/// Puts a saved state back: the world first (joints, ropes' pins and
/// emitters' anchors refer to its bodies), then the joint solver asked for
/// and each system. Each part is checked against this scene as it is
/// restored; the refused part's name (joint_solver, world, joints,
/// vehicles, ropes_and_cloth, particles) goes to *failedPart, or, when failedPart is
/// null, starts the message. A refused part leaves the parts before it
/// restored: callers that must not change on failure save first and put
/// that back (world.restore does). `fileInMods` accepts the files a stored
/// vehicle definition may name (its resolved engine sample): those inside
/// the mods' folders (isFileInMods).
Status restoreSystems(SceneSystems& scene, const SystemsState& saved,
                      const std::function<bool(const std::string&)>& fileInMods, std::string* failedPart = nullptr);

}  // namespace tumble::script
