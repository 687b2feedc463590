// The designer's gizmo as geometry (app/designer_gizmo.h): rays from the eye
// through a handle pick it, and dragging the pointer moves, turns or scales
// the object by exactly what the pointer's travel says, from near and far
// eyes, low and steep views alike.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "app/designer_gizmo.h"

namespace tumble::app {
namespace {

constexpr double kPi = 3.14159265358979323846;

ViewRay rayThrough(const Eigen::Vector3f& eye, const Eigen::Vector3f& point) {
  return ViewRay{eye, (point - eye).normalized()};
}

PlacedObject rockAt(double x, double z, double yaw_rad = 0.3) {
  PlacedObject o;
  o.kind = PlacedKind::Model;
  o.asset = "base:assets/models/rock.obj";
  o.position_m = Vec3(Real(x), Real(2.5), Real(z));
  o.yaw_rad = yaw_rad;
  o.scale = Vec3(1.5, 1.5, 1.5);
  return o;
}

// Eyes a player uses: low and near, high and steep, far away, and from the
// other sides of the object.
std::vector<Eigen::Vector3f> eyesAround(const Eigen::Vector3f& centre) {
  return {centre + Eigen::Vector3f(-12, 6, -20), centre + Eigen::Vector3f(3, 60, -8),
          centre + Eigen::Vector3f(250, 120, 300), centre + Eigen::Vector3f(15, 4, 18)};
}

TEST(DesignerGizmo, ARayThroughEachHandlePicksItAndARayBesideThemPicksNone) {
  const PlacedObject rock = rockAt(40, -15);
  for (const Eigen::Vector3f& eye : eyesAround(Eigen::Vector3f(40, 2.5f, -15))) {
    const GizmoFrame frame = gizmoFrameFor(rock, eye);
    for (GizmoHandle h : {GizmoHandle::MoveX, GizmoHandle::MoveZ, GizmoHandle::Rotate, GizmoHandle::Scale})
      EXPECT_EQ(pickGizmoHandle(frame, rayThrough(eye, gizmoHandlePoint(frame, h))), h)
          << gizmoHandleName(h) << " from " << eye.transpose();
    // The handles span about atan(1.1 x 0.15) = 0.16 rad around the centre
    // as seen from the eye: rays 0.4 rad off the centre pick nothing.
    const Eigen::Vector3f toCentre = (frame.centre_m - eye).normalized();
    const Eigen::Vector3f across = toCentre.cross(Eigen::Vector3f::UnitY()).normalized();
    const Eigen::Vector3f upward = across.cross(toCentre).normalized();
    for (const Eigen::Vector3f& axis : {across, upward, Eigen::Vector3f(-across), Eigen::Vector3f(-upward)})
      EXPECT_EQ(pickGizmoHandle(frame, ViewRay{eye, Eigen::AngleAxisf(0.4f, axis) * toCentre}), GizmoHandle::None)
          << eye.transpose();
    // The arm keeps the handles the same size on screen: a fixed fraction of the distance.
    EXPECT_NEAR(frame.arm_m / (eye - frame.centre_m).norm(), kGizmoArmPerDistance,
                kGizmoArmPerDistance * 0.01 + kGizmoMinArm_m / (eye - frame.centre_m).norm());
  }
}

TEST(DesignerGizmo, DraggingAnArrowMovesTheObjectByThePointersTravelAlongItsAxisOnly) {
  const PlacedObject rock = rockAt(40, -15);
  for (const Eigen::Vector3f& eye : eyesAround(Eigen::Vector3f(40, 2.5f, -15))) {
    const GizmoFrame frame = gizmoFrameFor(rock, eye);
    for (GizmoHandle h : {GizmoHandle::MoveX, GizmoHandle::MoveZ}) {
      const Eigen::Vector3f axis = h == GizmoHandle::MoveX ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitZ();
      const Eigen::Vector3f grab = gizmoHandlePoint(frame, h);
      auto drag = beginGizmoDrag(h, frame, rock, rayThrough(eye, grab));
      ASSERT_TRUE(drag) << gizmoHandleName(h);
      for (float travel_m : {3.0f, -7.5f, 0.25f}) {
        const PlacedObject moved = dragGizmo(*drag, rayThrough(eye, grab + travel_m * axis));
        const double tolerance_m = 1e-4 * (eye - grab).norm();
        EXPECT_NEAR(double(moved.position_m.x() - rock.position_m.x()), double(travel_m * axis.x()), tolerance_m);
        EXPECT_NEAR(double(moved.position_m.z() - rock.position_m.z()), double(travel_m * axis.z()), tolerance_m);
        EXPECT_EQ(moved.yaw_rad, rock.yaw_rad);
        EXPECT_EQ(moved.scale, rock.scale);
      }
    }
  }
}

TEST(DesignerGizmo, DraggingAnArrowWithThePointerOffItFollowsTheNearestPointOnTheAxis) {
  // The eye straight above a point 4 m along X and 2 m beside the axis: the
  // pointer's ray there is vertical, so the axis point nearest it is 4 m on,
  // and the object moves 4 m in X and none in Z.
  const PlacedObject rock = rockAt(0, 0);
  GizmoFrame frame = gizmoFrameFor(rock, Eigen::Vector3f(0, 40, 0));
  const Eigen::Vector3f grab = gizmoHandlePoint(frame, GizmoHandle::MoveX);
  const Eigen::Vector3f eye = grab + Eigen::Vector3f(4, 40, 2);
  frame = gizmoFrameFor(rock, eye);
  auto drag = beginGizmoDrag(GizmoHandle::MoveX, frame, rock, rayThrough(eye, grab));
  ASSERT_TRUE(drag);
  const PlacedObject moved = dragGizmo(*drag, ViewRay{eye, -Eigen::Vector3f::UnitY()});
  EXPECT_NEAR(double(moved.position_m.x()), 4.0, 1e-4);
  EXPECT_EQ(moved.position_m.z(), rock.position_m.z());
}

TEST(DesignerGizmo, DraggingTheRingTurnsTheObjectByTheAngleThePointerSweeps) {
  const PlacedObject rock = rockAt(-30, 12, 2.9);  // near +180 degrees: the result wraps
  for (const Eigen::Vector3f& eye : eyesAround(Eigen::Vector3f(-30, 2.5f, 12))) {
    const GizmoFrame frame = gizmoFrameFor(rock, eye);
    const float r = kGizmoRingRadius * frame.arm_m;
    auto ringAt = [&](double heading) -> Eigen::Vector3f {
      return frame.centre_m + Eigen::Vector3f(r * float(std::sin(heading)), 0, r * float(std::cos(heading)));
    };
    auto drag = beginGizmoDrag(GizmoHandle::Rotate, frame, rock, rayThrough(eye, ringAt(kPi / 2)));
    ASSERT_TRUE(drag) << eye.transpose();
    for (double swept : {0.7, -1.2, 2.5}) {
      const PlacedObject turned = dragGizmo(*drag, rayThrough(eye, ringAt(kPi / 2 + swept)));
      const double expected = std::remainder(rock.yaw_rad + swept, 2 * kPi);
      EXPECT_NEAR(std::remainder(turned.yaw_rad - expected, 2 * kPi), 0.0, 1e-4) << swept << " from " << eye.transpose();
      EXPECT_LE(std::abs(turned.yaw_rad), kPi);
      EXPECT_EQ(turned.position_m, rock.position_m);
    }
  }
}

TEST(DesignerGizmo, DraggingThePostScalesByTheRatioOfItsHeightsWithinLimits) {
  const PlacedObject rock = rockAt(5, 5);
  for (const Eigen::Vector3f& eye : eyesAround(Eigen::Vector3f(5, 2.5f, 5))) {
    const GizmoFrame frame = gizmoFrameFor(rock, eye);
    const Eigen::Vector3f top = gizmoHandlePoint(frame, GizmoHandle::Scale);
    auto drag = beginGizmoDrag(GizmoHandle::Scale, frame, rock, rayThrough(eye, top));
    ASSERT_TRUE(drag);
    for (float factor : {2.0f, 0.5f, 1.3f}) {
      const Eigen::Vector3f to = frame.centre_m + Eigen::Vector3f(0, factor * frame.arm_m, 0);
      const PlacedObject scaled = dragGizmo(*drag, rayThrough(eye, to));
      EXPECT_NEAR(double(scaled.scale.x()), double(rock.scale.x()) * factor, 1e-3 * factor) << eye.transpose();
      EXPECT_NEAR(double(scaled.scale.y() / scaled.scale.x()), 1.0, 1e-9) << "the shape keeps its proportions";
      EXPECT_EQ(scaled.position_m, rock.position_m);
    }
    // Below the centre: the smallest factor, never zero or negative.
    const PlacedObject smallest = dragGizmo(*drag, rayThrough(eye, frame.centre_m - Eigen::Vector3f(0, frame.arm_m, 0)));
    EXPECT_NEAR(double(smallest.scale.x()), double(rock.scale.x()) * kGizmoMinScale, 1e-6);
  }
}

TEST(DesignerGizmo, ARayParallelToWhatAHandleMovesOnStartsNoDragAndLeavesTheObjectAlone) {
  const PlacedObject rock = rockAt(0, 0);
  const GizmoFrame frame = gizmoFrameFor(rock, Eigen::Vector3f(0, 0.3f, -20));
  // Level with the ring's plane: no point on it to turn by.
  const ViewRay level{Eigen::Vector3f(0, frame.centre_m.y(), -20), Eigen::Vector3f::UnitZ()};
  EXPECT_FALSE(beginGizmoDrag(GizmoHandle::Rotate, frame, rock, level));
  // Along the Z arrow itself.
  EXPECT_FALSE(beginGizmoDrag(GizmoHandle::MoveZ, frame, rock, level));
  // A drag that started, then a ray along its axis: unchanged.
  const Eigen::Vector3f eye(-10, 8, -10);
  auto drag = beginGizmoDrag(GizmoHandle::MoveX, frame, rock, rayThrough(eye, gizmoHandlePoint(frame, GizmoHandle::MoveX)));
  ASSERT_TRUE(drag);
  EXPECT_EQ(dragGizmo(*drag, ViewRay{eye, Eigen::Vector3f::UnitX()}), rock);
}

}  // namespace
}  // namespace tumble::app
