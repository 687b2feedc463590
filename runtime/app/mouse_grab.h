#pragma once
// Mouse picking and dragging (the rag-doll paper's hands): the ray from the camera
// through a pixel, and a grab that holds the picked body point on a spring
// (physics::makeGrabDef) to the point under the cursor at the depth where
// it was picked. The input actions (grab pressed / dragged / released) come
// from the input bindings; the app calls begin / drag / end with the cursor.
#include "core/math.h"
#include "physics/joints/joint_system.h"
#include "physics/world.h"
#include "render/renderer.h"

namespace tumble::app {

struct PickRay {
  Vec3 origin_m = Vec3::Zero();
  Vec3 dir = -Vec3::UnitZ();  ///< unit
};

/// The ray from the camera's eye through pixel (x_px, y_px) of a
/// width x height view (origin top-left, y down), with the camera model of
/// render::Camera (eye on the orbit sphere, looking at target, Y up).
PickRay cameraRay(const render::Camera& camera, double x_px, double y_px, int width, int height);

class MouseGrab {
 public:
  /// Picks the nearest dynamic body along the ray (up to 1 km) and grabs it
  /// at the hit point. False when nothing dynamic was hit.
  bool begin(physics::World& world, physics::JointSystem& joints, const PickRay& ray);
  /// Moves the target to the point on the ray at the picking depth.
  void drag(physics::JointSystem& joints, const PickRay& ray);
  /// Lets go (also when the body or the joint is gone).
  void end(physics::JointSystem& joints);
  bool active() const { return !m_joint.isNull(); }
  physics::BodyId body() const { return m_body; }

 private:
  physics::JointId m_joint;
  physics::BodyId m_body;
  Real m_depth_m = 0;  ///< distance along the ray where the body was picked
};

}  // namespace tumble::app
