#pragma once
// ConstraintSolver: the hook through which constraints other than contacts
// (both joint solvers: joints/impulse_solver.cpp, joints/lagrange_substeps.cpp)
// are solved inside the World's substep loop, together with the contacts, on
// the same velocities.
//
// World::step calls, when a solver is set (World::setConstraintSolver):
//   prepare(world, dt, substeps)           once, after the narrow phase
//   per substep:
//     warmStart(vel, bodies)               after gravity/forces, with the contacts' warm start
//     solve(vel, bodies, true)  x N        before each contact solve sweep (position error fed back)
//       solvePushout(pseudo)               after each contact solve sweep: the push-out velocities (optional; impulse)
//     beforeIntegrate(vel, bodies)         after the last sweep (optional; the Lagrange joint solver)
//     projectPushout(pseudo, bodies)       the contacts' push-out velocities onto the joints at once (optional; Lagrange)
//     -- positions integrated --
//     solve(vel, bodies, false) x M        before each contact relax sweep (no bias)
//   finish(world)                          after the substeps, before sleep
//
// vel is the World's per-body velocity array (indexed like the bodies; see
// physics/internal/contact_solver.h); bodies are the World's bodies, whose
// positions and orientations are current (integrated each substep). A body
// that does not move this step (static, kinematic, asleep) must not have its
// velocity changed. The calls are virtual once per phase, not per row.
#include "core/math.h"

namespace tumble::physics {

class World;
struct Body;
struct SolverVelocity;

class ConstraintSolver {
 public:
  virtual ~ConstraintSolver() = default;
  /// Once per step before the substeps; dt_s the step, substeps its count.
  virtual void prepare(const World& world, Real dt_s, int substeps) = 0;
  /// Applies the accumulated impulses (warm start) at the start of a substep.
  virtual void warmStart(SolverVelocity* vel, const Body* bodies) = 0;
  /// One Gauss-Seidel sweep. useBias: the solve phase (position error fed
  /// back); false: the relax phase. Returns the sum of squared impulse
  /// changes relative to the sum of squared accumulated impulses (0 when the
  /// sweep changed nothing); the World stops a phase early only when both
  /// this and the contacts' residual are below WorldSettings::solverTolerance^2.
  virtual Real solve(SolverVelocity* vel, const Body* bodies, bool useBias) = 0;
  /// After the solve phase's last contact sweep, just before the positions
  /// are integrated with vel: a solver that must have the last word on the
  /// velocities the positions move with does its final pass here. Default:
  /// nothing (the impulse joints are solved with the contacts in solve()).
  virtual void beforeIntegrate(SolverVelocity* vel, const Body* bodies) {
    (void)vel;
    (void)bodies;
  }
  /// After each of the solve phase's contact sweeps: pseudo holds the
  /// split-impulse push-out velocities (contact_solver.cpp) the sweeps have
  /// built so far, which move the positions this substep and are then
  /// dropped. A solver may sweep its rows over them, so that contacts and
  /// constraints converge together on a push-out that keeps the constraints
  /// (jointed parts pushed out of the ground together). Default: nothing.
  virtual void solvePushout(SolverVelocity* pseudo) { (void)pseudo; }
  /// Just before the positions are integrated, after beforeIntegrate:
  /// pseudo holds the split-impulse push-out velocities the contacts found
  /// (contact_solver.cpp), which move the positions this substep and are
  /// then dropped. A solver may change them so that they keep its
  /// constraints (jointed parts pushed out of the ground together).
  /// Default: nothing.
  virtual void projectPushout(SolverVelocity* pseudo, const Body* bodies) {
    (void)pseudo;
    (void)bodies;
  }
  /// After the substeps (before sleep): read back forces, breaks.
  virtual void finish(const World& world) = 0;
};

}  // namespace tumble::physics
