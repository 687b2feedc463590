#pragma once
#include <vector>

#include "physics/body.h"
#include "physics/internal/manifold.h"

namespace tumble::physics {

struct SolverSettings {
  Real h = 0;  ///< substep length, s
  Real contactHertz = 30, contactDampingRatio = 10, maxPushout_mps = 3;
  Real restitutionThreshold_mps = 1;
  Real linearSlop_m = Real(0.005);
  bool softContacts = false;  ///< soft (spring-damper) push-out instead of Baumgarte
  Real baumgarte = Real(0.2);  ///< fraction of the overlap removed per substep (rigid model)
};

/// Positions at the start of the step (for updating separations) and the
/// split-impulse pseudo-velocities, which move positions but are never part
/// of the bodies' real velocities.
struct StepStart {
  const std::vector<Vec3>* position;
  const std::vector<Quat>* orientation;
  std::vector<Vec3>* pseudoLinear;
  std::vector<Vec3>* pseudoAngular;
};

void prepareContacts(std::vector<Manifold>& manifolds, const std::vector<Body>& bodies, const SolverSettings& s);
void warmStartContacts(std::vector<Manifold>& manifolds, std::vector<Body>& bodies);
void solveContacts(std::vector<Manifold>& manifolds, std::vector<Body>& bodies, const StepStart& start,
                   const SolverSettings& s, bool useBias);
void applyRestitution(std::vector<Manifold>& manifolds, std::vector<Body>& bodies, const SolverSettings& s);

}  // namespace tumble::physics
