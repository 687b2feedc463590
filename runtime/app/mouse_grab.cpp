#include "app/mouse_grab.h"

#include <cmath>

namespace tumble::app {

PickRay cameraRay(const render::Camera& c, double x_px, double y_px, int width, int height) {
  const Vec3 target = c.target.cast<Real>();
  const Real cp = std::cos(c.pitch_rad), sp = std::sin(c.pitch_rad);
  const Vec3 eye = target + Real(c.distance_m) * Vec3(cp * std::sin(c.yaw_rad), sp, cp * std::cos(c.yaw_rad));
  const Vec3 forward = (target - eye).normalized();
  const Vec3 right = forward.cross(Vec3::UnitY()).normalized();
  const Vec3 up = right.cross(forward);
  const Real h = std::max(1, height), w = std::max(1, width);
  const Real tanHalf = std::tan(Real(c.fovY_rad) / 2);
  // Normalised device coordinates: x right, y up, both in [-1, 1].
  const Real nx = Real(2 * (x_px + 0.5) / w - 1), ny = Real(1 - 2 * (y_px + 0.5) / h);
  PickRay r;
  r.origin_m = eye;
  r.dir = (forward + right * (nx * tanHalf * w / h) + up * (ny * tanHalf)).normalized();
  return r;
}

bool MouseGrab::begin(physics::World& world, physics::JointSystem& joints, const PickRay& ray) {
  end(joints);
  for (const physics::RayHit& hit : world.rayCastAll(ray.origin_m, ray.dir, 1000)) {
    if (hit.body.isNull() || !world.isValid(hit.body) || world.body(hit.body).type != physics::BodyType::Dynamic)
      continue;
    const physics::Body& b = world.body(hit.body);
    const Vec3 local = b.orientation.conjugate() * (hit.point_m - b.position_m);
    auto id = joints.createJoint(physics::makeGrabDef(world, hit.body, local, hit.point_m));
    if (!id) return false;
    world.wake(hit.body);
    m_joint = id.value();
    m_body = hit.body;
    m_depth_m = hit.distance_m;
    return true;
  }
  return false;
}

void MouseGrab::drag(physics::JointSystem& joints, const PickRay& ray) {
  if (!active()) return;
  if (!joints.setWorldAnchor(m_joint, ray.origin_m + ray.dir * m_depth_m)) m_joint = {};
}

void MouseGrab::end(physics::JointSystem& joints) {
  if (active()) joints.destroyJoint(m_joint);
  m_joint = {};
  m_body = {};
}

}  // namespace tumble::app
