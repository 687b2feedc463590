#include "app/error_audit.h"

#include <algorithm>
#include <cmath>

#include "app/scene.h"
#include "physics/joints/joint_system.h"

namespace tumble::app {
namespace {

Eigen::Vector3d wideVec(const Vec3& v) { return v.cast<double>(); }

/// World point of a joint's anchor on one side (bodyB null: the world point).
Eigen::Vector3d anchorPoint(const physics::World& world, physics::BodyId body, const Vec3& local_m) {
  if (body.isNull()) return wideVec(local_m);
  const physics::Body& b = world.body(body);
  return wideVec(b.position_m + b.orientation * local_m);
}

Quat frameOf(const physics::World& world, physics::BodyId body, const Quat& local) {
  return body.isNull() ? local : Quat(world.body(body).orientation * local);
}

/// Potential energy of a soft joint's springs (J): 1/2 k d^2 on the anchors'
/// separation d, and for Hinge and Fixed joints 1/2 k_a e^2 with e the angle
/// (rad) between the two frames' +X axes (Hinge) or of the whole relative
/// rotation (Fixed).
double softJointEnergy(const physics::World& world, const physics::JointDef& d) {
  if (!(d.linearStiffness_Npm > 0)) return 0;
  if (!world.isValid(d.bodyA) || (!d.bodyB.isNull() && !world.isValid(d.bodyB))) return 0;
  const Eigen::Vector3d sep = anchorPoint(world, d.bodyA, d.localAnchorA_m) - anchorPoint(world, d.bodyB, d.localAnchorB_m);
  double e = 0.5 * double(d.linearStiffness_Npm) * sep.squaredNorm();
  if (d.angularStiffness_Nmprad > 0 && (d.type == physics::JointType::Hinge || d.type == physics::JointType::Fixed)) {
    const Quat fa = frameOf(world, d.bodyA, d.localFrameA), fb = frameOf(world, d.bodyB, d.localFrameB);
    double angle = 0;
    if (d.type == physics::JointType::Fixed) {
      angle = double(fa.angularDistance(fb));
    } else {
      const double c = std::clamp(double((fa * Vec3::UnitX()).dot(fb * Vec3::UnitX())), -1.0, 1.0);
      angle = std::acos(c);
    }
    e += 0.5 * double(d.angularStiffness_Nmprad) * angle * angle;
  }
  return e;
}

/// The most power (W) a hinge motor can put in now: tau_max |w_rel . axis|.
double motorPowerBound(const physics::World& world, const physics::JointDef& d) {
  if (d.type != physics::JointType::Hinge || !d.enableMotor || !(d.maxMotorTorque_Nm > 0)) return 0;
  if (!world.isValid(d.bodyA) || (!d.bodyB.isNull() && !world.isValid(d.bodyB))) return 0;
  const Vec3 axis = frameOf(world, d.bodyA, d.localFrameA) * Vec3::UnitX();
  const Vec3 wa = world.body(d.bodyA).angularVelocity_radps;
  const Vec3 wb = d.bodyB.isNull() ? Vec3::Zero() : world.body(d.bodyB).angularVelocity_radps;
  return double(d.maxMotorTorque_Nm) * std::abs(double((wb - wa).dot(axis)));
}

}  // namespace

ErrorAudit::Snapshot ErrorAudit::measure(Scene& scene) const {
  Snapshot s;
  const physics::World& world = scene.world();
  const Eigen::Vector3d g = wideVec(world.settings().gravity_mps2);
  world.forEachBody([&](physics::BodyId, const physics::Body& b) {
    if (!b.isDynamic()) return;
    const Eigen::Vector3d v = wideVec(b.linearVelocity_mps);
    const Eigen::Vector3d wl = wideVec(b.orientation.conjugate() * b.angularVelocity_radps);
    s.kinetic_J += 0.5 * b.mass_kg * v.squaredNorm() + 0.5 * wl.dot(wideVec(b.inertiaLocal_kgm2).cwiseProduct(wl));
    s.potential_J -= b.mass_kg * g.dot(wideVec(b.position_m));
    s.momentum += b.mass_kg * v;
    s.mv_Ns += b.mass_kg * v.norm();
    s.mass_kg += b.mass_kg;
  });
  // World::totalEnergy is kinetic + gravity + world.spring potential.
  s.elastic_J = world.totalEnergy() - s.kinetic_J - s.potential_J;
  if (const physics::JointSystem* joints = scene.jointsIfAny()) {
    joints->forEachJoint([&](physics::JointId, const physics::JointDef& d) {
      s.elastic_J += softJointEnergy(world, d);
      s.motorRate_Nmps += motorPowerBound(world, d);
    });
  }
  s.work_J = world.externalWork_J();
  s.impulse = world.externalImpulse_Ns();
  return s;
}

void ErrorAudit::beforePhysics(Scene& scene) {
  if (!m_started) {
    // The world's own counters start here too (they would otherwise reset
    // inside the first World::step, after this snapshot).
    scene.world().resetErrorStats();
    m_started = true;
    double lowest = 0;
    bool first = true;
    scene.world().forEachBody([&](physics::BodyId, const physics::Body& b) {
      if (!b.isDynamic()) return;
      const double y = double(b.position_m.y() - b.shape.boundingRadius());
      lowest = first ? y : std::min(lowest, y);
      first = false;
    });
    const double g = double(scene.world().settings().gravity_mps2.norm());
    scene.world().forEachBody([&](physics::BodyId, const physics::Body& b) {
      if (b.isDynamic()) m_gravityPotential0_J += b.mass_kg * g * (double(b.position_m.y()) - lowest);
    });
  }
  m_before = measure(scene);
}

void ErrorAudit::afterPhysics(Scene& scene, double dt_s) {
  const Snapshot after = measure(scene);
  const Snapshot& b = m_before;
  // Energy: the change the physics made, less what forces and motors may do.
  const double motorWork_J = std::max(b.motorRate_Nmps, after.motorRate_Nmps) * dt_s;
  const double dE = (after.kinetic_J + after.potential_J + after.elastic_J) - (b.kinetic_J + b.potential_J + b.elastic_J);
  m_energyGain_J += dE - (after.work_J - b.work_J) - motorWork_J;
  m_elasticKineticMax_J = std::max({m_elasticKineticMax_J, b.kinetic_J + b.elastic_J, after.kinetic_J + after.elastic_J});
  m_energyScale_J = 1.0 + m_gravityPotential0_J + m_elasticKineticMax_J;
  m_energyGainMax_J = std::max(m_energyGainMax_J, m_energyGain_J);
  // Momentum: the change the physics made, less the external impulses.
  Eigen::Vector3d jointReaction = Eigen::Vector3d::Zero();
  if (const physics::JointSystem* joints = scene.jointsIfAny()) {
    joints->forEachJoint([&](physics::JointId id, const physics::JointDef& d) {
      if (d.bodyB.isNull()) jointReaction += wideVec(joints->lastForce_N(id)) * dt_s;
    });
  }
  m_momentumResidual += (after.momentum - b.momentum) - (after.impulse - b.impulse) - jointReaction;
  m_gravityImpulse_Ns += double(scene.world().settings().gravity_mps2.norm()) * b.mass_kg * dt_s;
  m_mvMax_Ns = std::max({m_mvMax_Ns, b.mv_Ns, after.mv_Ns});
  m_momentumScale_Ns = m_mvMax_Ns + m_gravityImpulse_Ns;
  m_momentumResidualMax_Ns = std::max(m_momentumResidualMax_Ns, m_momentumResidual.norm());
}

}  // namespace tumble::app
