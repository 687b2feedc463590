#pragma once
// Scripted player input for `tumble play --events FILE`: a small text file of
// timed events that play pushes into SDL's own event queue (SDL_PushEvent)
// at the start of the frame they name, so they take the same path as a
// player's keys, mouse and gamepad: renderer -> HUD -> input actions.
//
//   # frame  what   source / values        (a '#' starts a comment)
//   0    down   key:W                      key, mouse button or pad button held down
//   300  up     key:W                      ... and let go
//   10   axis   pad_axis:leftx -0.6        pad stick or trigger to a value in -1..1
//   20   move   640 360                    mouse pointer to pixel (x, y), top-left origin
//   21   down   mouse:left                 (at the pointer)
//   22   up     mouse:left
//   30   wheel  1                          wheel notches (y; "wheel X Y" for both)
//   90   quit                              the window's close button
//
// Sources are written as in bindings.lua (docs/input.md): key:Escape,
// key:F5, key:Left Shift, mouse:right, pad:a, pad:start, pad_axis:righttrigger.
// Frames count from 0 and must not decrease. Every mistake is reported
// with the file, the line and what is expected.
#include <string>
#include <vector>

#include "core/result.h"
#include "input/binding.h"

union SDL_Event;

namespace tumble::app {

struct PlayEvent {
  enum class Kind { Down, Up, Axis, Move, Wheel, Quit };
  long long frame = 0;
  Kind kind = Kind::Down;
  input::Source source;   ///< Down / Up: a key, mouse button or pad button; Axis: a pad axis
  double value = 0;       ///< Axis: -1..1
  float x = 0, y = 0;     ///< Move: pixels; Wheel: notches
  int line = 0;           ///< in the file, for messages
};

/// Parses the text of an events file; `name` is used in messages.
Result<std::vector<PlayEvent>> parsePlayEvents(const std::string& text, const std::string& name);
/// Reads and parses an events file.
Result<std::vector<PlayEvent>> loadPlayEvents(const std::string& path);

/// The SDL event a scripted event becomes. windowId: the window it is sent
/// to; pointer: the mouse position so far (moves update it), pixels.
SDL_Event toSdlEvent(const PlayEvent& e, unsigned windowId, float pointer[2]);

}  // namespace tumble::app
