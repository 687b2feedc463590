// Renderer::processEvents: SDL events to Controls and camera moves. Key
// bindings here are the engine's fixed debug keys; gameplay actions go
// through the input module and mods' bindings.lua instead.
#include <SDL.h>

#include <cmath>

#include "render/camera_rig.h"
#include "render/internal/camera_math.h"
#include "render/internal/renderer_impl.h"
#include "render/internal/time_scale.h"
#include "render/renderer.h"

namespace tumble::render {

namespace {

// A full-width drag turns the camera about two thirds of a turn on a 1280
// pixel window: fine control without needing several drags to go around.
constexpr float kOrbitRadPerPixel = 0.005f;
// One wheel notch moves 10 % closer or farther, so zoom feels the same at
// 2 m and at 200 m.
constexpr float kZoomPerNotch = 0.9f;

void applyKey(SDL_Keycode key, Controls& controls, Camera& camera) {
  switch (key) {
    case SDLK_p:
    case SDLK_SPACE: controls.paused = !controls.paused; break;
    case SDLK_n: requestSingleStep(controls); break;
    case SDLK_MINUS:
    case SDLK_KP_MINUS: controls.timeScale = slowerTimeScale(controls.timeScale); break;
    case SDLK_EQUALS:
    case SDLK_PLUS:
    case SDLK_KP_PLUS: controls.timeScale = fasterTimeScale(controls.timeScale); break;
    case SDLK_F12: controls.screenshotRequested = true; break;
    case SDLK_F2: controls.tuningPanelVisible = !controls.tuningPanelVisible; break;
    case SDLK_F3: controls.collisionView = !controls.collisionView; break;
    case SDLK_c: camera.mode = nextCameraMode(camera.mode, camera.vehicleModes); break;
    default: break;
  }
}

}  // namespace

void Renderer::processEvents(Controls& controls) {
  Impl& r = *m_impl;
  SDL_Event event;
  while (SDL_PollEvent(&event)) {
    if (r.hud) r.hud->processEvent(event);
    const bool hudKeyboard = r.hud && r.hud->wantsKeyboard();
    // A press belongs to the HUD if it lands on one of its windows, wherever
    // the pointer was at the last frame.
    const bool hudMouse = r.hud && (event.type == SDL_MOUSEBUTTONDOWN
                                        ? r.hud->wantsMousePress(float(event.button.x), float(event.button.y))
                                        : r.hud->wantsMouse());
    if (r.eventHook) {
      const bool keyboard = event.type == SDL_KEYDOWN || event.type == SDL_KEYUP;
      if (r.eventHook(event, keyboard ? hudKeyboard : hudMouse)) continue;
    }
    switch (event.type) {
      case SDL_QUIT: controls.quitRequested = true; break;
      case SDL_WINDOWEVENT:
        if (event.window.event == SDL_WINDOWEVENT_CLOSE) controls.quitRequested = true;
        break;
      case SDL_KEYDOWN:
        // Escape is the app's (the pause menu, an action in bindings.lua): it never quits.
        if (!hudKeyboard && event.key.repeat == 0) {
          applyKey(event.key.keysym.sym, controls, r.camera);
        }
        break;
      case SDL_MOUSEBUTTONDOWN:
        if (!hudMouse && (event.button.button == SDL_BUTTON_LEFT ||
                          event.button.button == SDL_BUTTON_RIGHT)) {
          r.dragging = true;
        }
        break;
      case SDL_MOUSEBUTTONUP: r.dragging = false; break;
      case SDL_MOUSEMOTION:
        if (r.dragging) {
          r.camera.yaw_rad -= kOrbitRadPerPixel * static_cast<float>(event.motion.xrel);
          r.camera.pitch_rad += kOrbitRadPerPixel * static_cast<float>(event.motion.yrel);
        }
        break;
      case SDL_MOUSEWHEEL:
        if (!hudMouse) {
          const float notches = event.wheel.direction == SDL_MOUSEWHEEL_FLIPPED
                                    ? -event.wheel.preciseY
                                    : event.wheel.preciseY;
          r.camera.distance_m *= std::pow(kZoomPerNotch, notches);
        }
        break;
      default: break;
    }
  }
  clampCamera(r.camera);
}

void Renderer::setEventHook(EventHook hook) { m_impl->eventHook = std::move(hook); }

void Renderer::addHudPanel(HudPanel panel) {
  if (m_impl->hud) m_impl->hud->addPanel(std::move(panel));
}

}  // namespace tumble::render
