// Cars as a player sees them (through drive.show, their display meshes with
// wheel arches): the hatchback's tyres show from behind, the truck's from
// the side, and each drawn wheel turns and steers exactly as its simulated
// wheel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include "../render/render_test_util.h"
#include "app/fixed_step.h"
#include "app/scene.h"
#include "render/model.h"
#include "vehicle/vehicle_system.h"

namespace tumble::app {
namespace {

std::unique_ptr<Scene> carScene(const std::string& car = "base:hatchback") {
  const char* source = std::getenv("TUMBLE_SOURCE_DIR");
  SceneOptions options;
  options.scenarioRef = "good:look_car";
  options.sets["car"] = car;
  options.modDirs = {std::string(source ? source : ".") + "/tests/app/mods"};
  auto scene = Scene::create(options);
  EXPECT_TRUE(scene.ok()) << (scene.ok() ? "" : scene.error());
  if (!scene.ok()) return nullptr;
  (*scene)->start();
  return std::move(*scene);
}

void runSteps(Scene& scene, int steps) {
  RunTimings t;
  for (int i = 0; i < steps; ++i) stepScene(scene, StepTime{i * scene.dt_s(), i}, t);
}

// The wheel model drawn at a hub: the instance nearest to it.
const render::ModelInstance* wheelAt(const render::FrameSnapshot& frame, const Eigen::Vector3f& hub) {
  const render::ModelInstance* best = nullptr;
  for (const render::ModelInstance& m : frame.models)
    if (!best || (m.position - hub).norm() < (best->position - hub).norm()) best = &m;
  return best && (best->position - hub).norm() < 1e-3f ? best : nullptr;
}

TEST(LookCar, TheDrawnWheelsTurnAndSteerWithTheSimulatedOnes) {
  auto scene = carScene();
  ASSERT_TRUE(scene);
  const vehicle::VehicleSystem* vehicles = scene->vehiclesIfAny();
  ASSERT_NE(vehicles, nullptr);
  vehicle::VehicleId car;
  vehicles->forEach([&](vehicle::VehicleId id) { car = id; });
  ASSERT_EQ(vehicles->wheelCount(car), 4);
  for (int checkpoint = 0; checkpoint < 3; ++checkpoint) {
    runSteps(*scene, 40);
    scene->savePreviousState();  // alpha = 1 below: the step's end, no interpolation
    render::FrameSnapshot frame;
    scene->snapshot(frame, 1.0);
    const Eigen::Quaternionf chassis = scene->world().body(vehicles->chassis(car)).orientation.cast<float>();
    for (int i = 0; i < 4; ++i) {
      const vehicle::WheelTelemetry& w = vehicles->wheel(car, i);
      const render::ModelInstance* drawn = wheelAt(frame, w.hub_m.cast<float>());
      ASSERT_NE(drawn, nullptr) << "wheel " << i << " drawn at its hub";
      // Undo the chassis and the steering: what is left is the spin about the axle (X).
      const Eigen::Quaternionf steer(Eigen::AngleAxisf(float(w.steer_rad), Eigen::Vector3f::UnitY()));
      const Eigen::Quaternionf spin = (chassis * steer).conjugate() * drawn->orientation;
      EXPECT_NEAR(spin.vec().y(), 0.0f, 1e-4f);
      EXPECT_NEAR(spin.vec().z(), 0.0f, 1e-4f);
      const float drawnAngle = 2.0f * std::atan2(spin.x(), spin.w());
      const float simulated = float(std::remainder(double(w.rotation_rad), 2 * kPi));
      EXPECT_NEAR(std::remainder(double(drawnAngle - simulated), 2 * kPi), 0.0, 1e-3)
          << "wheel " << i << " at step " << (checkpoint + 1) * 40;
    }
  }
  // Past half a turn, so the comparison above went through the angle's wrap.
  EXPECT_GT(std::abs(vehicles->wheel(car, 0).rotation_rad), kPi) << "the car rolled: the wheels turned";
}

// The car seen from `yaw_rad` (0: from the front, pi: from behind) and
// `pitch_rad` above, `distance_m` from the chassis, drawn with its display
// mesh and with the plain solid `plainModel` (the mod's inertia mesh) in its
// place: the pixels of each frame that pass `count`. The wheels are tinted
// green in both frames so their pixels are told from the black bumpers and
// wells.
std::pair<int, int> carPixels(const std::string& car, const std::string& plainModel, float yaw_rad, float pitch_rad,
                              float distance_m, const std::string& tag, const std::function<bool(int, int, int)>& count) {
  auto scene = carScene(car);
  if (!scene) return {-1, -1};
  runSteps(*scene, 30);  // settled on its springs
  scene->savePreviousState();
  render::FrameSnapshot shaped;
  scene->snapshot(shaped, 1.0);
  const vehicle::VehicleSystem* vehicles = scene->vehiclesIfAny();
  EXPECT_NE(vehicles, nullptr);
  if (!vehicles) return {-1, -1};
  vehicle::VehicleId id;
  vehicles->forEach([&](vehicle::VehicleId v) { id = v; });
  const physics::Body& chassis = scene->world().body(vehicles->chassis(id));
  int wheels = 0, bodies = 0;
  render::FrameSnapshot plain = shaped;
  for (std::size_t k = 0; k < shaped.models.size(); ++k) {
    bool isWheel = false;
    for (int i = 0; i < vehicles->wheelCount(id); ++i)
      isWheel |= (shaped.models[k].position - vehicles->wheel(id, i).hub_m.cast<float>()).norm() < 1e-3f;
    if (isWheel) {
      shaped.models[k].tint = plain.models[k].tint = {0.0f, 6.0f, 0.0f};  // dark rubber -> clearly green
      ++wheels;
      continue;
    }
    // The chassis' model: the same placement with the plain body.
    const char* source = std::getenv("TUMBLE_SOURCE_DIR");
    auto solid = render::loadModel(std::string(source ? source : ".") + "/mods/base/assets/models/" + plainModel);
    EXPECT_TRUE(solid.ok()) << (solid.ok() ? "" : solid.error());
    if (!solid.ok()) return {-1, -1};
    plain.models[k].model = *solid;
    ++bodies;
  }
  EXPECT_EQ(wheels, 4);
  EXPECT_EQ(bodies, 1);
  constexpr int kW = 640, kH = 360;
  auto renderer = render::test::makeOffscreenRenderer(kW, kH, /*hud=*/false);
  EXPECT_NE(renderer, nullptr) << "no OpenGL: offscreen rendering must work here";
  if (!renderer) return {-1, -1};
  render::Camera& camera = renderer->camera();
  camera.target = chassis.position_m.cast<float>();
  camera.yaw_rad = yaw_rad;
  camera.pitch_rad = pitch_rad;
  camera.distance_m = distance_m;
  render::test::ScratchDir scratch;
  auto shot = [&](const render::FrameSnapshot& frame, const std::string& name) {
    render::Controls controls;
    const std::string path = scratch.file(name);
    EXPECT_TRUE(renderer->drawFrame(frame, render::HudStats{}, controls, path.c_str()).ok());
    return render::test::loadPng(path);
  };
  const int seenShaped = render::test::countPixels(shot(shaped, tag + "_shaped.png"), count);
  const int seenPlain = render::test::countPixels(shot(plain, tag + "_plain.png"), count);
  std::printf("[look] %s: %d pixels with the display mesh, %d with the plain solid\n", tag.c_str(), seenShaped,
              seenPlain);
  return {seenShaped, seenPlain};
}

// From behind and above, as the chase camera sees the car: the drawn body
// (display mesh, rear tucked in, wheel arches) lets the rear tyres show;
// the plain solid the inertia comes from hides them. Behind the car (it
// faces +Z), 2.2 m above the chassis, 6.5 m back: the chase camera's offset
// (render::CameraRig).
TEST(LookCar, TyresShowFromBehind) {
  auto green = [](int r, int g, int b) { return g > r + 12 && g > b + 12; };
  const auto [shaped, plain] = carPixels("base:hatchback", "hatchback.obj", float(kPi), std::atan2(2.2f, 6.5f),
                                         std::hypot(2.2f, 6.5f), "hatchback_tyres", green);
  EXPECT_GT(shaped, 100) << "the rear tyres show beside and below the tucked-in rear";
  EXPECT_GT(shaped, 4 * plain + 50) << "the plain body hides them (" << plain << " px)";
}

// The truck from the side, a little above, as a passer-by sees it. Its
// tyres stand 6 cm out from the body, so they show either way; the drawn
// body has arches over them, black wells between each tyre's top and the
// arch (0.84 to 0.92 m up, 1.16 m long), where the plain body (its inertia
// solid) is green paint down to 0.62 m. At 8 m on 640 x 360 (about 40 px
// per metre) the two arches in view are a few hundred pixels of near-black
// (measured: 515 more than the plain body's bumpers and shadows).
TEST(LookCar, TruckHasWheelArchesOverItsTyres) {
  auto green = [](int r, int g, int b) { return g > r + 12 && g > b + 12 && g > 100; };
  auto black = [](int r, int g, int b) { return r < 40 && g < 40 && b < 40; };
  const auto [tyresShaped, tyresPlain] = carPixels("base:truck", "truck.obj", float(kPi) / 2, 0.15f, 8.0f, "truck_tyres", green);
  EXPECT_GT(tyresShaped, 1000) << "the tyres show from the side";
  EXPECT_GT(tyresShaped, tyresPlain * 9 / 10) << "the arches hide nothing of them";
  const auto [wellsShaped, wellsPlain] = carPixels("base:truck", "truck.obj", float(kPi) / 2, 0.15f, 8.0f, "truck_wells", black);
  EXPECT_GT(wellsShaped, wellsPlain + 150) << "the arches' black wells show over the tyres";
}

}  // namespace
}  // namespace tumble::app
