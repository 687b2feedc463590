#include "app/designer_gizmo.h"

#include <algorithm>
#include <cmath>

namespace tumble::app {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr int kRingSegments = 48;
constexpr float kLift_m = 0.3f;  // the centre above the object's ground point

Eigen::Vector3f toFloat(const Vec3& v) { return Eigen::Vector3f(float(v.x()), float(v.y()), float(v.z())); }

// The closest approach of a ray and a line through `p` along unit `u`: the
// parameters along each (ray s >= 0, line t) and the distance between the
// two points. Nothing when they are parallel.
struct Approach {
  float rayParam = 0, lineParam = 0, distance_m = 0;
};
std::optional<Approach> closestApproach(const ViewRay& ray, const Eigen::Vector3f& p, const Eigen::Vector3f& u) {
  const Eigen::Vector3f& d = ray.direction;
  const Eigen::Vector3f w = ray.origin_m - p;
  const float b = d.dot(u), dd = d.dot(w), ee = u.dot(w);
  const float denominator = 1.0f - b * b;  // both unit vectors
  if (denominator < 1e-6f) return std::nullopt;
  Approach a;
  a.rayParam = (b * ee - dd) / denominator;
  a.lineParam = (ee - b * dd) / denominator;
  if (a.rayParam < 0) {  // behind the eye: the eye itself is the closest point of the ray
    a.rayParam = 0;
    a.lineParam = ee;
  }
  a.distance_m = ((ray.origin_m + a.rayParam * d) - (p + a.lineParam * u)).norm();
  return a;
}

// The angle (rad) under which the ray misses the segment a..b, seen from the eye.
float missAngleToSegment(const ViewRay& ray, const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  const Eigen::Vector3f ab = b - a;
  const float length = ab.norm();
  if (length <= 0) return 1e9f;
  const Eigen::Vector3f u = ab / length;
  // The point of the segment nearest the ray: the line's closest point, clamped.
  float t = 0;
  if (auto approach = closestApproach(ray, a, u)) t = std::clamp(approach->lineParam, 0.0f, length);
  const Eigen::Vector3f q = a + t * u, toQ = q - ray.origin_m;
  const float along = toQ.dot(ray.direction);
  if (along <= 0) return 1e9f;
  return std::atan2((toQ - along * ray.direction).norm(), along);
}

// Where the ray meets the horizontal plane y = height; nothing if it runs along it or away.
std::optional<Eigen::Vector3f> onHorizontalPlane(const ViewRay& ray, float height_m) {
  if (std::abs(ray.direction.y()) < 1e-4f) return std::nullopt;
  const float s = (height_m - ray.origin_m.y()) / ray.direction.y();
  if (s <= 0) return std::nullopt;
  return ray.origin_m + s * ray.direction;
}

Eigen::Vector3f axisOf(GizmoHandle h) {
  return h == GizmoHandle::MoveX ? Eigen::Vector3f::UnitX()
         : h == GizmoHandle::MoveZ ? Eigen::Vector3f::UnitZ()
                                   : Eigen::Vector3f::UnitY();
}

Eigen::Vector3f ringPoint(const GizmoFrame& f, float angle_rad) {
  const float r = kGizmoRingRadius * f.arm_m;
  return f.centre_m + Eigen::Vector3f(r * std::sin(angle_rad), 0, r * std::cos(angle_rad));
}

}  // namespace

const char* gizmoHandleName(GizmoHandle handle) {
  switch (handle) {
    case GizmoHandle::MoveX: return "move_x";
    case GizmoHandle::MoveZ: return "move_z";
    case GizmoHandle::Rotate: return "rotate";
    case GizmoHandle::Scale: return "scale";
    case GizmoHandle::None: break;
  }
  return "none";
}

GizmoFrame gizmoFrameFor(const PlacedObject& object, const Eigen::Vector3f& eye_m) {
  GizmoFrame f;
  f.centre_m = toFloat(object.position_m) + Eigen::Vector3f(0, kLift_m, 0);
  f.arm_m = std::clamp(kGizmoArmPerDistance * (eye_m - f.centre_m).norm(), kGizmoMinArm_m, kGizmoMaxArm_m);
  return f;
}

Eigen::Vector3f gizmoHandlePoint(const GizmoFrame& f, GizmoHandle handle) {
  switch (handle) {
    case GizmoHandle::MoveX:
    case GizmoHandle::MoveZ: return f.centre_m + 0.6f * f.arm_m * axisOf(handle);
    case GizmoHandle::Rotate: return ringPoint(f, 0.25f * kPi);  // between the arrows
    case GizmoHandle::Scale: return f.centre_m + Eigen::Vector3f(0, f.arm_m, 0);
    case GizmoHandle::None: break;
  }
  return f.centre_m;
}

GizmoHandle pickGizmoHandle(const GizmoFrame& f, const ViewRay& ray) {
  GizmoHandle best = GizmoHandle::None;
  float bestAngle = kGizmoPickTolerance_rad;
  auto consider = [&](GizmoHandle h, float angle) {
    if (angle < bestAngle) {
      bestAngle = angle;
      best = h;
    }
  };
  // The arrows from a fifth of the arm out (the centre belongs to no handle).
  for (GizmoHandle h : {GizmoHandle::MoveX, GizmoHandle::MoveZ})
    consider(h, missAngleToSegment(ray, f.centre_m + 0.2f * f.arm_m * axisOf(h), f.centre_m + f.arm_m * axisOf(h)));
  // The post's upper half: the part above the arrows and the ring.
  consider(GizmoHandle::Scale, missAngleToSegment(ray, f.centre_m + Eigen::Vector3f(0, 0.5f * f.arm_m, 0),
                                                   f.centre_m + Eigen::Vector3f(0, 1.1f * f.arm_m, 0)));
  float ring = 1e9f;
  for (int k = 0; k < kRingSegments; ++k)
    ring = std::min(ring, missAngleToSegment(ray, ringPoint(f, 2 * kPi * float(k) / kRingSegments),
                                             ringPoint(f, 2 * kPi * float(k + 1) / kRingSegments)));
  consider(GizmoHandle::Rotate, ring);
  return best;
}

std::optional<GizmoDrag> beginGizmoDrag(GizmoHandle handle, const GizmoFrame& frame, const PlacedObject& object,
                                        const ViewRay& ray) {
  GizmoDrag drag;
  drag.handle = handle;
  drag.frame = frame;
  drag.start = object;
  switch (handle) {
    case GizmoHandle::MoveX:
    case GizmoHandle::MoveZ:
    case GizmoHandle::Scale: {
      auto a = closestApproach(ray, frame.centre_m, axisOf(handle));
      if (!a) return std::nullopt;
      drag.startValue = a->lineParam;
      if (handle == GizmoHandle::Scale && !(drag.startValue > 0.05f * frame.arm_m)) return std::nullopt;
      return drag;
    }
    case GizmoHandle::Rotate: {
      auto p = onHorizontalPlane(ray, frame.centre_m.y());
      if (!p) return std::nullopt;
      const Eigen::Vector3f v = *p - frame.centre_m;
      drag.startValue = std::atan2(v.x(), v.z());
      return drag;
    }
    case GizmoHandle::None: break;
  }
  return std::nullopt;
}

PlacedObject dragGizmo(const GizmoDrag& drag, const ViewRay& ray) {
  PlacedObject o = drag.start;
  switch (drag.handle) {
    case GizmoHandle::MoveX:
    case GizmoHandle::MoveZ: {
      auto a = closestApproach(ray, drag.frame.centre_m, axisOf(drag.handle));
      if (!a) return o;
      const Eigen::Vector3f moved = (a->lineParam - drag.startValue) * axisOf(drag.handle);
      o.position_m.x() += Real(moved.x());
      o.position_m.z() += Real(moved.z());
      return o;
    }
    case GizmoHandle::Rotate: {
      auto p = onHorizontalPlane(ray, drag.frame.centre_m.y());
      if (!p) return o;
      const Eigen::Vector3f v = *p - drag.frame.centre_m;
      // A heading angle grows with yaw: yaw about +Y turns +Z towards +X.
      const double turned = double(std::atan2(v.x(), v.z()) - drag.startValue);
      o.yaw_rad = std::remainder(drag.start.yaw_rad + turned, 2.0 * double(kPi));
      return o;
    }
    case GizmoHandle::Scale: {
      auto a = closestApproach(ray, drag.frame.centre_m, axisOf(drag.handle));
      if (!a) return o;
      const float factor = std::clamp(a->lineParam / drag.startValue, kGizmoMinScale, kGizmoMaxScale);
      o.scale = drag.start.scale * Real(factor);
      return o;
    }
    case GizmoHandle::None: break;
  }
  return o;
}

void addGizmoLines(const GizmoFrame& f, GizmoHandle highlighted, std::vector<render::DebugLine>& lines) {
  auto colour = [&](GizmoHandle h, const Eigen::Vector3f& base) {
    return h == highlighted ? Eigen::Vector3f(1.0f, 1.0f, 0.6f) : base;
  };
  auto add = [&](const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c) {
    render::DebugLine line{a, b, c};
    line.overlay = true;
    lines.push_back(line);
  };
  const float head = 0.15f * f.arm_m;
  for (GizmoHandle h : {GizmoHandle::MoveX, GizmoHandle::MoveZ}) {
    const Eigen::Vector3f u = axisOf(h), side = Eigen::Vector3f::UnitY().cross(u);
    const Eigen::Vector3f c = colour(h, h == GizmoHandle::MoveX ? Eigen::Vector3f(1.0f, 0.15f, 0.1f)
                                                                : Eigen::Vector3f(0.15f, 0.35f, 1.0f));
    const Eigen::Vector3f tip = f.centre_m + f.arm_m * u;
    add(f.centre_m, tip, c);
    add(tip, tip - head * u + 0.5f * head * side, c);
    add(tip, tip - head * u - 0.5f * head * side, c);
    add(tip, tip - head * u + 0.5f * head * Eigen::Vector3f::UnitY(), c);
  }
  const Eigen::Vector3f ring = colour(GizmoHandle::Rotate, {1.0f, 0.8f, 0.1f});
  for (int k = 0; k < kRingSegments; ++k)
    add(ringPoint(f, 2 * kPi * float(k) / kRingSegments), ringPoint(f, 2 * kPi * float(k + 1) / kRingSegments), ring);
  const Eigen::Vector3f post = colour(GizmoHandle::Scale, {0.92f, 0.92f, 0.92f});
  const Eigen::Vector3f top = f.centre_m + Eigen::Vector3f(0, f.arm_m, 0);
  add(f.centre_m, top, post);
  const float s = 0.08f * f.arm_m;  // a small square cap on the post
  const Eigen::Vector3f corners[4] = {top + Eigen::Vector3f(-s, 0, -s), top + Eigen::Vector3f(s, 0, -s),
                                      top + Eigen::Vector3f(s, 0, s), top + Eigen::Vector3f(-s, 0, s)};
  for (int k = 0; k < 4; ++k) add(corners[k], corners[(k + 1) % 4], post);
}

}  // namespace tumble::app
