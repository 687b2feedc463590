#pragma once
// Continuous collision helpers shared by the collision pipeline (ccd.cpp
// explains the method).
#include "physics/body.h"
#include "physics/internal/manifold.h"

namespace tumble::physics {

/// A sphere that can move more than 2 * spec this step against a shape that
/// neither moves nor turns: its contact at the time of impact of its path
/// (motion, m, this step), none if the path misses; a sphere already within
/// spec of the shape gets the ordinary contact. sphereIsA: the sphere is
/// side a of the manifold (the normal points from a to b).
bool sweptSphereContact(const Body& sphere, const Body& other, const Vec3& motion_m, Real spec_m, bool sphereIsA,
                        Manifold& m);

}  // namespace tumble::physics
