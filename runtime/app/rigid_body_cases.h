#pragma once
// Rigid-body problems for the numerics lab's reports (issue 7): the world is
// a physics::World driven through its public API, so the reports measure the
// same engine the scenarios run. Lives in app because it is the only module
// that may see both numerics and physics.
#include <vector>

#include "numerics/reference_problems.h"
#include "numerics/stability.h"

namespace tumble::app {

/// Work-precision problems: free rigid body (energy and |L|), resting box
/// stack (drift).
std::vector<numerics::PrecisionProblem> rigidBodyPrecisionProblems();

/// The stiff and extreme suite: mass ratios 1:100 and 1:1000, a 500 m/s
/// projectile at a thin wall, 50 interpenetrating boxes, a stack 10 km from
/// the origin, 1 cm and 100 m boxes, a top spinning at 100 rad/s.
std::vector<numerics::StabilityCase> rigidBodyStabilityCases();

}  // namespace tumble::app
