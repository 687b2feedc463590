#pragma once
// The Dear ImGui heads-up display: the debug panel (frame timings,
// simulation counters, the pause / step / slow-motion controls; shown while
// Controls::debugPanelVisible), and messages (script errors) in red.
// Owns its ImGui context and the SDL2 + OpenGL3 backends from libimgui.
#include <SDL.h>
#include <imgui.h>

#include <array>
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
  /// Whether a button pressed at (x, y) (window pixels) is the HUD's: over a
  /// window it drew last frame that takes the mouse, or while a popup is
  /// open (a click outside closes it), as ImGui itself decides a fresh
  /// press. wantsMouse() says where the pointer was at the last frame, which
  /// is wrong for a press whose pointer jumped there since (an instant
  /// click from the panel to the ground).
  bool wantsMousePress(float x_px, float y_px) const;

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
  // The pointer from the last mouse event (motion or button), pixels, until
  // it leaves the window: where ImGui sees the pointer. The SDL backend
  // (1.86) reads it from SDL's mouse focus and global state instead: the
  // offscreen driver (play --frames) never sets those, and under X the
  // global state can stay where the pointer was (XTest motion from xdotool
  // does not move it): ImGui then still saw the pointer over the panel after
  // a click there, so the next press on the ground was taken as the panel's.
  bool m_haveMotion = false;
  float m_motionX = 0, m_motionY = 0;
  // Buttons held between their down and up events (left, right, middle):
  // the backend reads held buttons from SDL's mouse state, which scripted
  // events never set, so a dragged slider did not move.
  bool m_held[3] = {false, false, false};
  // The windows that take the mouse, as drawn in the last frame (x0, y0,
  // x1, y1 pixels), and whether a popup was open: for wantsMousePress.
  std::vector<std::array<float, 4>> m_mouseWindows;
  bool m_popupOpen = false;
  bool m_hadMessages = false;
  std::vector<HudPanel> m_panels;
  bool m_hadTuning = false;
};

}  // namespace tumble::render
