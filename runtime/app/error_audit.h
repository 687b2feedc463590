#pragma once
// The run report's energy and momentum error figures (docs/report.md,
// "Error figures"). Measured around the physics of each fixed step, from
// just before the joints' pre-step work to just after World::step, so what
// scripts do between steps (set_velocity, new bodies, moved anchors) is never
// taken for an error, and what the solvers do always is.
//
//   energy gain of a step   = dE - W_forces - W_motors_max
//     E            kinetic (translation and rotation) + gravity's potential
//                  + world.spring potential + soft joints' spring potential
//     W_forces     work of the forces and torques scripts applied, in the step
//     W_motors_max the most the hinge motors could do: tau_max |w_rel| dt
//   energy_rel_drift_max = max over steps of max(0, sum of the gains so far)
//                          / energy scale
//   energy scale = 1 J + m g (height above the lowest body, at the first
//                  step) + the largest kinetic + spring energy seen
//
//   momentum residual of a step = dP - J_external
//     J_external   gravity, script forces and impulses inside the step,
//                  damping, contacts with static, kinematic or sleeping
//                  bodies and the height field (World::externalImpulse_Ns),
//                  and world-anchored joints' reaction (force x dt)
//   momentum_rel_drift_max = max over steps of |sum of the residuals so far|
//                            / momentum scale
//   momentum scale = the largest sum of m |v| seen + |g| (sum of m) t
#include <Eigen/Core>

namespace tumble::app {

class Scene;

class ErrorAudit {
 public:
  /// Right before the step's physics (the joints' pre-step work included).
  void beforePhysics(Scene& scene);
  /// Right after World::step.
  void afterPhysics(Scene& scene, double dt_s);

  double energyRelDriftMax() const { return m_energyScale_J > 0 ? m_energyGainMax_J / m_energyScale_J : 0; }
  double energyGainMax_J() const { return m_energyGainMax_J; }  ///< largest summed gain, J
  double energyScale_J() const { return m_energyScale_J; }
  double momentumRelDriftMax() const {
    return m_momentumScale_Ns > 0 ? m_momentumResidualMax_Ns / m_momentumScale_Ns : 0;
  }
  double momentumResidualMax_Ns() const { return m_momentumResidualMax_Ns; }  ///< kg m/s
  double momentumScale_Ns() const { return m_momentumScale_Ns; }

 private:
  struct Snapshot {
    double kinetic_J = 0, potential_J = 0, elastic_J = 0, work_J = 0, motorRate_Nmps = 0, mv_Ns = 0, mass_kg = 0;
    Eigen::Vector3d momentum = Eigen::Vector3d::Zero(), impulse = Eigen::Vector3d::Zero();
  };
  Snapshot measure(Scene& scene) const;

  bool m_started = false;
  Snapshot m_before;
  double m_energyGain_J = 0, m_energyGainMax_J = 0, m_energyScale_J = 0, m_gravityPotential0_J = 0;
  double m_elasticKineticMax_J = 0, m_gravityImpulse_Ns = 0, m_mvMax_Ns = 0;
  Eigen::Vector3d m_momentumResidual = Eigen::Vector3d::Zero();
  double m_momentumResidualMax_Ns = 0, m_momentumScale_Ns = 0;
};

}  // namespace tumble::app
