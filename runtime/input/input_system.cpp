#include "input/input_system.h"

#include <SDL.h>

#include <algorithm>
#include <cmath>

#include "core/log.h"

namespace tumble::input {

namespace {

// Pads report axes as -32768..32767 (sticks) and 0..32767 (triggers).
constexpr float kPadAxisScale = 1.0f / 32767.0f;
// A pad axis pushed this far counts as a choice while capturing.
constexpr float kCaptureAxisTravel = 0.5f;

bool sameSource(const Source& a, const Source& b) {
  // A half axis and the whole axis share the stick: one shadows the other.
  return a.device == b.device && a.code == b.code && (a.device != Device::Key || a.keyMods == b.keyMods);
}

std::uint8_t heldMods(const std::array<bool, 512>& keys) {
  std::uint8_t m = 0;
  if (keys[SDL_SCANCODE_LCTRL] || keys[SDL_SCANCODE_RCTRL]) m |= kModCtrl;
  if (keys[SDL_SCANCODE_LSHIFT] || keys[SDL_SCANCODE_RSHIFT]) m |= kModShift;
  if (keys[SDL_SCANCODE_LALT] || keys[SDL_SCANCODE_RALT]) m |= kModAlt;
  if (keys[SDL_SCANCODE_LGUI] || keys[SDL_SCANCODE_RGUI]) m |= kModGui;
  return m;
}

}  // namespace

InputSystem::InputSystem(BindingSet definitions) : m_defs(std::move(definitions)) {
  for (std::size_t i = 0; i < m_defs.actions.size(); ++i) {
    m_index[m_defs.actions[i].name] = int(i);
    m_bindings.push_back(m_defs.actions[i].bindings);
  }
  m_state.resize(m_defs.actions.size());
  for (const ContextDef& c : m_defs.contexts) m_contextOn[c.name] = c.enabled;
  rebuildOwnership();
}

void InputSystem::redefine(BindingSet definitions) {
  const Overrides kept = overrides();
  const std::map<std::string, bool> contextsWere = m_contextOn;
  std::unordered_map<std::string, ActionState> stateWas;
  for (std::size_t i = 0; i < m_defs.actions.size(); ++i) stateWas[m_defs.actions[i].name] = m_state[i];
  m_defs = std::move(definitions);
  m_index.clear();
  m_bindings.clear();
  m_state.assign(m_defs.actions.size(), ActionState{});
  for (std::size_t i = 0; i < m_defs.actions.size(); ++i) {
    m_index[m_defs.actions[i].name] = int(i);
    m_bindings.push_back(m_defs.actions[i].bindings);
    if (auto it = stateWas.find(m_defs.actions[i].name); it != stateWas.end()) m_state[i] = it->second;
  }
  m_contextOn.clear();
  for (const ContextDef& c : m_defs.contexts) {
    auto was = contextsWere.find(c.name);
    m_contextOn[c.name] = was != contextsWere.end() ? was->second : c.enabled;
  }
  m_foreign = {};
  rebuildOwnership();
  (void)applyOverrides(kept);  // bindings that no longer parse were reported when saved
}

InputSystem::~InputSystem() {
  // After an SDL_Quit the controllers are gone already; closing them again
  // would touch freed memory.
  if (!m_gamepads || !SDL_WasInit(SDL_INIT_GAMECONTROLLER)) return;
  for (void* pad : m_pads) SDL_GameControllerClose(static_cast<SDL_GameController*>(pad));
  SDL_QuitSubSystem(SDL_INIT_GAMECONTROLLER);
}

int InputSystem::find(std::string_view name) const {
  auto it = m_index.find(name);
  return it == m_index.end() ? -1 : it->second;
}

std::string InputSystem::unknownActionMessage(std::string_view name) const {
  std::vector<std::string> names;
  for (const ActionDef& a : m_defs.actions) names.push_back(a.name);
  std::string msg = "unknown action \"" + std::string(name) + "\"" + didYouMean(name, names);
  if (names.empty()) msg += " (no mod loaded in this run declares actions; see mods/base/bindings.lua)";
  return msg;
}

Status InputSystem::enableGamepads() {
  if (m_gamepads) return Ok{};
  if (SDL_InitSubSystem(SDL_INIT_GAMECONTROLLER) != 0)
    return makeError(std::string("gamepads unavailable: ") + SDL_GetError());
  m_gamepads = true;  // already connected pads arrive as SDL_CONTROLLERDEVICEADDED events
  return Ok{};
}

bool InputSystem::contextOn(const std::string& name) const {
  auto it = m_contextOn.find(name);
  return it == m_contextOn.end() || it->second;
}

void InputSystem::rebuildOwnership() {
  // A binding is shadowed when an enabled context of higher priority binds
  // the same source. Tens of actions: the quadratic walk costs nothing and
  // runs only when bindings or contexts change.
  auto priorityOf = [&](const std::string& ctx) {
    const ContextDef* c = m_defs.findContext(ctx);
    return c ? c->priority : 0;
  };
  m_owned.assign(m_bindings.size(), {});
  for (std::size_t a = 0; a < m_bindings.size(); ++a) {
    const ActionDef& def = m_defs.actions[a];
    const bool on = contextOn(def.context);
    const int prio = priorityOf(def.context);
    m_owned[a].resize(m_bindings[a].size());
    for (std::size_t b = 0; b < m_bindings[a].size(); ++b) {
      auto shadowed = [&](const Source& s) {
        for (std::size_t o = 0; o < m_bindings.size(); ++o) {
          const ActionDef& other = m_defs.actions[o];
          if (!contextOn(other.context) || priorityOf(other.context) <= prio) continue;
          for (const Binding& ob : m_bindings[o])
            if (sameSource(ob.source, s) || (ob.pair && sameSource(ob.positive, s))) return true;
        }
        return false;
      };
      const Binding& bind = m_bindings[a][b];
      m_owned[a][b].owned = on && !shadowed(bind.source);
      m_owned[a][b].ownedPositive = on && bind.pair && !shadowed(bind.positive);
    }
  }
}

double InputSystem::sourceValue(const Source& s, bool withMotion) const {
  switch (s.device) {
    case Device::Key:
      if (s.code < 0 || s.code >= int(m_keys.size()) || !m_keys[std::size_t(s.code)]) return 0;
      return (heldMods(m_keys) & s.keyMods) == s.keyMods ? 1.0 : 0.0;
    case Device::MouseButton: return s.code >= 0 && s.code < int(m_mouse.size()) && m_mouse[std::size_t(s.code)] ? 1 : 0;
    case Device::MouseMotion: return withMotion ? m_motion[s.code & 1] : 0.0;
    case Device::MouseWheel: return withMotion ? m_wheel[s.code & 1] : 0.0;
    case Device::PadButton:
      return s.code >= 0 && s.code < int(m_padButtons.size()) && m_padButtons[std::size_t(s.code)] ? 1 : 0;
    case Device::PadAxis: {
      if (s.code < 0 || s.code >= int(m_padAxes.size())) return 0;
      double v = m_padAxes[std::size_t(s.code)];
      if (s.half > 0) return std::max(v, 0.0);
      if (s.half < 0) return std::max(-v, 0.0);
      return v;
    }
  }
  return 0;
}

double InputSystem::bindingValue(int action, std::size_t b, bool withMotion) const {
  const Binding& bind = m_bindings[std::size_t(action)][b];
  const BoundSource& own = m_owned[std::size_t(action)][b];
  double raw = 0;
  if (bind.pair) {
    raw = (own.ownedPositive ? sourceValue(bind.positive, withMotion) : 0.0) -
          (own.owned ? sourceValue(bind.source, withMotion) : 0.0);
  } else if (own.owned) {
    raw = sourceValue(bind.source, withMotion);
  }
  return raw == 0 ? 0.0 : applyModifiers(raw, bind.modifiers);
}

double InputSystem::evaluate(int action, bool withMotion) const {
  // The binding pushed farthest wins (a key and a stick on one axis do not add up).
  double best = 0;
  for (std::size_t b = 0; b < m_bindings[std::size_t(action)].size(); ++b) {
    double v = bindingValue(action, b, withMotion);
    if (std::fabs(v) > std::fabs(best)) best = v;
  }
  if (m_defs.actions[std::size_t(action)].type == ActionType::Button)
    best = std::clamp(best, 0.0, 1.0);
  return best;
}

bool InputSystem::isDown(int, double v) const { return std::fabs(v) >= kDownThreshold; }

void InputSystem::updateLive() {
  for (int a = 0; a < actionCount(); ++a) {
    ActionState& s = m_state[std::size_t(a)];
    double v = evaluate(a, false);
    bool live = isDown(a, v);
    if (live && !s.live) {
      s.latchPress = true;
      s.latchValue = v;
      if (!s.framePress) {
        s.framePress = true;
        m_framePresses.push_back(a);
      }
    } else if (!live && s.live) {
      s.latchRelease = true;
    }
    s.live = live;
  }
}

std::vector<InputSystem::StepState> InputSystem::stepStates() const {
  std::vector<StepState> out;
  out.reserve(m_state.size());
  for (const ActionState& s : m_state) out.push_back(StepState{s.value, s.down, s.pressed, s.released});
  return out;
}

void InputSystem::step() {
  ++m_steps;
  if (m_playBack) {
    // A replay: the recorded states, and the devices' edges are dropped.
    for (std::size_t a = 0; a < m_state.size(); ++a) {
      ActionState& s = m_state[a];
      const StepState r = a < m_playBack->size() ? (*m_playBack)[a] : StepState{};
      s.value = r.value;
      s.down = r.down;
      s.pressed = r.pressed;
      s.released = r.released;
      s.latchPress = s.latchRelease = false;
    }
    m_playBack.reset();
    m_motion[0] = m_motion[1] = 0;
    m_wheel[0] = m_wheel[1] = 0;
    return;
  }
  for (int a = 0; a < actionCount(); ++a) {
    ActionState& s = m_state[std::size_t(a)];
    const bool prevDown = s.down;
    double v = 0;
    bool downNow = false, repressed = false;
    if (s.injected) {
      v = s.injectValue;
      downNow = isDown(a, v);
    } else {
      v = evaluate(a, true);
      downNow = isDown(a, v);
      if (!downNow && s.latchPress) {  // pressed and released since the last step: a tap
        downNow = true;
        v = s.latchValue;
      }
      repressed = prevDown && s.latchPress && s.latchRelease;
    }
    s.value = v;
    s.down = downNow;
    s.pressed = (downNow && !prevDown) || repressed;
    s.released = (prevDown && !downNow) || repressed;
    s.latchPress = s.latchRelease = false;
  }
  m_motion[0] = m_motion[1] = 0;
  m_wheel[0] = m_wheel[1] = 0;
}

void InputSystem::inject(int action, double value) {
  ActionState& s = m_state[std::size_t(action)];
  s.injected = true;
  s.injectValue = value;
}

void InputSystem::clearInjection(int action) { m_state[std::size_t(action)].injected = false; }

std::vector<int> InputSystem::takeFramePresses() {
  std::vector<int> out;
  out.swap(m_framePresses);
  for (int a : out) m_state[std::size_t(a)].framePress = false;
  return out;
}

Status InputSystem::setContextEnabled(std::string_view name, bool enabled) {
  auto it = m_contextOn.find(std::string(name));
  if (it == m_contextOn.end()) {
    return makeError("unknown input context \"" + std::string(name) + "\"" + didYouMean(name, contextNames()));
  }
  if (it->second == enabled) return Ok{};
  it->second = enabled;
  rebuildOwnership();
  updateLive();  // keys held in a context switched off are released
  return Ok{};
}

bool InputSystem::contextEnabled(std::string_view name) const { return contextOn(std::string(name)); }

std::vector<std::string> InputSystem::contextNames() const {
  std::vector<std::string> out;
  for (const ContextDef& c : m_defs.contexts) out.push_back(c.name);
  return out;
}

bool InputSystem::usedByOwnedBinding(Device device, int code) const {
  for (std::size_t a = 0; a < m_bindings.size(); ++a) {
    for (std::size_t b = 0; b < m_bindings[a].size(); ++b) {
      const Binding& bind = m_bindings[a][b];
      const BoundSource& own = m_owned[a][b];
      if (own.owned && bind.source.device == device && bind.source.code == code) return true;
      if (bind.pair && own.ownedPositive && bind.positive.device == device && bind.positive.code == code) return true;
    }
  }
  return false;
}

void InputSystem::beginCapture() {
  m_capturing = true;
  m_captured.reset();
}

std::optional<std::pair<bool, Source>> InputSystem::takeCaptured() {
  auto out = m_captured;
  m_captured.reset();
  return out;
}

void InputSystem::captureFrom(const SDL_Event& e) {
  Source s;
  switch (e.type) {
    case SDL_KEYDOWN: {
      if (e.key.repeat) return;
      SDL_Scancode sc = e.key.keysym.scancode;
      if (sc == SDL_SCANCODE_ESCAPE) {
        m_captured = std::make_pair(false, Source{});
        m_capturing = false;
        return;
      }
      // A modifier alone waits for the key it modifies.
      if (sc == SDL_SCANCODE_LCTRL || sc == SDL_SCANCODE_RCTRL || sc == SDL_SCANCODE_LSHIFT ||
          sc == SDL_SCANCODE_RSHIFT || sc == SDL_SCANCODE_LALT || sc == SDL_SCANCODE_RALT ||
          sc == SDL_SCANCODE_LGUI || sc == SDL_SCANCODE_RGUI)
        return;
      s = {Device::Key, int(sc), 0, heldMods(m_keys)};
      break;
    }
    case SDL_MOUSEBUTTONDOWN: s = {Device::MouseButton, int(e.button.button), 0, 0}; break;
    case SDL_CONTROLLERBUTTONDOWN: s = {Device::PadButton, int(e.cbutton.button), 0, 0}; break;
    case SDL_CONTROLLERAXISMOTION: {
      float v = float(e.caxis.value) * kPadAxisScale;
      if (std::fabs(v) < kCaptureAxisTravel) return;
      s = {Device::PadAxis, int(e.caxis.axis), std::int8_t(v > 0 ? 1 : -1), 0};  // the half pushed
      break;
    }
    default: return;
  }
  m_captured = std::make_pair(true, s);
  m_capturing = false;
}

bool InputSystem::handleEvent(const SDL_Event& e, bool uiWants) {
  bool consumed = false;
  switch (e.type) {
    case SDL_KEYDOWN:
    case SDL_KEYUP: {
      const bool isDown = e.type == SDL_KEYDOWN;
      const int sc = int(e.key.keysym.scancode);
      if (sc < 0 || sc >= int(m_keys.size())) break;
      if (isDown && e.key.repeat) return usedByOwnedBinding(Device::Key, sc);
      if (m_capturing && isDown) {
        captureFrom(e);  // a modifier alone keeps capturing; it is held for ctrl+X
        if (m_capturing) m_keys[std::size_t(sc)] = true;
        return true;
      }
      if (isDown && uiWants) break;
      m_keys[std::size_t(sc)] = isDown;
      consumed = usedByOwnedBinding(Device::Key, sc);
      break;
    }
    case SDL_MOUSEBUTTONDOWN:
    case SDL_MOUSEBUTTONUP: {
      const bool isDown = e.type == SDL_MOUSEBUTTONDOWN;
      const int b = int(e.button.button);
      if (b < 0 || b >= int(m_mouse.size())) break;
      if (m_capturing && isDown && !uiWants) {
        captureFrom(e);
        return true;
      }
      if (isDown && uiWants) break;
      m_mouse[std::size_t(b)] = isDown;
      consumed = usedByOwnedBinding(Device::MouseButton, b);
      break;
    }
    case SDL_MOUSEMOTION: {
      if (!uiWants) {
        m_motion[0] += e.motion.xrel;
        m_motion[1] += e.motion.yrel;
      }
      if (SDL_Window* w = SDL_GetWindowFromID(e.motion.windowID)) {
        int width = 0, height = 0;
        SDL_GetWindowSize(w, &width, &height);
        if (width > 0 && height > 0)
          setPointer(2.0f * float(e.motion.x) / float(width) - 1.0f, 1.0f - 2.0f * float(e.motion.y) / float(height));
      }
      return false;  // the camera still orbits while a button drags
    }
    case SDL_MOUSEWHEEL: {
      if (uiWants) break;
      const float flip = e.wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -1.0f : 1.0f;
      m_wheel[0] += flip * e.wheel.preciseX;
      m_wheel[1] += flip * e.wheel.preciseY;
      consumed = usedByOwnedBinding(Device::MouseWheel, 1) || usedByOwnedBinding(Device::MouseWheel, 0);
      return consumed;
    }
    case SDL_CONTROLLERBUTTONDOWN:
    case SDL_CONTROLLERBUTTONUP: {
      const int b = int(e.cbutton.button);
      if (b < 0 || b >= int(m_padButtons.size())) break;
      if (m_capturing && e.type == SDL_CONTROLLERBUTTONDOWN) {
        captureFrom(e);
        return true;
      }
      m_padButtons[std::size_t(b)] = e.type == SDL_CONTROLLERBUTTONDOWN;
      consumed = true;
      break;
    }
    case SDL_CONTROLLERAXISMOTION: {
      const int a = int(e.caxis.axis);
      if (a < 0 || a >= int(m_padAxes.size())) break;
      if (m_capturing) {
        captureFrom(e);
        if (!m_capturing) return true;
      }
      m_padAxes[std::size_t(a)] = std::clamp(float(e.caxis.value) * kPadAxisScale, -1.0f, 1.0f);
      consumed = true;
      break;
    }
    case SDL_CONTROLLERDEVICEADDED: {
      if (SDL_GameController* pad = SDL_GameControllerOpen(e.cdevice.which)) {
        m_pads.push_back(pad);
        log::info(std::string("input: gamepad connected: ") + (SDL_GameControllerName(pad) ? SDL_GameControllerName(pad) : "?"));
      }
      return false;
    }
    case SDL_CONTROLLERDEVICEREMOVED: {
      SDL_GameController* pad = SDL_GameControllerFromInstanceID(e.cdevice.which);
      auto it = std::find(m_pads.begin(), m_pads.end(), static_cast<void*>(pad));
      if (it != m_pads.end()) {
        SDL_GameControllerClose(pad);
        m_pads.erase(it);
      }
      m_padButtons.fill(false);  // nothing stays held by a pad that left
      m_padAxes.fill(0);
      break;
    }
    default: return false;
  }
  updateLive();
  return consumed;
}

void InputSystem::setBindings(int action, std::vector<Binding> bindings) {
  m_bindings[std::size_t(action)] = std::move(bindings);
  rebuildOwnership();
  updateLive();
}

void InputSystem::resetBindings(int action) { setBindings(action, m_defs.actions[std::size_t(action)].bindings); }

void InputSystem::resetAllBindings() {
  for (int a = 0; a < actionCount(); ++a) m_bindings[std::size_t(a)] = m_defs.actions[std::size_t(a)].bindings;
  rebuildOwnership();
  updateLive();
}

Overrides InputSystem::overrides() const {
  Overrides out = m_foreign;
  for (int a = 0; a < actionCount(); ++a) {
    const auto& current = m_bindings[std::size_t(a)];
    if (current == m_defs.actions[std::size_t(a)].bindings) continue;
    std::vector<std::string> texts;
    for (const Binding& b : current) texts.push_back(toText(b));
    out[m_defs.actions[std::size_t(a)].name] = std::move(texts);
  }
  return out;
}

std::vector<std::string> InputSystem::applyOverrides(const Overrides& overrides) {
  std::vector<std::string> problems;
  m_foreign.clear();
  for (const auto& [name, texts] : overrides) {
    int a = find(name);
    if (a < 0) {
      m_foreign[name] = texts;  // another mod's action: kept for when it is loaded
      continue;
    }
    std::vector<Binding> list;
    for (const std::string& t : texts) {
      auto b = parseBinding(t);
      if (!b) {
        problems.push_back("action \"" + name + "\": " + b.error() + " (binding skipped)");
        continue;
      }
      if (b->pair && action(a).type != ActionType::Axis) {
        problems.push_back("action \"" + name + "\": \"" + t + "\" is a key pair, which only an axis takes (skipped)");
        continue;
      }
      list.push_back(*b);
    }
    m_bindings[std::size_t(a)] = std::move(list);
  }
  rebuildOwnership();
  updateLive();
  return problems;
}

}  // namespace tumble::input
