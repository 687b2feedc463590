// Keys, window events and the mouse reach Controls and the camera through
// Renderer::processEvents. Events are pushed into SDL's queue exactly as the
// video driver would deliver them.
#include <SDL.h>
#include <gtest/gtest.h>

#include "render/renderer.h"
#include "render_test_util.h"

namespace tumble::render {
namespace {

void pushKey(SDL_Keycode key) {
  SDL_Event event{};
  event.type = SDL_KEYDOWN;
  event.key.state = SDL_PRESSED;
  event.key.keysym.sym = key;
  event.key.keysym.scancode = SDL_GetScancodeFromKey(key);
  ASSERT_EQ(SDL_PushEvent(&event), 1) << SDL_GetError();
  event.type = SDL_KEYUP;
  event.key.state = SDL_RELEASED;
  ASSERT_EQ(SDL_PushEvent(&event), 1) << SDL_GetError();
}

class RenderControls : public ::testing::Test {
 protected:
  void SetUp() override {
    // With the HUD, so key events also pass through ImGui on their way.
    m_renderer = test::makeOffscreenRenderer(320, 240, /*hud=*/true);
    ASSERT_NE(m_renderer, nullptr);
  }
  std::unique_ptr<Renderer> m_renderer;
  Controls m_controls;
};

TEST_F(RenderControls, PauseKeysToggle) {
  pushKey(SDLK_p);
  m_renderer->processEvents(m_controls);
  EXPECT_TRUE(m_controls.paused);
  pushKey(SDLK_SPACE);
  m_renderer->processEvents(m_controls);
  EXPECT_FALSE(m_controls.paused);
}

TEST_F(RenderControls, StepSlowMotionScreenshotAndCameraKeys) {
  pushKey(SDLK_n);
  pushKey(SDLK_MINUS);
  pushKey(SDLK_MINUS);
  pushKey(SDLK_F12);
  pushKey(SDLK_c);
  m_renderer->processEvents(m_controls);
  EXPECT_TRUE(m_controls.stepOnce);
  EXPECT_TRUE(m_controls.paused);
  EXPECT_FLOAT_EQ(m_controls.timeScale, 0.25f);
  EXPECT_TRUE(m_controls.screenshotRequested);
  EXPECT_EQ(m_renderer->camera().mode, CameraMode::Follow);
  EXPECT_FALSE(m_controls.quitRequested);

  pushKey(SDLK_EQUALS);
  pushKey(SDLK_c);
  m_renderer->processEvents(m_controls);
  EXPECT_FLOAT_EQ(m_controls.timeScale, 0.5f);
  EXPECT_EQ(m_renderer->camera().mode, CameraMode::Orbit);
}

TEST_F(RenderControls, F3TogglesTheCollisionView) {
  pushKey(SDLK_F3);
  m_renderer->processEvents(m_controls);
  EXPECT_TRUE(m_controls.collisionView);
  pushKey(SDLK_F3);
  m_renderer->processEvents(m_controls);
  EXPECT_FALSE(m_controls.collisionView);
}

TEST_F(RenderControls, HeldKeyRepeatsDoNotToggleAgain) {
  SDL_Event event{};
  event.type = SDL_KEYDOWN;
  event.key.keysym.sym = SDLK_p;
  SDL_PushEvent(&event);
  event.key.repeat = 1;
  SDL_PushEvent(&event);
  SDL_PushEvent(&event);
  m_renderer->processEvents(m_controls);
  EXPECT_TRUE(m_controls.paused);
}

// Escape belongs to the app (its pause menu); a player never loses the game
// to one key. Closing the window quits.
TEST_F(RenderControls, EscapeNeverQuitsWindowCloseDoes) {
  pushKey(SDLK_ESCAPE);
  m_renderer->processEvents(m_controls);
  EXPECT_FALSE(m_controls.quitRequested);

  Controls again;
  SDL_Event quit{};
  quit.type = SDL_QUIT;
  SDL_PushEvent(&quit);
  m_renderer->processEvents(again);
  EXPECT_TRUE(again.quitRequested);
}

TEST(RenderMouse, DragOrbitsAndWheelZooms) {
  auto renderer = test::makeOffscreenRenderer(320, 240, /*hud=*/false);
  ASSERT_NE(renderer, nullptr);
  Controls controls;
  const Camera before = renderer->camera();

  SDL_Event event{};
  event.type = SDL_MOUSEMOTION;  // not dragging yet: no change
  event.motion.xrel = 50;
  SDL_PushEvent(&event);
  renderer->processEvents(controls);
  EXPECT_FLOAT_EQ(renderer->camera().yaw_rad, before.yaw_rad);

  event = SDL_Event{};
  event.type = SDL_MOUSEBUTTONDOWN;
  event.button.button = SDL_BUTTON_LEFT;
  event.button.state = SDL_PRESSED;
  SDL_PushEvent(&event);
  event = SDL_Event{};
  event.type = SDL_MOUSEMOTION;
  event.motion.xrel = 100;
  event.motion.yrel = 20;
  SDL_PushEvent(&event);
  event = SDL_Event{};
  event.type = SDL_MOUSEBUTTONUP;
  event.button.button = SDL_BUTTON_LEFT;
  SDL_PushEvent(&event);
  renderer->processEvents(controls);
  EXPECT_LT(renderer->camera().yaw_rad, before.yaw_rad);
  EXPECT_GT(renderer->camera().pitch_rad, before.pitch_rad);

  event = SDL_Event{};
  event.type = SDL_MOUSEWHEEL;
  event.wheel.y = 2;
  event.wheel.preciseY = 2.0f;
  SDL_PushEvent(&event);
  renderer->processEvents(controls);
  EXPECT_NEAR(renderer->camera().distance_m, before.distance_m * 0.81f, 1e-3f);
}

}  // namespace
}  // namespace tumble::render
