// Mouse picking: the camera ray through the centre of the view hits what the
// camera looks at, and a grab dragged upwards lifts the picked body.
#include <gtest/gtest.h>

#include "app/mouse_grab.h"

namespace tumble::app {
namespace {

TEST(MouseGrab, CentreRayGoesFromTheEyeToTheTarget) {
  render::Camera cam;
  cam.target = Eigen::Vector3f(1, 2, 3);
  const PickRay r = cameraRay(cam, 399.5, 299.5, 800, 600);  // the centre pixel
  const Vec3 toTarget = cam.target.cast<Real>() - r.origin_m;
  EXPECT_NEAR(toTarget.norm(), cam.distance_m, 1e-3);
  EXPECT_NEAR(r.dir.dot(toTarget.normalized()), 1, 1e-5);
  // A pixel right of the centre looks to the camera's right (x-z plane), one above looks up.
  const PickRay right = cameraRay(cam, 700, 299.5, 800, 600), up = cameraRay(cam, 399.5, 50, 800, 600);
  EXPECT_GT(right.dir.cross(r.dir).y(), 0) << "right of the view turns clockwise seen from above";
  EXPECT_GT(up.dir.y(), r.dir.y());
}

TEST(MouseGrab, PickedBoxFollowsTheCursorUpAndIsLetGo) {
  for (auto solver : {physics::JointSolverKind::Lagrange, physics::JointSolverKind::Impulse}) {
    physics::World world;
    physics::JointSettings js;
    js.solver = solver;
    physics::JointSystem joints(world, js);
    physics::BodyDef ground;
    ground.type = physics::BodyType::Static;
    ground.shape = physics::Shape::plane();
    (void)world.createBody(ground).value();
    physics::BodyDef box;
    box.shape = physics::Shape::box(Vec3::Constant(Real(0.5)));
    box.position_m = Vec3(0, Real(0.5), 0);
    box.mass_kg = 20;
    const physics::BodyId b = world.createBody(box).value();
    render::Camera cam;
    cam.target = Eigen::Vector3f(0, 0.5f, 0);
    MouseGrab grab;
    ASSERT_TRUE(grab.begin(world, joints, cameraRay(cam, 399.5, 299.5, 800, 600)));
    EXPECT_EQ(grab.body(), b);
    // Drag the cursor up by 100 pixels: the target rises about 1.3 m.
    for (int i = 0; i < 120; ++i) {
      grab.drag(joints, cameraRay(cam, 399.5, 199.5, 800, 600));
      joints.step(Real(1.0 / 60));
    }
    EXPECT_GT(world.body(b).position_m.y(), 1.2) << physics::jointSolverName(solver);
    grab.end(joints);
    EXPECT_FALSE(grab.active());
    EXPECT_EQ(joints.jointCount(), 0);
    // Let go, it falls back to the ground (it may land on an edge: y < 0.8 m).
    for (int i = 0; i < 120; ++i) joints.step(Real(1.0 / 60));
    EXPECT_LT(world.body(b).position_m.y(), 0.8) << physics::jointSolverName(solver);
  }
}

}  // namespace
}  // namespace tumble::app
