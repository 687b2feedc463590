#pragma once
// The player's HUD in play, drawn as a game's HUD (no window frames: large
// figures on semi-transparent panels in the screen corners, scaled with the
// window):
//   bottom right  speedometer (dial and digits, km/h), rev counter (bar with
//                 the red zone from the car's rev limiter) and gear (R, N, 1..)
//   top right     lap widget: current lap time, last, best, gate k of n,
//                 lap k of n; the scenario feeds it (hud.set_lap, bind_hud.cpp)
//   bottom left   minimap: the terrain from above (app/minimap.h) or, without
//                 a terrain, a plain plan of the gates; the car as an arrow,
//                 the gates as numbered dots with the next one highlighted
//   top centre    messages coloured by kind that fade (app/message_log.h), and
//                 the script-error console's badge (app/script_console.h)
// The driving parts appear only while the scene has a vehicle; the `hud`
// action (H) hides and shows the HUD. What it shows is kept in a HudView,
// which the play report writes (docs/play-events.md).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/message_log.h"
#include "app/minimap.h"
#include "app/scene.h"
#include "app/script_console.h"

namespace tumble::app {

/// What the HUD shows in the current frame.
struct HudView {
  bool visible = true;            ///< the `hud` action toggles it
  bool vehicle = false;           ///< a driven vehicle exists (the driving parts are drawn)
  std::string vehicleName;
  double speed_kmh = 0;           ///< signed: negative in reverse
  double rpm = 0;
  double redline_rpm = 0;         ///< the engine's rev limiter (VehicleDef engine.maxRpm)
  double dialMax_rpm = 0;         ///< the rev counter's scale end
  int gear = 0;                   ///< -1 R, 0 N, 1..
  std::string speedText, rpmText, gearText;  ///< the figures as drawn
  script::LapDisplay lap;
  std::string lapTimeText, lastText, bestText, gateText, lapCountText;
  std::string minimap;            ///< "terrain", "plan" (gates without terrain) or "" (none)
  float carX_m = 0, carZ_m = 0;   ///< world, m
  float forwardX = 0, forwardZ = 1;  ///< the car's heading in the ground plane (unit)
  std::vector<Vec3> gates_m;
  std::vector<HudMessage> messages;
};

/// "R", "N", "1", "2", ...
std::string gearText(int gear);
/// "1:23.45" (minutes:seconds.hundredths); "-" for a missing time.
std::string lapTimeText(std::optional<double> seconds);

class GameHud {
 public:
  GameHud() = default;
  GameHud(const GameHud&) = delete;
  GameHud& operator=(const GameHud&) = delete;
  ~GameHud();
  /// The renderer whose GL context the HUD's textures (the minimap) live in;
  /// without one the minimap is drawn as a rectangle per cell.
  void setRenderer(render::Renderer* renderer) { m_renderer = renderer; }
  /// Reads the scene after the frame's steps (time_s: simulated time now).
  void update(Scene& scene, double time_s);
  /// A hot reload took effect: the errors leave the HUD (the console keeps them).
  void reloaded() { m_messages.clearErrors(); }
  /// A restart replaced the scene (and its script host).
  void newSession() {
    m_messages.newSession();
    m_console.newSession();
  }
  void toggleVisible() { m_visible = !m_visible; }
  ScriptConsole& console() { return m_console; }
  const HudView& view() const { return m_view; }
  const MinimapImage& minimapImage() const { return m_minimap; }
  /// Builds the HUD (call inside the HUD's ImGui frame: Renderer::addHudPanel).
  void draw();
  /// The "hud" object of the play report.
  nlohmann::json report() const;

 private:
  void drawSpeedometer(float s);
  void drawLap(float s);
  void drawMinimap(float s);
  void drawMessages(float s);

  bool m_visible = true;
  bool m_drawn = false;  ///< the widgets were drawn since the last update(): on screen in the last frame
  HudView m_view;
  MessageLog m_messages;
  ScriptConsole m_console;
  MinimapImage m_minimap;
  render::Renderer* m_renderer = nullptr;
  render::UiImage m_minimapTexture;  ///< m_minimap uploaded (one quad instead of ~9000 rectangles)
  int m_minimapTextureBuild = -1;    ///< m_minimap.builds() it was made from
};

}  // namespace tumble::app
