#pragma once
// Rigid-body problems for the numerics lab's reports (`tumble report`): the
// world is a physics::World driven through its public API, so the reports
// measure the same engine the scenarios run. Part of the report tool, which
// links both numerics and physics (runtime modules never see each other
// here).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "numerics/reference_problems.h"
#include "numerics/stability.h"
#include "physics/world.h"

namespace tumble::tools {

/// Work-precision problems: free rigid body (energy and |L|), resting box
/// stack (drift), a stiff applied spring in the world (every integrator),
/// a 10-link chain per joint solver, a rag-doll drop.
std::vector<numerics::PrecisionProblem> rigidBodyPrecisionProblems();

/// The stiff and extreme suite: mass ratios 1:100 and 1:1000, a 500 m/s
/// projectile at a thin wall, 50 interpenetrating boxes, a stack 10 km from
/// the origin, 1 cm and 100 m boxes, a top spinning at 100 rad/s, a world
/// spring with k/m = 1e6 (every integrator), a 100-link hanging chain per
/// joint solver, a heavy box on a light rag-doll, a stiff cloth.
std::vector<numerics::StabilityCase> rigidBodyStabilityCases();

// ---- joint solvers -------------------------------------------------------------

/// Bodies joined by ball joints, stepped the joint solver's way.
class JointRig {
 public:
  virtual ~JointRig() = default;
  /// One step of dt: the joints' work and World::step.
  virtual void step(Real dt_s) = 0;
  /// Largest anchor separation now (m).
  virtual double anchorError_m() const = 0;
};

/// A joint solver the chain cases run: `chain` joins bodies[i] to
/// bodies[i + 1] at anchors[i + 1] with ball joints and bodies[0] to the
/// world at anchors[0]. The lagrange solver (Lagrange multipliers) and the
/// impulse solver (impulses in the contact loop), both physics/joints, are
/// registered here, and the chain problem and case run once per solver:
/// chain_10_links_lagrange, chain_10_links_impulse, chain_100_links_lagrange,
/// chain_100_links_impulse. Another one can join with registerJointSolver
/// before the report runs.
struct JointSolverCase {
  std::string name;  ///< "lagrange", "impulse": suffix of the case and problem names
  std::function<std::unique_ptr<JointRig>(physics::World& world, const std::vector<physics::BodyId>& bodies,
                                          const std::vector<Vec3>& anchors_m)>
      chain;
};
void registerJointSolver(JointSolverCase solver);
const std::vector<JointSolverCase>& jointSolvers();

}  // namespace tumble::tools
