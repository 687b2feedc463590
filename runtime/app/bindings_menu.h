#pragma once
// The in-game bindings menu (F1 or the pad's Back button): every action of
// the loaded mods with its bindings; click one to rebind it ("press a key"),
// x removes it, + adds one, Reset restores the mod's defaults, Save writes
// the differences to the user's bindings.json (input/overrides_file.h).
//
// Where it lives: render may not include input, so the menu is app code
// that draws with Dear ImGui inside the HUD's frame (Renderer::addHudPanel)
// and changes the InputSystem directly.
#include <string>
#include <vector>

#include "input/input_system.h"
#include "render/renderer.h"

namespace tumble::app {
class PauseMenu;
}

namespace tumble::app {

class BindingsMenu {
 public:
  /// Applies the player's overrides from configPath. A file that cannot be
  /// read is reported (log and the menu's status line), the defaults are
  /// used and the file is left as it is until the player presses Save.
  BindingsMenu(input::InputSystem& input, std::string configPath);

  void toggle();
  bool isOpen() const { return m_open; }
  /// The game pauses while the menu is open and resumes as it was when it
  /// closes (applyFrameInput calls this every frame).
  void syncPause(render::Controls& controls);
  /// Builds the window (call inside an ImGui frame). Does nothing when closed.
  void draw();
  /// Starts "press a key" for the action's binding `slot` (-1: a new one);
  /// the next drawn frame after the key takes it (what clicking a binding does).
  void rebind(int action, int slot);
  bool rebinding() const { return m_captureAction >= 0; }
  /// Writes the overrides now (what the Save button does).
  Status save();
  const std::string& status() const { return m_status; }
  /// Where each binding's button was drawn in the last frame the menu was
  /// open, window pixels (top-left origin): for the play report and tests
  /// that click one.
  struct ButtonRect {
    std::string action, label;
    int slot = 0;
    float x_px = 0, y_px = 0, w_px = 0, h_px = 0;
  };
  const std::vector<ButtonRect>& lastLayout() const { return m_layout; }

 private:
  void drawAction(int action);
  void finishCapture();

  input::InputSystem& m_input;
  std::string m_path;
  std::string m_status;
  bool m_open = false;
  bool m_dirty = false;
  bool m_pauseApplied = false, m_pausedBefore = false;
  // Capture in progress: which action and which binding it replaces (-1: a new one).
  int m_captureAction = -1, m_captureSlot = -1;
  bool m_waitingPositive = false;  ///< a key pair: the negative key is in m_pairNegative
  input::Source m_pairNegative;
  std::vector<ButtonRect> m_layout;
};

/// What the player asked play for in a frame beyond render::Controls.
struct FrameRequests {
  bool restart = false;  ///< the restart key or the pause menu's Restart
  bool toggleConsole = false;  ///< the console key: the script-error console (app/script_console.h)
  bool toggleHud = false;      ///< the hud key: the driving HUD on or off (app/driving_hud.h)
  bool changeVehicle = false;  ///< the pause menu's Change vehicle
  bool settings = false;       ///< the pause menu's Settings
  bool mainMenu = false;       ///< the pause menu's Main menu
  bool backToDesigner = false; ///< the pause menu's Back to designer
};

/// Once per rendered frame, after Renderer::processEvents: the app's own
/// actions pressed since the last frame (they work while the simulation is
/// paused): pause, screenshot, menu (opens this menu, which pauses the
/// game), camera (the next camera mode: orbit, follow, and chase, hood,
/// cockpit when the scenario follows a body), debug_panel; with a pause
/// menu also pause_menu (Escape: closes the bindings menu if it is open,
/// else opens or closes the pause menu; never quits), the menu's ui_up /
/// ui_down / ui_select, and restart (into `requests`). Actions no loaded
/// mod declares are skipped. Then the world ray under the pointer for
/// input.pointer_ray().
void applyFrameInput(input::InputSystem& input, BindingsMenu& menu, render::Controls& controls,
                     render::Renderer& renderer, PauseMenu* pauseMenu = nullptr, FrameRequests* requests = nullptr);

}  // namespace tumble::app
