// drive.show (scripts/tumble/drive.lua) draws a car's chassis mesh where
// the physics car is: for the three base cars standing still on flat
// ground (tests/vehicle/mods/vtest/scenarios/show.lua), the model's ground
// (its y = 0 plane) passes through the tyres' contact points, and the
// chassis box sits inside the drawn body. Read from the frame snapshot the
// renderer draws, in process.
#include <gtest/gtest.h>

#include <cstdlib>

#include "app/fixed_step.h"
#include "app/scene.h"
#include "app/scene_models.h"
#include "render/model.h"
#include "vehicle/vehicle_system.h"

namespace tumble::app {
namespace {

TEST(DriveShow, ChassisModelsStandOnTheTyresContactPoints) {
  const char* source = std::getenv("TUMBLE_SOURCE_DIR");
  SceneOptions options;
  options.scenarioRef = "vtest:show";
  options.modDirs = {std::string(source ? source : ".") + "/tests/vehicle/mods"};
  auto created = Scene::create(options);
  ASSERT_TRUE(created.ok()) << created.error();
  Scene& scene = **created;
  scene.start();
  const double dt = scene.dt_s();
  RunTimings timings;
  for (int step = 0; step < 150; ++step) {  // 2.5 s: the springs settle
    scene.savePreviousState();
    stepScene(scene, StepTime{step * dt, step}, timings);
  }
  scene.savePreviousState();
  render::FrameSnapshot frame;
  scene.snapshot(frame, 1.0);
  const vehicle::VehicleSystem* vehicles = scene.vehiclesIfAny();
  ASSERT_NE(vehicles, nullptr);
  int checked = 0;
  vehicles->forEach([&](vehicle::VehicleId id) {
    const physics::Body& chassis = scene.world().body(vehicles->chassis(id));
    const std::string name = vehicles->def(id).name;
    ASSERT_LT(chassis.linearVelocity_mps.norm(), 0.01) << name << " is at rest";
    // The chassis model: the model drive.show put on the chassis body, as drawn.
    std::string file;
    for (const script::ModelAttachment& a : scene.host().presentation().attachments)
      if (a.body == vehicles->chassis(id)) file = a.file;
    ASSERT_FALSE(file.empty()) << name << " has no model";
    auto model = scene.models().get(file);
    ASSERT_TRUE(model.ok()) << model.error();
    const render::ModelInstance* drawn = nullptr;
    for (const render::ModelInstance& m : frame.models)
      if (m.model == *model) drawn = &m;
    ASSERT_NE(drawn, nullptr) << name;
    const Quat q = drawn->orientation.cast<Real>();
    auto toModel = [&](const Vec3& world) {
      return Vec3((q.conjugate() * (world - drawn->position.cast<Real>())).cwiseQuotient(drawn->scale.cast<Real>()));
    };
    for (int i = 0; i < vehicles->wheelCount(id); ++i) {
      const vehicle::WheelTelemetry& w = vehicles->wheel(id, i);
      ASSERT_TRUE(w.contact) << name << " wheel " << i;
      EXPECT_NEAR(w.contactPoint_m.y(), 0, 0.01) << name << " wheel " << i << " stands on the plane";
      // The model's ground is y = 0 in its own frame: 1 cm tolerance (the
      // springs settle to within a millimetre; the fit through the axles is exact for two).
      EXPECT_NEAR(toModel(w.contactPoint_m).y(), 0, 0.01) << name << " wheel " << i << ": drawn ground vs contact";
    }
    // The chassis box centre lies inside the drawn body's bounds.
    const Vec3 centre = toModel(chassis.position_m - chassis.orientation * vehicles->def(id).chassis.centerOfMass_m);
    const render::BoundingBox& bounds = drawn->model->nodes[0].coverBox;
    EXPECT_TRUE((centre.cast<float>().array() > bounds.min.array()).all() &&
                (centre.cast<float>().array() < bounds.max.array()).all())
        << name << ": chassis box centre " << centre.transpose() << " outside the drawn body";
    ++checked;
  });
  EXPECT_EQ(checked, 3);
}

}  // namespace
}  // namespace tumble::app
