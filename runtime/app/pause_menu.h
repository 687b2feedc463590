#pragma once
// The pause menu (Escape or the pad's Start button in a scene): Resume,
// Restart, Change vehicle (driving scenarios: the vehicle picker, then a
// restart with the new car), Settings, Main menu, Quit to desktop. The game waits while it is open; Escape again
// resumes. Mouse: click an item. Keyboard and pad: the `ui` input context
// (ui_up, ui_down, ui_select; base's bindings.lua) is on while the menu is
// open and moves the highlight / picks the item.
//
// Items are a list so that later pages (Main menu, Settings) slot in as
// entries with their own Choice. Drawn with Dear ImGui inside the HUD's
// frame (Renderer::addHudPanel), like the bindings menu: render never
// includes input or app.
#include <string>
#include <vector>

#include "input/input_system.h"
#include "render/renderer.h"

namespace tumble::app {

class PauseMenu {
 public:
  enum class Choice { None, Resume, Restart, ChangeVehicle, Settings, MainMenu, Quit, BackToDesigner };
  struct Item {
    std::string label;
    Choice choice;
  };
  /// Where an item was drawn in the last frame, in window pixels (top-left
  /// origin): what the player saw, for the play report and for tests that
  /// click it.
  struct ItemRect {
    std::string label;
    float x_px = 0, y_px = 0, w_px = 0, h_px = 0;
  };

  PauseMenu();
  /// The input system whose `ui` context the menu switches (a restart makes
  /// a new scene, hence a new input system). Null: keyboard navigation off.
  void setInput(input::InputSystem* input);
  /// Offers "Change vehicle" (the scenario takes a vehicle, app/game_catalog.h).
  void setVehicleChoice(bool offered);
  /// Offers "Back to designer" (a scene the designer is driving, app/designer_mode.h).
  void setDesignerReturn(bool offered);

  void open();
  void close();
  void toggle() { isOpen() ? close() : open(); }
  bool isOpen() const { return m_open; }
  /// The game is paused while the menu is open and resumes as it was when
  /// it closes (call every frame, like BindingsMenu::syncPause).
  void syncPause(render::Controls& controls);

  /// Keyboard / pad: move the highlight (wraps) and pick the highlighted item.
  void moveSelection(int delta);
  void activate();
  int selected() const { return m_selected; }
  const std::vector<Item>& items() const { return m_items; }
  /// The item picked since the last call (then the menu has closed), or None.
  Choice takeChoice();

  /// Builds the window (call inside an ImGui frame). Does nothing when closed.
  void draw();
  const std::vector<ItemRect>& lastLayout() const { return m_layout; }

 private:
  void choose(Choice c);
  void syncUiContext();

  input::InputSystem* m_input = nullptr;
  std::vector<Item> m_items;
  std::vector<ItemRect> m_layout;
  bool m_open = false;
  int m_selected = 0;
  Choice m_choice = Choice::None;
  bool m_pauseApplied = false, m_pausedBefore = false;
  bool m_vehicleOffered = false, m_designerReturn = false;
};

}  // namespace tumble::app
