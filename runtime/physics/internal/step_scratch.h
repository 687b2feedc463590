#pragma once
// The World's per-step working arrays, shared by the files that make up a
// step (world_step.cpp, collision_pipeline.cpp, ccd.cpp). Kept between steps
// so that stepping does not allocate once warm.
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/math.h"
#include "physics/internal/broad_phase.h"
#include "physics/internal/contact_solver.h"
#include "physics/internal/height_field_collision.h"
#include "physics/internal/manifold.h"
#include "physics/internal/worker_pool.h"

namespace tumble::physics {

struct StepScratch {
  std::unique_ptr<WorkerPool> pool;  ///< WorldSettings::threads > 1: the other threads
  ContactSolver contacts;
  std::vector<SolverVelocity> vel, pseudo;  ///< real and split-impulse velocities, per body slot
  std::vector<SolverPose> pose;             ///< displacement since the step began, per body slot
  std::vector<Aabb> boxes;
  std::vector<std::uint8_t> active;
  std::vector<std::uint32_t> planes, statics;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  // Last step's manifolds bucketed for warm starting: a pair's manifolds
  // (a < b) by b, a height-field manifold by its body a; the manifolds of
  // bucket k are old[oldIndex[oldStart[k] .. oldStart[k + 1])].
  std::vector<Manifold> old;
  std::vector<std::uint32_t> oldStart, oldIndex, cursor;
  HeightFieldScratch heightField;
  std::vector<Manifold> pairManifolds;  ///< manifolds of one body pair (compounds have several)
  std::vector<std::uint32_t> usedOld;   ///< old height-field manifolds already inherited from
  std::vector<std::uint32_t> filterStart;  ///< per body a: its pairs in m_noCollide start here (sorted by a)
  std::vector<Vec3> linear;  ///< per body slot: linear velocities for BodyIntegration::advance
  std::vector<Vec3> turn;  ///< per body slot: w change of the torque-free turn not yet applied
  bool integrationEngaged = false;  ///< this substep's translation came from integrate.cpp
};

}  // namespace tumble::physics
