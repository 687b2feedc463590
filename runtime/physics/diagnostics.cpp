// Diagnostics: the error figures of the run report (energy and momentum
// drift, World::trackErrors; deepest overlap and most contacts are gathered
// by the collision pipeline, non-finite states by world_step.cpp), the
// determinism hash (World::stateHash) and the contacts' debug drawing.
#include <algorithm>
#include <cmath>

#include "core/hash.h"
#include "physics/internal/manifold.h"
#include "physics/world.h"

namespace tumble::physics {

double World::totalEnergy() const {
  double e = 0;
  const Eigen::Vector3d g = m_settings.gravity_mps2.cast<double>();
  for (const Body& b : m_bodies) {
    if (!b.alive || !b.isDynamic()) continue;
    Eigen::Vector3d v = b.linearVelocity_mps.cast<double>();
    Eigen::Vector3d wl = (b.orientation.conjugate() * b.angularVelocity_radps).cast<double>();
    e += 0.5 * b.mass_kg * v.squaredNorm() + 0.5 * wl.dot(b.inertiaLocal_kgm2.cast<double>().cwiseProduct(wl));
    e -= b.mass_kg * g.dot(b.position_m.cast<double>());
  }
  if (m_integration->springCount() > 0) e += m_integration->springEnergy(*this);
  return e;
}

Eigen::Vector3d World::totalMomentum() const {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (const Body& b : m_bodies)
    if (b.alive && b.isDynamic()) p += b.mass_kg * b.linearVelocity_mps.cast<double>();
  return p;
}

void World::resetErrorStats() {
  m_error = ErrorStats{};
  m_energy0 = totalEnergy();
  m_externalWork = 0;
  m_momentum0 = totalMomentum();
  m_externalImpulse.setZero();
  m_trackingStarted = true;
  // Energy scale: the energy that could be converted in the scene, so that a
  // resting scene (E ~ 0) does not divide by zero: sum of |kinetic| plus
  // m g (height above the lowest body) plus 1 J.
  double lowest = 0, ke = 0, mg = 0;
  bool first = true;
  const double g = m_settings.gravity_mps2.cast<double>().norm();
  for (const Body& b : m_bodies)
    if (b.alive && b.isDynamic()) {
      double y = b.position_m.y() - b.shape.boundingRadius();
      lowest = first ? y : std::min(lowest, y);
      first = false;
    }
  double ms = 0;
  for (const Body& b : m_bodies)
    if (b.alive && b.isDynamic()) {
      ke += 0.5 * b.mass_kg * b.linearVelocity_mps.squaredNorm();
      mg += b.mass_kg * g * (b.position_m.y() - lowest);
      ms += b.mass_kg * b.linearVelocity_mps.norm();
    }
  m_energyScale = ke + mg + 1.0;
  m_momentumScale = ms;
}

void World::trackErrors(Real dt) {
  // Energy: contacts (restitution <= 1, friction, soft constraints) and
  // damping can only remove energy, so any gain beyond the work done by
  // scripts is numerical error. energy_rel_drift_max is the largest such gain
  // relative to the scene's energy scale.
  double e = totalEnergy();
  double gain = (e - m_energy0 - m_externalWork) / m_energyScale;
  m_error.energyRelDriftMax = std::max<Real>(m_error.energyRelDriftMax, Real(std::max(gain, 0.0)));
  // Momentum: gravity, forces and impulses from static bodies and scripts are
  // external; what remains must cancel pairwise between dynamic bodies.
  (void)dt;
  double ms = 0;
  for (const Body& b : m_bodies)
    if (b.alive && b.isDynamic() && b.awake) ms += b.mass_kg * b.linearVelocity_mps.norm();
  m_momentumScale = std::max(m_momentumScale, ms);
  Eigen::Vector3d drift = totalMomentum() - m_momentum0 - m_externalImpulse;
  if (m_momentumScale > 0)
    m_error.momentumRelDriftMax = std::max<Real>(m_error.momentumRelDriftMax, Real(drift.norm() / m_momentumScale));
}

std::uint64_t World::stateHash() const {
  Hasher h;
  for (std::uint32_t i = 0; i < m_bodies.size(); ++i) {
    const Body& b = m_bodies[i];
    if (!b.alive) continue;
    h.value(i);
    h.bytes(b.position_m.data(), sizeof(Real) * 3);
    h.bytes(b.orientation.coeffs().data(), sizeof(Real) * 4);
    h.bytes(b.linearVelocity_mps.data(), sizeof(Real) * 3);
    h.bytes(b.angularVelocity_radps.data(), sizeof(Real) * 3);
  }
  return h.digest();
}

void World::debugDraw(DebugDraw& draw) const {
  for (const Manifold& m : m_manifolds)
    for (int i = 0; i < m.count; ++i) {
      const Vec3& p = m.points[i].point_m;
      draw.line(p, p + m.normal * Real(0.3), Vec3(1, 1, 0));
    }
}

}  // namespace tumble::physics
