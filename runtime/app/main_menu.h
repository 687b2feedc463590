#pragma once
// The main menu: what `tumble play` shows when given no scenario, and the
// pages the pause menu opens over a running game (Change vehicle, Settings).
//
//   Root       Play, Designer (the scenario designer, app/designer_mode.h), Settings, Quit
//   Mods       one entry per mod found (mods/, ~/.local/share/tumble/mods, --mods)
//   Scenarios  the mod's scenarios: title, description and a thumbnail of the
//              selected one (app/thumbnails.h)
//   Vehicles   for a scenario that declares the `car` parameter: every
//              vehicle definition it can spawn, with mass, peak power,
//              drive layout and tyre grip read from the definitions
//   Settings   resolution, fullscreen, quality preset, volumes, bindings (F1)
//   ConfirmQuit  Escape on Root asks before quitting
//
// Navigation: mouse (hover, click), keyboard (arrows, Return, Escape =
// back) and pad (d-pad or left stick, A, B). The keys come from a small
// input::InputSystem of its own (menuBindings()): the menu works before any
// mod is loaded. Drawn with Dear ImGui in the HUD's frame (addHudPanel).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/game_catalog.h"
#include "app/player_settings.h"
#include "input/binding.h"

namespace tumble::app {

class ThumbnailCache;

class MainMenu {
 public:
  enum class Page { Closed, Root, Mods, Scenarios, Vehicles, Settings, ConfirmQuit };
  /// What the player asked for since the last takeRequests().
  struct Requests {
    std::optional<std::string> startScenario;  ///< MOD:NAME to start
    std::optional<std::string> vehicle;        ///< with this vehicle (MOD:NAME), for a driving scenario
    bool quit = false;
    bool openDesigner = false;     ///< the root page's Designer
    bool backToGame = false;       ///< opened over a game and left with Back: reopen the pause menu
    bool openBindings = false;     ///< the settings page's "Key and pad bindings"
    bool settingsChanged = false;  ///< the window or quality changed: apply (and they were saved)
  };
  /// Where an item was drawn in the last frame (window pixels, top-left).
  struct ItemRect {
    std::string label;
    float x_px = 0, y_px = 0, w_px = 0, h_px = 0;
  };

  MainMenu(GameCatalog& catalog, PlayerSettings& settings, std::string settingsPath, ThumbnailCache* thumbnails);

  /// The main menu's root page (no game running).
  void openRoot();
  /// Over a running game: the vehicle picker for this scenario (starting on
  /// `drivenVehicle`, the car being driven, MOD:NAME; empty: the scenario's
  /// default), or settings. Back from there returns to the game
  /// (Requests::backToGame).
  void openVehicles(const std::string& scenarioRef, const std::string& drivenVehicle = "");
  void openSettings();
  void close() { m_page = Page::Closed; }
  bool isOpen() const { return m_page != Page::Closed; }
  bool overGame() const { return m_overGame; }
  Page page() const { return m_page; }
  static const char* pageName(Page page);

  /// Keyboard / pad (the menu's actions, menuBindings()).
  void moveSelection(int delta);
  void adjust(int delta);  ///< left / right on a setting
  void activate();
  void back();
  /// Dispatches one of the menu's action names (ui_up, ui_down, ...).
  void onAction(const std::string& name);

  Requests takeRequests();
  /// A message shown at the bottom (a broken settings file, a failed start).
  void setStatus(std::string text) { m_status = std::move(text); }

  void draw();
  const std::vector<ItemRect>& lastLayout() const { return m_layout; }
  int selected() const { return m_selected; }
  std::string selectedLabel() const;
  /// On the scenarios page: the highlighted scenario's thumbnail status
  /// (ThumbnailCache::status); empty elsewhere.
  std::string thumbnailStatus() const;

 private:
  enum class Kind { Button, Choice, Slider, Toggle };
  struct Item {
    std::string label;
    std::string value;  ///< shown on the right (choices, sliders, toggles)
    Kind kind = Kind::Button;
    bool enabled = true;
    std::string note;   ///< shown for a disabled item ("not yet available")
    std::function<void()> activate;
    std::function<void(int)> adjust;
    float fraction = -1;  ///< a slider's position 0..1, drawn as a bar; < 0: none
  };
  void go(Page page);
  void rebuild();
  void buildRoot();
  void buildMods();
  void buildScenarios();
  void buildVehicles();
  void buildSettings();
  void buildConfirmQuit();
  void settingsEdited(bool applyNow);
  void drawDetails(float x, float y, float w, float h);
  std::string title() const;

  GameCatalog& m_catalog;
  PlayerSettings& m_settings;
  std::string m_settingsPath;
  ThumbnailCache* m_thumbnails;
  Page m_page = Page::Closed;
  bool m_overGame = false;
  std::string m_mod, m_scenario;  ///< chosen so far
  std::string m_drivenVehicle;     ///< the picker over a game starts on it (openVehicles)
  std::vector<Item> m_items;
  std::vector<ItemRect> m_layout;
  int m_selected = 0;
  bool m_scrollToSelected = false;
  std::vector<std::pair<Page, int>> m_history;  ///< pages to go back to, with their selection
  Requests m_requests;
  std::string m_status;
};

/// The menu's own actions in context "ui": ui_up, ui_down, ui_left,
/// ui_right, ui_select, ui_back, on arrows / Return / Escape and the pad's
/// d-pad, left stick, A and B.
input::BindingSet menuBindings();

}  // namespace tumble::app
