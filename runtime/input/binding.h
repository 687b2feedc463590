#pragma once
// Input bindings as plain data: what mods' bindings.lua declare and what the
// player's overrides change. No SDL state lives here; the names are SDL's.
//
// Index
//   ActionType, Device, Source        an action's kind; one physical input
//   Modifiers, applyModifiers         dead zone, response curve, invert, scale
//   Binding, parseBinding, toText     one source (or a key pair) + modifiers, and its text form
//   ActionDef, ContextDef, BindingSet what bindings.lua declare, merged by mod load order
//   suggestNames, keyNames, ...       close valid names for error messages
//
// Text form of a binding (bindings.lua, the user's bindings.json, the menu):
//   key:W  key:ctrl+R  key:Space       a keyboard key (SDL scancode name, any case),
//                                      optionally with modifiers ctrl, shift, alt, gui
//   keys:A/D                           a key pair for an axis: first -1, second +1
//   mouse:left|middle|right|x1|x2      a mouse button
//   mouse_axis:x|y                     mouse motion, pixels during the step (right, down +)
//   wheel:y|x                          wheel notches during the step (up, right +)
//   pad:a|b|x|y|start|back|dpup|...    a gamepad button (SDL GameController names)
//   pad_axis:leftx|lefty|rightx|righty|lefttrigger|righttrigger, with an optional
//                                      + or - for one half (pad_axis:lefty- is 0..1 pushing up)
// followed by modifiers: ";dead_zone=0.15;curve=2;invert;scale=0.5".
// Keys are bound by scancode (the key's place on the keyboard), so W A S D
// stay where they are on AZERTY and other layouts.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.h"

namespace tumble::input {

/// button: value 0..1 (1 for a key; a trigger gives its travel), down at
/// value >= kDownThreshold. axis: value -1..1 for sticks and key pairs,
/// unbounded for mouse motion and wheel; down at |value| >= kDownThreshold.
enum class ActionType : std::uint8_t { Button, Axis };
inline constexpr double kDownThreshold = 0.5;

enum class Device : std::uint8_t { Key, MouseButton, MouseMotion, MouseWheel, PadButton, PadAxis };

/// Modifier keys a key binding may require (bit set).
enum KeyMod : std::uint8_t { kModCtrl = 1, kModShift = 2, kModAlt = 4, kModGui = 8 };

/// One physical input.
struct Source {
  Device device = Device::Key;
  int code = 0;               ///< SDL_Scancode, SDL mouse button, axis (0 x, 1 y), SDL_GameControllerButton/Axis
  std::int8_t half = 0;       ///< PadAxis: +1 / -1 uses only that half (as 0..1); 0 the whole axis
  std::uint8_t keyMods = 0;   ///< Key: KeyMod bits that must be held as well
  bool operator==(const Source&) const = default;
};

/// Applied to each binding's raw value, in this order: dead zone, curve,
/// invert, scale.
struct Modifiers {
  double deadZone = 0;  ///< fraction of full travel (0..0.95) read as 0; the rest is stretched back to 0..1
  double curve = 1;     ///< response exponent: |v|^curve keeps the sign (2: fine control near centre)
  bool invert = false;  ///< flips the sign
  double scale = 1;     ///< multiplies the result (mouse_axis: per pixel)
  bool operator==(const Modifiers&) const = default;
};
double applyModifiers(double raw, const Modifiers& m);

struct Binding {
  Source source;        ///< for a key pair: the key giving -1
  Source positive;      ///< for a key pair: the key giving +1
  bool pair = false;    ///< keys:NEG/POS
  Modifiers modifiers;
  bool operator==(const Binding&) const = default;
};

/// Parses the text form above. The error says what is wrong and what would
/// be valid (an unknown key name lists close valid names).
Result<Binding> parseBinding(std::string_view text);
/// Canonical text; parseBinding(toText(b)) == b.
std::string toText(const Binding& b);
/// Text of one source for menus ("W", "ctrl+R", "mouse left", "pad a").
std::string sourceLabel(const Source& s);
/// Text of a binding for menus ("A / D", "pad leftx (dead zone 0.15)").
std::string bindingLabel(const Binding& b);

struct ActionDef {
  std::string name;     ///< "throttle"; mods other than base prefix theirs: "mymod.fire"
  ActionType type = ActionType::Button;
  std::string context;  ///< the context it belongs to
  std::string label;    ///< shown in the menu; empty: the name
  std::vector<Binding> bindings;  ///< the defaults (overrides change a copy at run time)
  Modifiers modifiers;  ///< defaults for bindings the player adds in the menu
  std::string mod;      ///< the mod that declared it last
};

/// A group of actions switched on and off together. When two enabled
/// contexts bind the same source, the one with the higher priority gets it
/// and the other does not see it (equal priority: both see it).
struct ContextDef {
  std::string name;
  int priority = 0;
  bool enabled = true;  ///< at start; scripts switch with input.set_context
};

struct BindingSet {
  std::vector<ContextDef> contexts;
  std::vector<ActionDef> actions;
  const ActionDef* findAction(std::string_view name) const;
  const ContextDef* findContext(std::string_view name) const;
};

/// Merges `later` (a mod later in load order) into `into`: contexts merge
/// by name (the later priority and enabled win); an action with a new name
/// is added; an action with a known name replaces the earlier defaults if
/// it has the same type and context, otherwise it is a problem and ignored.
/// Problems are appended as messages naming the action.
void mergeBindings(BindingSet& into, const BindingSet& later, std::vector<std::string>& problems);

/// Up to `max` names from `valid` closest to `name` (edit distance, case
/// ignored; prefixes count as close). Empty when nothing is close.
std::vector<std::string> suggestNames(std::string_view name, const std::vector<std::string>& valid, int max = 4);
/// " (did you mean: a, b?)" or "" — for the end of an error message.
std::string didYouMean(std::string_view name, const std::vector<std::string>& valid);
/// Valid names, for messages and menus.
const std::vector<std::string>& keyNames();
const std::vector<std::string>& padButtonNames();
const std::vector<std::string>& padAxisNames();

}  // namespace tumble::input
