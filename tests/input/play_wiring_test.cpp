// Play's wiring, with a real (offscreen) window and HUD: SDL events reach
// the input system through the renderer's hook, bound keys are consumed so
// the renderer does not act on them twice, unbound ones still drive the
// camera and debug keys, and F1 opens the bindings menu inside the HUD.
#include <SDL.h>

#include <cmath>

#include "app/bindings_menu.h"
#include "input/overrides_file.h"
#include "input_fixture.h"
#include "script/mod_bindings.h"

namespace tumble::test {

namespace {

void pushKey(SDL_Scancode sc) {
  SDL_Event e = keyEvent(sc, true);
  e.key.keysym.sym = SDL_GetKeyFromScancode(sc);
  ASSERT_EQ(SDL_PushEvent(&e), 1) << SDL_GetError();
  e.type = SDL_KEYUP;
  ASSERT_EQ(SDL_PushEvent(&e), 1) << SDL_GetError();
}

class PlayWiring : public ::testing::Test {
 protected:
  void SetUp() override {
    ::setenv("SDL_VIDEODRIVER", "offscreen", 1);
    render::WindowConfig config;
    config.width = 320;
    config.height = 240;
    config.forceOffscreen = true;
    auto r = render::Renderer::create(config);
    ASSERT_TRUE(r) << r.error();
    m_renderer = std::move(*r);
    script::ModInfo base;
    base.name = "base";
    base.dir = std::string(TUMBLE_SOURCE_DIR) + "/mods/base";
    m_input = std::make_unique<input::InputSystem>(script::loadModBindings(base).set);
    m_configPath = (testDir() / "bindings.json").string();
    m_menu = std::make_unique<app::BindingsMenu>(*m_input, m_configPath);
    m_renderer->setEventHook([this](const SDL_Event& e, bool hudWants) { return m_input->handleEvent(e, hudWants); });
    m_renderer->addHudPanel([this] { m_menu->draw(); });
  }

  void frame() {
    m_renderer->processEvents(m_controls);
    app::applyFrameInput(*m_input, *m_menu, m_controls, *m_renderer);
  }

  std::unique_ptr<render::Renderer> m_renderer;
  std::unique_ptr<input::InputSystem> m_input;
  std::unique_ptr<app::BindingsMenu> m_menu;
  render::Controls m_controls;
  std::string m_configPath;
};

TEST_F(PlayWiring, PauseIsAnActionThatTogglesOncePerPress) {
  pushKey(SDL_SCANCODE_P);
  frame();
  EXPECT_TRUE(m_controls.paused) << "once, not toggled back by the renderer's own P";
  pushKey(SDL_SCANCODE_P);
  frame();
  EXPECT_FALSE(m_controls.paused) << "unpauses although no fixed step ran";
}

TEST_F(PlayWiring, TheCameraKeyWorksWithAndWithoutTheVehicleContext) {
  pushKey(SDL_SCANCODE_C);
  frame();
  EXPECT_EQ(m_renderer->camera().mode, render::CameraMode::Follow) << "vehicle off: the renderer's C";
  ASSERT_TRUE(m_input->setContextEnabled("vehicle", true));
  pushKey(SDL_SCANCODE_C);
  frame();
  EXPECT_EQ(m_renderer->camera().mode, render::CameraMode::Orbit) << "vehicle on: the camera action, once";
}

TEST_F(PlayWiring, GameplayKeysReachTheActionsAndDebugKeysTheRenderer) {
  ASSERT_TRUE(m_input->setContextEnabled("vehicle", true));
  SDL_Event w = keyEvent(SDL_SCANCODE_W, true);
  ASSERT_EQ(SDL_PushEvent(&w), 1);
  pushKey(SDL_SCANCODE_N);  // single step stays a renderer key
  frame();
  m_input->step();
  EXPECT_TRUE(m_input->pressed(m_input->find("throttle")));
  EXPECT_TRUE(m_controls.stepOnce);
}

TEST_F(PlayWiring, F1OpensTheBindingsMenuAndTheHudDrawsIt) {
  pushKey(SDL_SCANCODE_F1);
  frame();
  EXPECT_TRUE(m_menu->isOpen());
  EXPECT_TRUE(m_controls.paused) << "the game waits while the player rebinds";
  render::FrameSnapshot snap;
  render::HudStats hud;
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(m_renderer->drawFrame(snap, hud, m_controls));
  pushKey(SDL_SCANCODE_F1);
  frame();
  EXPECT_FALSE(m_menu->isOpen());
  EXPECT_FALSE(m_controls.paused) << "and resumes as it was";
}

TEST_F(PlayWiring, APlayerRebindsInTheMenuAndSavesOnlyTheChanges) {
  pushKey(SDL_SCANCODE_F1);
  frame();
  ASSERT_TRUE(m_menu->isOpen());
  render::FrameSnapshot snap;
  render::HudStats hud;
  auto draw = [&] { ASSERT_TRUE(m_renderer->drawFrame(snap, hud, m_controls)); };
  const int throttle = m_input->find("throttle"), steer = m_input->find("steer");

  m_menu->rebind(throttle, 0);  // click on "W"
  pushKey(SDL_SCANCODE_I);
  frame();
  draw();
  EXPECT_FALSE(m_menu->rebinding());
  EXPECT_EQ(input::toText(m_input->bindings(throttle)[0]), "key:I");
  m_input->step();
  EXPECT_FALSE(m_input->down(throttle)) << "the key pressed to rebind did not drive the game";

  m_menu->rebind(steer, 0);  // an axis: two keys, - then +
  pushKey(SDL_SCANCODE_J);
  frame();
  draw();
  EXPECT_TRUE(m_menu->rebinding()) << "waits for the + key";
  pushKey(SDL_SCANCODE_L);
  frame();
  draw();
  EXPECT_EQ(input::toText(m_input->bindings(steer)[0]), "keys:J/L");

  m_menu->rebind(steer, 2);  // the stick: push the right stick instead; its dead zone stays
  m_input->handleEvent(padAxisEvent(SDL_CONTROLLER_AXIS_RIGHTX, -30000), false);
  draw();
  EXPECT_EQ(input::toText(m_input->bindings(steer)[2]), "pad_axis:rightx;dead_zone=0.15;curve=1.5");

  m_menu->rebind(throttle, -1);  // Escape cancels
  pushKey(SDL_SCANCODE_ESCAPE);
  frame();
  draw();
  EXPECT_FALSE(m_controls.quitRequested) << "Escape cancelled the capture and did not quit";
  EXPECT_EQ(m_input->bindings(throttle).size(), 3u);

  ASSERT_TRUE(m_menu->save());
  auto saved = input::loadOverrides(m_configPath);
  ASSERT_TRUE(saved) << saved.error();
  ASSERT_EQ(saved->size(), 2u) << "throttle and steer only";
  ASSERT_EQ(saved->count("throttle"), 1u);
  EXPECT_EQ(saved->at("throttle").at(0), "key:I");
}

TEST_F(PlayWiring, ThePointerRayStartsAtTheEyeAndPointsAtTheCameraTargetFromTheCentre) {
  EXPECT_FALSE(m_input->pointerRay()) << "no pointer yet";
  m_input->setPointer(0, 0);  // the centre of the view
  frame();
  auto ray = m_input->pointerRay();
  ASSERT_TRUE(ray);
  const render::Camera& cam = m_renderer->camera();
  const Eigen::Vector3f eye = cam.target + cam.distance_m * Eigen::Vector3f(std::cos(cam.pitch_rad) * std::sin(cam.yaw_rad),
                                                                           std::sin(cam.pitch_rad),
                                                                           std::cos(cam.pitch_rad) * std::cos(cam.yaw_rad));
  EXPECT_LT((ray->origin_m.cast<float>() - eye).norm(), 1e-4f);
  const Eigen::Vector3f toTarget = (cam.target - eye).normalized();
  EXPECT_GT(ray->direction.cast<float>().dot(toTarget), 0.99999f);
  m_input->setPointer(1, 0);  // the right edge: half the horizontal field of view away
  frame();
  const float aspect = 320.0f / 240.0f;
  const float halfFovX = std::atan(std::tan(cam.fovY_rad / 2) * aspect);
  EXPECT_NEAR(std::acos(m_input->pointerRay()->direction.cast<float>().dot(toTarget)), halfFovX, 1e-4f);
}

}  // namespace
}  // namespace tumble::test
