#pragma once
// Helpers for input tests: synthetic SDL events (no window, no SDL_Init:
// InputSystem only reads the event structs) and small binding sets.
#include <SDL.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "input/binding.h"
#include "input/input_system.h"

namespace tumble::test {

inline SDL_Event keyEvent(SDL_Scancode sc, bool down, bool repeat = false) {
  SDL_Event e{};
  e.type = down ? SDL_KEYDOWN : SDL_KEYUP;
  e.key.keysym.scancode = sc;
  e.key.repeat = repeat ? 1 : 0;
  return e;
}

inline SDL_Event mouseButtonEvent(Uint8 button, bool down) {
  SDL_Event e{};
  e.type = down ? SDL_MOUSEBUTTONDOWN : SDL_MOUSEBUTTONUP;
  e.button.button = button;
  return e;
}

inline SDL_Event mouseMotionEvent(int dx, int dy) {
  SDL_Event e{};
  e.type = SDL_MOUSEMOTION;
  e.motion.xrel = dx;
  e.motion.yrel = dy;
  return e;
}

inline SDL_Event padAxisEvent(SDL_GameControllerAxis axis, Sint16 value) {
  SDL_Event e{};
  e.type = SDL_CONTROLLERAXISMOTION;
  e.caxis.axis = Uint8(axis);
  e.caxis.value = value;
  return e;
}

inline SDL_Event padButtonEvent(SDL_GameControllerButton b, bool down) {
  SDL_Event e{};
  e.type = down ? SDL_CONTROLLERBUTTONDOWN : SDL_CONTROLLERBUTTONUP;
  e.cbutton.button = Uint8(b);
  return e;
}

inline input::Binding bind(const std::string& text) {
  auto b = input::parseBinding(text);
  EXPECT_TRUE(b) << text << ": " << (b ? "" : b.error());
  return b ? *b : input::Binding{};
}

/// An action in `context` with the given binding texts.
inline input::ActionDef actionDef(const std::string& name, input::ActionType type, const std::string& context,
                                  const std::vector<std::string>& bindings) {
  input::ActionDef a;
  a.name = name;
  a.type = type;
  a.context = context;
  for (const auto& t : bindings) a.bindings.push_back(bind(t));
  return a;
}

/// A fresh folder per test under the build tree.
inline std::filesystem::path testDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  auto dir = std::filesystem::path(TUMBLE_TEST_TMP) / (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace tumble::test
