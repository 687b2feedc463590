#pragma once
// The Dear ImGui heads-up display: the debug panel (frame timings,
// simulation counters, the pause / step / slow-motion controls; shown while
// Controls::debugPanelVisible), and messages (script errors) in red.
// Owns its ImGui context and the SDL2 + OpenGL3 backends from libimgui.
#include <SDL.h>
#include <imgui.h>

#include <memory>
#include <vector>

#include "core/result.h"
#include "render/renderer.h"

struct ImGuiContext;

namespace tumble::render {

/// The tuning panel's window (tuning_panel.cpp); edits go into `panel`.
void buildTuningPanel(TuningPanel& panel, bool* open);

class Hud {
 public:
  static Result<std::unique_ptr<Hud>> create(SDL_Window* window, SDL_GLContext context);
  ~Hud();
  Hud(const Hud&) = delete;
  Hud& operator=(const Hud&) = delete;

  void processEvent(const SDL_Event& event);
  /// True while the HUD uses the keyboard / mouse (typing, dragging a
  /// slider, pointer over a HUD window); the game should then ignore them.
  bool wantsKeyboard() const;
  bool wantsMouse() const;

  /// The app's windows, built after the HUD's own (Renderer::addHudPanel).
  void addPanel(HudPanel panel) { m_panels.push_back(std::move(panel)); }
  /// Lays out and draws the HUD into the bound framebuffer. Button and
  /// slider changes go into `controls`. tuning: the tuning panel, drawn
  /// while controls.tuningPanelVisible (null: none).
  void draw(const HudStats& stats, Controls& controls, CameraMode cameraMode, TuningPanel* tuning = nullptr);

 private:
  Hud() = default;
  void newFrame();
  void build(const HudStats& stats, Controls& controls, CameraMode cameraMode, TuningPanel* tuning);
  void buildDebugPanel(const HudStats& stats, Controls& controls, CameraMode cameraMode, TuningPanel* tuning);
  void buildMessages(const HudStats& stats, const ImVec2& display);

  ImGuiContext* m_context = nullptr;
  bool m_sdlBackend = false, m_glBackend = false;
  bool m_primed = false;
  // The pointer from the last mouse motion event, pixels: used when SDL
  // reports no window under the mouse (the offscreen driver never gives one
  // the mouse focus), so scripted moves and clicks reach the HUD's windows.
  bool m_haveMotion = false;
  float m_motionX = 0, m_motionY = 0;
  // Buttons held between their down and up events (left, right, middle).
  // The SDL backend (1.86) reads held buttons from SDL's mouse state, which
  // scripted events never set, and while a button is held under X it reads
  // the pointer from the global mouse state, which stays where the press was
  // when the motion comes from XTest (xdotool): either way a dragged slider
  // did not move. While a button is held the events say where the pointer is.
  bool m_held[3] = {false, false, false};
  bool m_hadMessages = false;
  std::vector<HudPanel> m_panels;
  bool m_hadTuning = false;
};

}  // namespace tumble::render
