#pragma once
// The input system: SDL events in, named actions out, once per fixed step.
//
// Index
//   InputSystem           actions' state per fixed step, contexts, injection
//     handleEvent         SDL events (keyboard, mouse, SDL GameController)
//     step                the fixed step's snapshot: value, down, pressed, released
//     inject              values from scripts, tests and autopilots
//     takeFramePresses    per-frame presses for the app (pause works while paused)
//     setBindings, ...    rebinding; overrides() are the differences from defaults
//     beginCapture, ...   "press a key to bind" for the menu
//
// Determinism: events only change device state and latch edges; the state
// scripts read is fixed by step() at the start of each fixed step, so every
// callback in a step sees the same values. An action pressed and released
// between two steps (a tap inside one rendered frame) is down and pressed in
// the next step and released in the one after: an edge is never lost. With
// no events (headless) only injected values change anything, so a run with
// the same injections gives the same result.
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "input/binding.h"

union SDL_Event;

namespace tumble::input {

/// The player's changes: action name -> its whole binding list (text form).
/// Only actions whose bindings differ from the defaults appear.
using Overrides = std::map<std::string, std::vector<std::string>>;

class InputSystem {
 public:
  explicit InputSystem(BindingSet definitions = {});
  ~InputSystem();
  InputSystem(const InputSystem&) = delete;
  InputSystem& operator=(const InputSystem&) = delete;

  const BindingSet& definitions() const { return m_defs; }
  /// Hot reload of bindings.lua: new definitions (actions, default bindings,
  /// contexts) replace the old. The player's overrides are kept (applied
  /// again over the new defaults), and so are the enabled flags of contexts
  /// that still exist (scripts switch them); an action keeps its state
  /// (held, injected) when it still exists under the same name.
  void redefine(BindingSet definitions);
  int actionCount() const { return int(m_defs.actions.size()); }
  /// Index of the action, -1 if there is none.
  int find(std::string_view name) const;
  const ActionDef& action(int index) const { return m_defs.actions[std::size_t(index)]; }
  /// "unknown action "x" (did you mean: ...?)" — the message scripts get.
  std::string unknownActionMessage(std::string_view name) const;

  // --- Devices -------------------------------------------------------------
  /// Opens the SDL GameController subsystem so pads send events (play only).
  /// Failure is not fatal: keyboard and mouse still work.
  Status enableGamepads();
  /// One SDL event. `uiWants`: the UI (HUD) uses this device now; presses
  /// are then ignored (releases still count, so no key sticks). Returns true
  /// when an enabled binding uses the event (the caller then leaves it alone).
  bool handleEvent(const SDL_Event& event, bool uiWants = false);
  /// Pointer position in the window, normalised: x, y in -1..1, y up. Valid
  /// once the mouse moved over the window.
  std::optional<std::array<float, 2>> pointer() const { return m_pointer; }
  void setPointer(float x, float y) { m_pointer = std::array<float, 2>{x, y}; }
  /// The world ray under the pointer (the app computes it from the camera
  /// each frame; none headless): origin in m, unit direction.
  struct Ray {
    Vec3 origin_m, direction;
  };
  std::optional<Ray> pointerRay() const { return m_pointerRay; }
  void setPointerRay(const Vec3& origin_m, const Vec3& direction) { m_pointerRay = Ray{origin_m, direction}; }

  // --- Per fixed step --------------------------------------------------------
  /// Takes the snapshot for the coming fixed step. Call once per step,
  /// before any script runs.
  void step();
  double value(int action) const { return m_state[std::size_t(action)].value; }
  bool down(int action) const { return m_state[std::size_t(action)].down; }
  bool pressed(int action) const { return m_state[std::size_t(action)].pressed; }
  bool released(int action) const { return m_state[std::size_t(action)].released; }
  std::int64_t steps() const { return m_steps; }

  /// From the next step on the action reads `value` whatever the devices do
  /// (a button: value >= 0.5 is down). clearInjection gives it back to them.
  void inject(int action, double value);
  void clearInjection(int action);
  bool injected(int action) const { return m_state[std::size_t(action)].injected; }

  /// What scripts read of one action in one step: recorded by `play
  /// --record` after each step, played back by `run --replay`.
  struct StepState {
    double value = 0;
    bool down = false, pressed = false, released = false;
    bool operator==(const StepState&) const = default;
  };
  /// Every action's state in the current step, in action order.
  std::vector<StepState> stepStates() const;
  /// The next step() takes exactly these states (in action order; missing
  /// actions read as released) instead of the devices and injections; the
  /// step after that is back to normal unless this is called again.
  void playBack(std::vector<StepState> states) { m_playBack = std::move(states); }

  /// Actions that went down since the last call, per rendered frame, in the
  /// order pressed (for the app's own actions: pause, menu, screenshot; they
  /// must work while the simulation is paused and no step runs).
  std::vector<int> takeFramePresses();

  // --- Contexts --------------------------------------------------------------
  Status setContextEnabled(std::string_view name, bool enabled);
  bool contextEnabled(std::string_view name) const;
  std::vector<std::string> contextNames() const;

  // --- Rebinding -------------------------------------------------------------
  const std::vector<Binding>& bindings(int action) const { return m_bindings[std::size_t(action)]; }
  void setBindings(int action, std::vector<Binding> bindings);
  void resetBindings(int action);
  void resetAllBindings();
  /// Differences from the defaults, plus entries for actions this run does
  /// not know (another mod's), kept so saving does not lose them.
  Overrides overrides() const;
  /// Applies the player's overrides. Entries for unknown actions are kept
  /// (see overrides()); an unparsable binding is skipped with a message.
  std::vector<std::string> applyOverrides(const Overrides& overrides);

  /// Menu: the next key, mouse button, pad button or pad axis pushed past
  /// half travel is captured instead of acting (Escape cancels).
  void beginCapture();
  void cancelCapture() { m_capturing = false; }
  bool capturing() const { return m_capturing; }
  /// The captured source once there is one (then capture ends); the bool is
  /// false when the player cancelled with Escape.
  std::optional<std::pair<bool, Source>> takeCaptured();

 private:
  struct ActionState {
    double value = 0;
    bool down = false, pressed = false, released = false;
    bool live = false;           ///< down by device state right now (between steps)
    bool latchPress = false, latchRelease = false;  ///< edges since the last step
    double latchValue = 0;       ///< value when latchPress was set
    bool framePress = false;
    bool injected = false, injectedNow = false;
    double injectValue = 0;
  };
  std::optional<std::vector<StepState>> m_playBack;  ///< playBack(): the next step's states
  struct BoundSource {
    bool owned = true, ownedPositive = true;  ///< not shadowed by a higher-priority context
  };

  void rebuildOwnership();
  double sourceValue(const Source& s, bool withMotion) const;
  double bindingValue(int action, std::size_t b, bool withMotion) const;
  double evaluate(int action, bool withMotion) const;
  bool isDown(int action, double v) const;
  void updateLive();
  bool usedByOwnedBinding(Device device, int code) const;
  bool contextOn(const std::string& name) const;
  void captureFrom(const SDL_Event& e);

  // Lookup by string_view without building a std::string (input.value is
  // called from Lua every step).
  struct NameHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  BindingSet m_defs;
  std::unordered_map<std::string, int, NameHash, std::equal_to<>> m_index;
  std::vector<std::vector<Binding>> m_bindings;           ///< current, per action
  std::vector<std::vector<BoundSource>> m_owned;          ///< parallel to m_bindings
  std::vector<ActionState> m_state;
  std::vector<int> m_framePresses;
  std::map<std::string, bool> m_contextOn;
  Overrides m_foreign;  ///< overrides of actions not loaded in this run
  std::int64_t m_steps = 0;

  // Device state.
  std::array<bool, 512> m_keys{};
  std::array<bool, 8> m_mouse{};
  std::array<bool, 32> m_padButtons{};
  std::array<float, 8> m_padAxes{};
  double m_motion[2] = {0, 0}, m_wheel[2] = {0, 0};  ///< since the last step: px, notches
  std::optional<std::array<float, 2>> m_pointer;
  std::optional<Ray> m_pointerRay;
  std::vector<void*> m_pads;  ///< SDL_GameController*
  bool m_gamepads = false;

  bool m_capturing = false;
  std::optional<std::pair<bool, Source>> m_captured;
};

}  // namespace tumble::input
