#pragma once
// The script-error console for modders (the `console` action, ` by default,
// rebindable in the bindings menu): every script error of the session,
// newest last, as mod, file:line and message, with the Lua traceback under
// each; Clear empties it. While closed, a small badge at the top of the
// screen counts the errors it holds.
//
// It does not open by itself on a new error: an overlay that covers the road
// and takes the pointer in the middle of a drive is worse for a player than
// the red HUD message and the badge, and a modder opens it with one key.
//
// Drawn with Dear ImGui inside the HUD's frame (Renderer::addHudPanel).
#include <cstddef>
#include <string>
#include <vector>

#include "script/scenario_host.h"

namespace tumble::app {

class ScriptConsole {
 public:
  struct Entry {
    std::string mod, file, message, traceback;
    int line = 0;
  };
  /// Where a button was drawn in the last frame, window pixels (top-left origin).
  struct Rect {
    float x_px = 0, y_px = 0, w_px = 0, h_px = 0;
  };

  /// Takes the host's errors that are new since the last call.
  void sync(const script::ScenarioHost& host);
  /// A restart made a new host: its errors count from its first; the
  /// entries so far stay until Clear.
  void newSession() { m_seen = 0; }
  void toggle() { m_open = !m_open; }
  bool isOpen() const { return m_open; }
  void clear() { m_entries.clear(); }
  const std::vector<Entry>& entries() const { return m_entries; }
  /// The Clear button in the last frame (zero size while closed).
  const Rect& clearButton() const { return m_clearButton; }

  /// The window while open, the badge while closed with entries (call inside an ImGui frame).
  void draw();

  static constexpr std::size_t kMaxEntries = 500;  ///< the oldest go first

 private:
  std::size_t m_seen = 0;
  std::vector<Entry> m_entries;
  bool m_open = false;
  Rect m_clearButton;
};

}  // namespace tumble::app
