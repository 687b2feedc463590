#pragma once
// The messages the player sees in play, coloured by kind (info white,
// warning yellow, error red) and fading out over their last second:
// game.message lines (script/bind_game.cpp), script errors as they happen
// (the console keeps them all; the HUD shows each for kErrorSeconds), and the
// scenario's hud_text lines and outcome, which stay while the script shows
// them. A hot reload that takes effect removes the errors from the HUD: the
// fix is in, the old complaint goes.
//
// Times are simulated seconds (what game.message counts in), so a paused
// game keeps its messages and a scripted play gives the same ones on every
// machine.
#include <cstddef>
#include <string>
#include <vector>

#include "script/scenario_host.h"

namespace tumble::app {

struct HudMessage {
  std::string text;
  script::MessageKind kind = script::MessageKind::Info;
  float alpha = 1;  ///< 1 opaque .. 0 gone (the last kFade_s of its time)
};

class MessageLog {
 public:
  static constexpr double kErrorSeconds = 8;  ///< a script error stays on the HUD this long, s
  static constexpr double kFade_s = 1;        ///< messages fade out over their last second

  /// Takes the host's errors that are new since the last call. time_s: now.
  void update(const script::ScenarioHost& host, double time_s);
  /// A restart made a new host: its errors count from its first, the old ones leave.
  void newSession() {
    m_seenErrors = 0;
    m_errors.clear();
  }
  /// A reload took effect: the errors shown so far leave the HUD.
  void clearErrors() { m_errors.clear(); }
  /// What the HUD shows at time_s, top to bottom: outcome, score, timed
  /// messages (oldest first), errors, then the hud_text lines.
  std::vector<HudMessage> visible(const script::ScenarioHost& host, double time_s) const;

 private:
  struct Timed {
    std::string text;
    double start_s = 0, end_s = 0;
  };
  std::size_t m_seenErrors = 0;
  std::vector<Timed> m_errors;
};

/// Opacity of a message shown from start_s to end_s at time_s: 1, then a
/// linear fade over the last `fade_s`, 0 outside.
float messageAlpha(double start_s, double end_s, double time_s, double fade_s);

}  // namespace tumble::app
