// Bindings as data: the text form, modifiers, merging by mod load order and
// the "did you mean" suggestions. Names come from SDL's own tables
// (SDL_GetScancodeName, SDL_GameControllerGetStringForButton), which work
// without SDL_Init, so `tumble check` validates keys without a window.
#include "input/binding.h"

#include <SDL.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace tumble::input {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

struct NamedCode {
  const char* name;
  int code;
};
constexpr NamedCode kMouseButtons[] = {{"left", SDL_BUTTON_LEFT},
                                       {"middle", SDL_BUTTON_MIDDLE},
                                       {"right", SDL_BUTTON_RIGHT},
                                       {"x1", SDL_BUTTON_X1},
                                       {"x2", SDL_BUTTON_X2}};
constexpr NamedCode kKeyMods[] = {{"ctrl", kModCtrl}, {"shift", kModShift}, {"alt", kModAlt}, {"gui", kModGui}};

std::vector<std::string> namesOf(const NamedCode* begin, const NamedCode* end) {
  std::vector<std::string> out;
  for (const NamedCode* n = begin; n != end; ++n) out.push_back(n->name);
  return out;
}

int findNamed(const NamedCode* begin, const NamedCode* end, const std::string& name) {
  for (const NamedCode* n = begin; n != end; ++n)
    if (name == n->name) return n->code;
  return -1;
}

const char* nameOf(const NamedCode* begin, const NamedCode* end, int code) {
  for (const NamedCode* n = begin; n != end; ++n)
    if (n->code == code) return n->name;
  return "?";
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

Result<Source> parseKey(std::string name, const std::string& whole) {
  Source s;
  s.device = Device::Key;
  // Modifier prefixes: "ctrl+shift+R". A lone "+" style key name does not
  // exist in SDL (it is "Keypad +"), so '+' only separates modifiers.
  for (bool found = true; found;) {
    found = false;
    for (const NamedCode& m : kKeyMods) {
      std::string prefix = std::string(m.name) + "+";
      if (name.size() > prefix.size() && lower(name.substr(0, prefix.size())) == prefix) {
        s.keyMods |= std::uint8_t(m.code);
        name = name.substr(prefix.size());
        found = true;
      }
    }
  }
  SDL_Scancode sc = SDL_GetScancodeFromName(name.c_str());
  if (sc == SDL_SCANCODE_UNKNOWN || name.empty())
    return makeError("\"" + whole + "\": unknown key \"" + name + "\"" + didYouMean(name, keyNames()) +
                     "; key names are SDL's (W, Space, Left, Return, F5, Left Shift, Keypad 8 ...)");
  s.code = int(sc);
  return s;
}

Status parseModifier(const std::string& token, Modifiers& m, const std::string& whole) {
  auto eq = token.find('=');
  std::string key = lower(token.substr(0, eq));
  if (key == "invert" && eq == std::string::npos) {
    m.invert = true;
    return Ok{};
  }
  static const std::vector<std::string> known{"dead_zone", "curve", "invert", "scale"};
  if (eq == std::string::npos || (key != "dead_zone" && key != "curve" && key != "scale")) {
    return makeError("\"" + whole + "\": unknown modifier \"" + token + "\"" + didYouMean(key, known) +
                     "; expected dead_zone=0..0.95, curve=0.2..5, scale=NUMBER or invert");
  }
  std::string num = token.substr(eq + 1);
  char* end = nullptr;
  double v = std::strtod(num.c_str(), &end);
  if (num.empty() || *end != '\0' || !std::isfinite(v))
    return makeError("\"" + whole + "\": " + key + " needs a number, got \"" + num + "\"");
  if (key == "dead_zone") {
    if (v < 0 || v > 0.95) return makeError("\"" + whole + "\": dead_zone must be 0..0.95 (fraction of travel)");
    m.deadZone = v;
  } else if (key == "curve") {
    if (v < 0.2 || v > 5) return makeError("\"" + whole + "\": curve must be an exponent in 0.2..5");
    m.curve = v;
  } else {
    m.scale = v;
  }
  return Ok{};
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

double applyModifiers(double raw, const Modifiers& m) {
  double a = std::fabs(raw);
  if (m.deadZone > 0) a = a <= m.deadZone ? 0.0 : (a - m.deadZone) / (1.0 - m.deadZone);
  if (m.curve != 1 && a > 0) a = std::pow(a, m.curve);
  double v = raw < 0 ? -a : a;
  if (m.invert) v = -v;
  return v * m.scale;
}

const std::vector<std::string>& keyNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (int sc = 0; sc < SDL_NUM_SCANCODES; ++sc) {
      const char* n = SDL_GetScancodeName(SDL_Scancode(sc));
      if (n && *n && SDL_GetScancodeFromName(n) == SDL_Scancode(sc)) out.emplace_back(n);
    }
    return out;
  }();
  return names;
}

const std::vector<std::string>& padButtonNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (int b = 0; b < SDL_CONTROLLER_BUTTON_MAX; ++b)
      if (const char* n = SDL_GameControllerGetStringForButton(SDL_GameControllerButton(b))) out.emplace_back(n);
    return out;
  }();
  return names;
}

const std::vector<std::string>& padAxisNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (int a = 0; a < SDL_CONTROLLER_AXIS_MAX; ++a)
      if (const char* n = SDL_GameControllerGetStringForAxis(SDL_GameControllerAxis(a))) out.emplace_back(n);
    return out;
  }();
  return names;
}

Result<Binding> parseBinding(std::string_view textView) {
  const std::string text(textView);
  static const std::vector<std::string> kinds{"key", "keys", "mouse", "mouse_axis", "wheel", "pad", "pad_axis"};
  auto colon = text.find(':');
  if (colon == std::string::npos || colon + 1 >= text.size())
    return makeError("\"" + text + "\": expected KIND:NAME with KIND one of key, keys, mouse, mouse_axis, wheel, pad, "
                     "pad_axis (for example key:W, keys:A/D, mouse:left, pad:a, pad_axis:leftx)");
  const std::string kind = lower(text.substr(0, colon));
  // Modifiers follow the first ';' after the name's first character (";" is
  // itself a key name: "key:;" binds the semicolon key).
  auto semi = text.find(';', colon + 2);
  std::string name = text.substr(colon + 1, semi == std::string::npos ? std::string::npos : semi - colon - 1);
  Binding b;
  while (semi != std::string::npos) {
    auto next = text.find(';', semi + 1);
    std::string token = text.substr(semi + 1, next == std::string::npos ? std::string::npos : next - semi - 1);
    if (Status st = parseModifier(token, b.modifiers, text); !st) return makeError(st.error());
    semi = next;
  }
  if (kind == "key") {
    auto k = parseKey(name, text);
    if (!k) return makeError(k.error());
    b.source = *k;
  } else if (kind == "keys") {
    auto slash = name.find('/', 1);
    if (slash == std::string::npos || slash + 1 >= name.size())
      return makeError("\"" + text + "\": expected keys:NEGATIVE/POSITIVE, for example keys:A/D or keys:Left/Right");
    auto neg = parseKey(name.substr(0, slash), text);
    if (!neg) return makeError(neg.error());
    auto pos = parseKey(name.substr(slash + 1), text);
    if (!pos) return makeError(pos.error());
    b.source = *neg;
    b.positive = *pos;
    b.pair = true;
  } else if (kind == "mouse") {
    int code = findNamed(std::begin(kMouseButtons), std::end(kMouseButtons), lower(name));
    if (code < 0)
      return makeError("\"" + text + "\": unknown mouse button \"" + name + "\"" +
                       didYouMean(name, namesOf(std::begin(kMouseButtons), std::end(kMouseButtons))) +
                       "; expected left, middle, right, x1 or x2");
    b.source = {Device::MouseButton, code, 0, 0};
  } else if (kind == "mouse_axis" || kind == "wheel") {
    std::string axis = lower(name);
    if (axis != "x" && axis != "y") return makeError("\"" + text + "\": expected " + kind + ":x or " + kind + ":y");
    b.source = {kind == "wheel" ? Device::MouseWheel : Device::MouseMotion, axis == "x" ? 0 : 1, 0, 0};
  } else if (kind == "pad") {
    SDL_GameControllerButton button = SDL_GameControllerGetButtonFromString(lower(name).c_str());
    if (button == SDL_CONTROLLER_BUTTON_INVALID)
      return makeError("\"" + text + "\": unknown gamepad button \"" + name + "\"" + didYouMean(name, padButtonNames()) +
                       "; valid: " + joinNames(padButtonNames()));
    b.source = {Device::PadButton, int(button), 0, 0};
  } else if (kind == "pad_axis") {
    std::string axisName = lower(name);
    std::int8_t half = 0;
    if (!axisName.empty() && (axisName.back() == '+' || axisName.back() == '-')) {
      half = axisName.back() == '+' ? 1 : -1;
      axisName.pop_back();
    }
    SDL_GameControllerAxis axis = SDL_GameControllerGetAxisFromString(axisName.c_str());
    if (axis == SDL_CONTROLLER_AXIS_INVALID)
      return makeError("\"" + text + "\": unknown gamepad axis \"" + axisName + "\"" +
                       didYouMean(axisName, padAxisNames()) + "; valid: " + joinNames(padAxisNames()) +
                       " (add + or - for one half)");
    b.source = {Device::PadAxis, int(axis), half, 0};
  } else {
    return makeError("\"" + text + "\": unknown kind \"" + kind + "\"" + didYouMean(kind, kinds) +
                     "; expected key, keys, mouse, mouse_axis, wheel, pad or pad_axis");
  }
  return b;
}

std::string sourceLabel(const Source& s) {
  switch (s.device) {
    case Device::Key: {
      std::string mods;
      for (const NamedCode& m : kKeyMods)
        if (s.keyMods & m.code) mods += std::string(m.name) + "+";
      return mods + SDL_GetScancodeName(SDL_Scancode(s.code));
    }
    case Device::MouseButton: return std::string("mouse ") + nameOf(std::begin(kMouseButtons), std::end(kMouseButtons), s.code);
    case Device::MouseMotion: return s.code == 0 ? "mouse x" : "mouse y";
    case Device::MouseWheel: return s.code == 0 ? "wheel x" : "wheel y";
    case Device::PadButton: {
      const char* n = SDL_GameControllerGetStringForButton(SDL_GameControllerButton(s.code));
      return std::string("pad ") + (n ? n : "?");
    }
    case Device::PadAxis: {
      const char* n = SDL_GameControllerGetStringForAxis(SDL_GameControllerAxis(s.code));
      return std::string("pad ") + (n ? n : "?") + (s.half > 0 ? "+" : s.half < 0 ? "-" : "");
    }
  }
  return "?";
}

namespace {

std::string sourceText(const Source& s) {
  switch (s.device) {
    case Device::Key: return sourceLabel(s);
    case Device::MouseButton: return nameOf(std::begin(kMouseButtons), std::end(kMouseButtons), s.code);
    case Device::MouseMotion:
    case Device::MouseWheel: return s.code == 0 ? "x" : "y";
    case Device::PadButton:
    case Device::PadAxis: return sourceLabel(s).substr(4);  // without "pad "
  }
  return "?";
}

const char* kindText(const Binding& b) {
  if (b.pair) return "keys";
  switch (b.source.device) {
    case Device::Key: return "key";
    case Device::MouseButton: return "mouse";
    case Device::MouseMotion: return "mouse_axis";
    case Device::MouseWheel: return "wheel";
    case Device::PadButton: return "pad";
    case Device::PadAxis: return "pad_axis";
  }
  return "?";
}

std::string modifierText(const Modifiers& m, const char* sep, const char* eq) {
  std::string out;
  if (m.deadZone != 0) out += sep + std::string("dead_zone") + eq + number(m.deadZone);
  if (m.curve != 1) out += sep + std::string("curve") + eq + number(m.curve);
  if (m.invert) out += sep + std::string("invert");
  if (m.scale != 1) out += sep + std::string("scale") + eq + number(m.scale);
  return out;
}

}  // namespace

std::string toText(const Binding& b) {
  std::string out = std::string(kindText(b)) + ":" + sourceText(b.source);
  if (b.pair) {
    out += '/';
    out += sourceText(b.positive);
  }
  out += modifierText(b.modifiers, ";", "=");
  return out;
}

std::string bindingLabel(const Binding& b) {
  std::string out = b.pair ? sourceLabel(b.source) + " / " + sourceLabel(b.positive) : sourceLabel(b.source);
  std::string mods = modifierText(b.modifiers, ", ", " ");
  if (!mods.empty()) out += " (" + mods.substr(2) + ")";
  return out;
}

const ActionDef* BindingSet::findAction(std::string_view name) const {
  for (const ActionDef& a : actions)
    if (a.name == name) return &a;
  return nullptr;
}

const ContextDef* BindingSet::findContext(std::string_view name) const {
  for (const ContextDef& c : contexts)
    if (c.name == name) return &c;
  return nullptr;
}

void mergeBindings(BindingSet& into, const BindingSet& later, std::vector<std::string>& problems) {
  for (const ContextDef& c : later.contexts) {
    auto it = std::find_if(into.contexts.begin(), into.contexts.end(), [&](const ContextDef& x) { return x.name == c.name; });
    if (it == into.contexts.end()) into.contexts.push_back(c);
    else *it = c;
  }
  for (const ActionDef& a : later.actions) {
    auto it = std::find_if(into.actions.begin(), into.actions.end(), [&](const ActionDef& x) { return x.name == a.name; });
    if (it == into.actions.end()) {
      into.actions.push_back(a);
    } else if (it->type != a.type || it->context != a.context) {
      problems.push_back("action \"" + a.name + "\" of mod " + a.mod + " is a " +
                         (a.type == ActionType::Axis ? "axis" : "button") + " in context \"" + a.context +
                         "\", but mod " + it->mod + " declared it a " +
                         (it->type == ActionType::Axis ? "axis" : "button") + " in context \"" + it->context +
                         "\"; a later mod may only change an action's default bindings (kept " + it->mod + "'s)");
    } else {
      *it = a;
    }
  }
}

std::vector<std::string> suggestNames(std::string_view nameView, const std::vector<std::string>& valid, int max) {
  const std::string name = lower(nameView);
  std::vector<std::pair<std::size_t, std::string>> scored;
  for (const std::string& v : valid) {
    std::string lv = lower(v);
    std::size_t d = editDistance(name, lv);
    bool prefix = !name.empty() && (lv.rfind(name, 0) == 0 || name.rfind(lv, 0) == 0) && lv.size() > 1;
    std::size_t limit = std::max<std::size_t>(1, std::min(name.size(), lv.size()) / 3 + 1);
    if (d <= limit || prefix) scored.emplace_back(prefix ? std::min<std::size_t>(d, 1) : d, v);
  }
  std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  for (const auto& [d, v] : scored) {
    if (int(out.size()) >= max) break;
    if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
  }
  return out;
}

std::string didYouMean(std::string_view name, const std::vector<std::string>& valid) {
  auto close = suggestNames(name, valid);
  return close.empty() ? std::string() : " (did you mean: " + joinNames(close) + "?)";
}

}  // namespace tumble::input
