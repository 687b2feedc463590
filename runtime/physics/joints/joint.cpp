// Joint definitions: helpers and validation (see joint.h).
#include "physics/joints/joint.h"

#include <cmath>
#include <string>

#include "physics/internal/joint_types.h"
#include "physics/world.h"

namespace tumble::physics {

const char* jointTypeName(JointType type) {
  if (int(type) < 0 || int(type) > int(JointType::Fixed)) return "?";
  return jointTypeRows(type).name;
}

Quat frameFromAxis(const Vec3& axis) {
  const Real n = axis.norm();
  if (!(n > 0)) return Quat::Identity();
  return Quat::FromTwoVectors(Vec3::UnitX(), axis / n);
}

JointDef makeJointDef(const World& world, JointType type, BodyId a, BodyId b, const Vec3& anchor_m,
                      const Vec3& axis) {
  JointDef d;
  d.type = type;
  d.bodyA = a;
  d.bodyB = b;
  const Quat frame = frameFromAxis(axis);
  const Body& A = world.body(a);
  d.localAnchorA_m = A.orientation.conjugate() * (anchor_m - A.position_m);
  d.localFrameA = (A.orientation.conjugate() * frame).normalized();
  if (b.isNull()) {
    d.localAnchorB_m = anchor_m;
    d.localFrameB = frame;
  } else {
    const Body& B = world.body(b);
    d.localAnchorB_m = B.orientation.conjugate() * (anchor_m - B.position_m);
    d.localFrameB = (B.orientation.conjugate() * frame).normalized();
  }
  return d;
}

JointDef makeGrabDef(const World& world, BodyId body, const Vec3& localPoint_m, const Vec3& target_m, Real hertz) {
  JointDef d;
  d.type = JointType::Ball;
  d.bodyA = body;
  d.localAnchorA_m = localPoint_m;
  d.localAnchorB_m = target_m;
  const Real m = world.body(body).mass_kg, omega = 2 * kPi * hertz;
  d.linearStiffness_Npm = m * omega * omega;
  // Damping m omega: a damping ratio of 0.5 for the centre of mass, rising
  // towards 1 for a point far from it (less effective mass). Critical
  // damping of the centre (2 m omega) made the Lagrange solver's explicit spring
  // blow up for a box grabbed at a face (h c / m_eff = 2.1 > 2 at 60 Hz).
  d.linearDamping_Nspm = m * omega;
  return d;
}

static bool finiteQuat(const Quat& q) { return q.coeffs().allFinite() && q.norm() > Real(1e-6); }

Status validateJointDef(const World& world, const JointDef& d) {
  if (!world.isValid(d.bodyA)) return makeError("joint field 'body_a' must be a live body");
  if (!d.bodyB.isNull() && !world.isValid(d.bodyB))
    return makeError("joint field 'body_b' must be a live body or nil (nil = the world)");
  if (d.bodyA == d.bodyB) return makeError("joint fields 'body_a' and 'body_b' must be different bodies");
  const bool dynA = world.body(d.bodyA).type == BodyType::Dynamic;
  const bool dynB = !d.bodyB.isNull() && world.body(d.bodyB).type == BodyType::Dynamic;
  if (!dynA && !dynB) return makeError("a joint needs at least one dynamic body ('body_a' or 'body_b')");
  if (!d.localAnchorA_m.allFinite() || !d.localAnchorB_m.allFinite())
    return makeError("joint fields 'anchor_a' and 'anchor_b' must be finite (metres)");
  if (!finiteQuat(d.localFrameA) || !finiteQuat(d.localFrameB))
    return makeError("joint fields 'frame_a' and 'frame_b' must be finite, non-zero quaternions");
  auto angle = [](Real x) { return std::isfinite(x) && x > -kPi && x < kPi; };
  if (d.type == JointType::Hinge && d.enableLimit) {
    if (!angle(d.lowerAngle_rad) || !angle(d.upperAngle_rad) || d.lowerAngle_rad > d.upperAngle_rad)
      return makeError("hinge fields 'lower_angle' <= 'upper_angle' must lie in (-pi, pi) rad, got " +
                       std::to_string(d.lowerAngle_rad) + " and " + std::to_string(d.upperAngle_rad));
  }
  if (d.type == JointType::ConeTwist) {
    if (!std::isfinite(d.swingLimit_rad) || d.swingLimit_rad <= 0 || d.swingLimit_rad >= kPi)
      return makeError("cone-twist field 'swing_limit' must lie in (0, pi) rad, got " +
                       std::to_string(d.swingLimit_rad));
    if (!angle(d.twistLower_rad) || !angle(d.twistUpper_rad) || d.twistLower_rad > 0 || d.twistUpper_rad < 0)
      return makeError("cone-twist fields 'twist_lower' in (-pi, 0] and 'twist_upper' in [0, pi) rad");
  }
  auto nonNeg = [](Real x) { return std::isfinite(x) && x >= 0; };
  if (!std::isfinite(d.motorSpeed_radps) || !nonNeg(d.maxMotorTorque_Nm))
    return makeError("hinge motor fields: 'motor_speed' must be finite (rad/s) and 'max_motor_torque' >= 0 (N m)");
  if (!nonNeg(d.linearStiffness_Npm) || !nonNeg(d.linearDamping_Nspm) || !nonNeg(d.angularStiffness_Nmprad) ||
      !nonNeg(d.angularDamping_Nmsprad))
    return makeError("joint spring fields (stiffness, damping) must be finite numbers >= 0");
  if (!nonNeg(d.breakForce_N) || !nonNeg(d.breakTorque_Nm))
    return makeError("joint fields 'break_force' (N) and 'break_torque' (N m) must be >= 0 (0 = unbreakable)");
  return Ok{};
}

}  // namespace tumble::physics
