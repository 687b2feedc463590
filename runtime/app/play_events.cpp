#include "app/play_events.h"

#include <SDL.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/file_util.h"

namespace tumble::app {

namespace {

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

bool parseNumber(const std::string& text, double& out) {
  std::istringstream in(text);
  in >> out;
  return in && in.eof() && std::isfinite(out);
}

// Splits off the last whitespace-separated word.
std::pair<std::string, std::string> splitLast(const std::string& s) {
  const auto at = s.find_last_of(" \t");
  if (at == std::string::npos) return {"", s};
  return {trim(s.substr(0, at)), s.substr(at + 1)};
}

constexpr const char* kForm =
    "expected FRAME down|up SOURCE, FRAME axis pad_axis:NAME VALUE, FRAME move X Y, FRAME wheel Y | X Y, or FRAME quit";

}  // namespace

Result<std::vector<PlayEvent>> parsePlayEvents(const std::string& text, const std::string& name) {
  std::vector<PlayEvent> out;
  std::istringstream lines(text);
  std::string raw;
  int lineNo = 0;
  long long lastFrame = 0;
  while (std::getline(lines, raw)) {
    ++lineNo;
    const std::string line = trim(raw.substr(0, raw.find('#')));
    if (line.empty()) continue;
    auto fail = [&](const std::string& why) {
      return makeError(name + ":" + std::to_string(lineNo) + ": " + why + " (line: \"" + line + "\")");
    };
    std::istringstream words(line);
    std::string frameText, verb;
    words >> frameText >> verb;
    std::string rest;
    std::getline(words, rest);
    rest = trim(rest);
    PlayEvent e;
    e.line = lineNo;
    double frame = 0;
    if (!parseNumber(frameText, frame) || frame < 0 || frame != std::floor(frame) || frame > 1e12)
      return fail("the frame must be a whole number >= 0, got \"" + frameText + "\"; " + kForm);
    e.frame = (long long)frame;
    if (e.frame < lastFrame)
      return fail("frame " + std::to_string(e.frame) + " comes after frame " + std::to_string(lastFrame) +
                  "; events must be in frame order");
    lastFrame = e.frame;
    if (verb == "down" || verb == "up") {
      e.kind = verb == "down" ? PlayEvent::Kind::Down : PlayEvent::Kind::Up;
      auto b = input::parseBinding(rest);
      if (!b) return fail(b.error());
      const input::Device d = b->source.device;
      if (b->pair || (d != input::Device::Key && d != input::Device::MouseButton && d != input::Device::PadButton))
        return fail("\"" + rest + "\" is not a key, mouse button or pad button (key:W, mouse:left, pad:a)");
      if (b->source.keyMods) return fail("hold the modifier key with its own down line instead of \"" + rest + "\"");
      e.source = b->source;
    } else if (verb == "axis") {
      auto [sourceText, valueText] = splitLast(rest);
      auto b = input::parseBinding(sourceText);
      if (!b) return fail(b.error());
      if (b->source.device != input::Device::PadAxis || b->source.half != 0)
        return fail("\"" + sourceText + "\" is not a whole pad axis (pad_axis:leftx, lefty, rightx, righty, lefttrigger, righttrigger)");
      if (!parseNumber(valueText, e.value) || e.value < -1 || e.value > 1)
        return fail("the axis value must be a number in -1..1, got \"" + valueText + "\"");
      e.kind = PlayEvent::Kind::Axis;
      e.source = b->source;
    } else if (verb == "move" || verb == "wheel") {
      std::istringstream nums(rest);
      std::vector<double> v;
      std::string word;
      while (nums >> word) {
        double x = 0;
        if (!parseNumber(word, x)) return fail("\"" + word + "\" is not a number");
        v.push_back(x);
      }
      if (verb == "move") {
        if (v.size() != 2 || v[0] < 0 || v[1] < 0) return fail("move takes two pixel coordinates >= 0: FRAME move X Y");
        e.kind = PlayEvent::Kind::Move;
        e.x = float(v[0]), e.y = float(v[1]);
      } else {
        if (v.empty() || v.size() > 2) return fail("wheel takes notches: FRAME wheel Y, or FRAME wheel X Y");
        e.kind = PlayEvent::Kind::Wheel;
        e.x = v.size() == 2 ? float(v[0]) : 0.0f;
        e.y = float(v.back());
      }
    } else if (verb == "quit") {
      if (!rest.empty()) return fail("quit takes nothing after it");
      e.kind = PlayEvent::Kind::Quit;
    } else {
      return fail(verb.empty() ? std::string("no event after the frame; ") + kForm
                               : "unknown event \"" + verb + "\"; " + kForm);
    }
    out.push_back(e);
  }
  return out;
}

Result<std::vector<PlayEvent>> loadPlayEvents(const std::string& path) {
  auto text = readTextFile(path);
  if (!text) return makeError("events file: " + text.error());
  return parsePlayEvents(*text, path);
}

SDL_Event toSdlEvent(const PlayEvent& e, unsigned windowId, float pointer[2]) {
  SDL_Event ev{};
  const Uint32 now = SDL_GetTicks();
  switch (e.kind) {
    case PlayEvent::Kind::Down:
    case PlayEvent::Kind::Up: {
      const bool down = e.kind == PlayEvent::Kind::Down;
      switch (e.source.device) {
        case input::Device::Key:
          ev.type = down ? SDL_KEYDOWN : SDL_KEYUP;
          ev.key.timestamp = now;
          ev.key.windowID = windowId;
          ev.key.state = down ? SDL_PRESSED : SDL_RELEASED;
          ev.key.keysym.scancode = SDL_Scancode(e.source.code);
          ev.key.keysym.sym = SDL_GetKeyFromScancode(SDL_Scancode(e.source.code));
          break;
        case input::Device::MouseButton:
          ev.type = down ? SDL_MOUSEBUTTONDOWN : SDL_MOUSEBUTTONUP;
          ev.button.timestamp = now;
          ev.button.windowID = windowId;
          ev.button.button = Uint8(e.source.code);
          ev.button.state = down ? SDL_PRESSED : SDL_RELEASED;
          ev.button.clicks = 1;
          ev.button.x = int(std::lround(pointer[0]));
          ev.button.y = int(std::lround(pointer[1]));
          break;
        default:  // PadButton (the parser allows nothing else)
          ev.type = down ? SDL_CONTROLLERBUTTONDOWN : SDL_CONTROLLERBUTTONUP;
          ev.cbutton.timestamp = now;
          ev.cbutton.button = Uint8(e.source.code);
          ev.cbutton.state = down ? SDL_PRESSED : SDL_RELEASED;
          break;
      }
      break;
    }
    case PlayEvent::Kind::Axis:
      ev.type = SDL_CONTROLLERAXISMOTION;
      ev.caxis.timestamp = now;
      ev.caxis.axis = Uint8(e.source.code);
      ev.caxis.value = Sint16(std::lround(std::clamp(e.value, -1.0, 1.0) * 32767.0));
      break;
    case PlayEvent::Kind::Move:
      ev.type = SDL_MOUSEMOTION;
      ev.motion.timestamp = now;
      ev.motion.windowID = windowId;
      ev.motion.x = int(std::lround(e.x));
      ev.motion.y = int(std::lround(e.y));
      ev.motion.xrel = int(std::lround(e.x - pointer[0]));
      ev.motion.yrel = int(std::lround(e.y - pointer[1]));
      pointer[0] = e.x, pointer[1] = e.y;
      break;
    case PlayEvent::Kind::Wheel:
      ev.type = SDL_MOUSEWHEEL;
      ev.wheel.timestamp = now;
      ev.wheel.windowID = windowId;
      ev.wheel.x = int(std::lround(e.x));
      ev.wheel.y = int(std::lround(e.y));
      ev.wheel.preciseX = e.x;
      ev.wheel.preciseY = e.y;
      ev.wheel.direction = SDL_MOUSEWHEEL_NORMAL;
      break;
    case PlayEvent::Kind::Quit:
      ev.type = SDL_QUIT;
      ev.quit.timestamp = now;
      break;
  }
  return ev;
}

}  // namespace tumble::app
