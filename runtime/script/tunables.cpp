#include "script/tunables.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/file_util.h"

namespace fs = std::filesystem;

namespace tumble::script {

namespace {
std::string numberText(double v) {
  std::ostringstream out;
  out.precision(10);
  out << v;
  return out.str();
}

const char* kindName(Tunable::Kind k) {
  switch (k) {
    case Tunable::Kind::Number: return "number";
    case Tunable::Kind::Bool: return "bool";
    case Tunable::Kind::Choice: return "choice";
  }
  return "?";
}

std::string limitsText(const Tunable& t) {
  std::string s = "[";
  s += std::isfinite(t.min) ? numberText(t.min) : std::string("-inf");
  s += ", ";
  s += std::isfinite(t.max) ? numberText(t.max) : std::string("inf");
  s += "]";
  return s;
}
}  // namespace

std::string Tunable::valueText() const {
  double v = value();
  switch (kind) {
    case Kind::Number: return numberText(v);
    case Kind::Bool: return v != 0 ? "true" : "false";
    case Kind::Choice: {
      auto i = std::size_t(v);
      return i < choices.size() ? choices[i] : std::string();
    }
  }
  return {};
}

Result<int> Tunables::declare(Tunable spec) {
  // Built only for a message: this runs for every tune.* call.
  auto what = [&spec] { return "tune." + std::string(kindName(spec.kind)) + "(\"" + spec.name + "\")"; };
  if (spec.name.empty()) return makeError("tune: a tunable needs a name");
  if (spec.kind == Tunable::Kind::Number) {
    if (!(spec.min <= spec.max)) return makeError(what() + ": min must be <= max, got " + limitsText(spec));
    if (!std::isfinite(spec.defaultValue) || spec.defaultValue < spec.min || spec.defaultValue > spec.max)
      return makeError(what() + ": default " + numberText(spec.defaultValue) + " is outside " + limitsText(spec));
    if (!(spec.step >= 0) || !std::isfinite(spec.step)) return makeError(what() + ": step must be a number >= 0");
  }
  if (spec.kind == Tunable::Kind::Choice && spec.choices.empty())
    return makeError(what() + ": needs at least one choice");
  int index = find(spec.name);
  if (index >= 0) {
    Tunable& t = m_items[std::size_t(index)];
    if (t.kind != spec.kind)
      return makeError(what() + ": \"" + spec.name + "\" is already a " + kindName(t.kind) +
                       " tunable; one name, one kind");
    // Same declaration as last time (the common case: tune.number in
    // on_update every step): nothing to do.
    if (t.defaultValue == spec.defaultValue && t.min == spec.min && t.max == spec.max && t.step == spec.step &&
        t.unit == spec.unit && t.choices == spec.choices && t.description == spec.description)
      return index;
    std::optional<double> user = t.userValue;
    if (user && t.kind == Tunable::Kind::Number) *user = std::clamp(*user, spec.min, spec.max);
    if (user && t.kind == Tunable::Kind::Choice) {
      // Keep the chosen name if it still exists.
      std::string chosen = t.valueText();
      auto it = std::find(spec.choices.begin(), spec.choices.end(), chosen);
      user = it == spec.choices.end() ? std::nullopt : std::optional<double>(double(it - spec.choices.begin()));
    }
    t = std::move(spec);
    t.userValue = user;
    ++m_revision;
    return index;
  }
  m_items.push_back(std::move(spec));
  index = int(m_items.size() - 1);
  if (auto it = m_pending.find(m_items.back().name); it != m_pending.end()) {
    double v = 0;
    if (Status st = parseInto(m_items.back(), it->second.text, it->second.origin, &v); st)
      m_items.back().userValue = v;
    else
      m_problems.push_back(st.error());
    m_pending.erase(it);
  }
  ++m_revision;
  return index;
}

int Tunables::find(const std::string& name) const {
  for (std::size_t i = 0; i < m_items.size(); ++i)
    if (m_items[i].name == name) return int(i);
  return -1;
}

Status Tunables::parseInto(const Tunable& t, const std::string& text, const std::string& origin, double* out) const {
  const std::string where = origin + " tune." + t.name + "=" + text;
  switch (t.kind) {
    case Tunable::Kind::Number: {
      char* end = nullptr;
      double v = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != 0 || !std::isfinite(v))
        return makeError(where + ": expected a number" + (t.unit.empty() ? "" : " in " + t.unit));
      if (v < t.min || v > t.max) return makeError(where + ": outside " + limitsText(t));
      *out = v;
      return Ok{};
    }
    case Tunable::Kind::Bool:
      if (text != "true" && text != "false") return makeError(where + ": expected true or false");
      *out = text == "true" ? 1 : 0;
      return Ok{};
    case Tunable::Kind::Choice: {
      auto it = std::find(t.choices.begin(), t.choices.end(), text);
      if (it == t.choices.end()) {
        std::string known;
        for (const auto& c : t.choices) known += (known.empty() ? "" : ", ") + c;
        return makeError(where + ": expected one of " + known);
      }
      *out = double(it - t.choices.begin());
      return Ok{};
    }
  }
  return makeError(where + ": unknown kind");
}

Status Tunables::set(const std::string& name, double value) {
  int i = find(name);
  if (i < 0) return makeError("tune." + name + ": no such tunable (the scenario has not declared it)");
  Tunable& t = m_items[std::size_t(i)];
  switch (t.kind) {
    case Tunable::Kind::Number:
      if (!std::isfinite(value) || value < t.min || value > t.max)
        return makeError("tune." + name + " = " + numberText(value) + ": outside " + limitsText(t));
      break;
    case Tunable::Kind::Bool: value = value != 0 ? 1 : 0; break;
    case Tunable::Kind::Choice:
      if (!(value >= 0 && value < double(t.choices.size())) || value != std::floor(value))
        return makeError("tune." + name + ": choice index " + numberText(value) + " out of range");
      break;
  }
  t.userValue = value;
  ++m_revision;
  return Ok{};
}

Status Tunables::setText(const std::string& name, const std::string& text, const std::string& origin) {
  int i = find(name);
  if (i < 0) {
    m_pending[name] = {text, origin};
    return Ok{};
  }
  double v = 0;
  if (Status st = parseInto(m_items[std::size_t(i)], text, origin, &v); !st) return st;
  m_items[std::size_t(i)].userValue = v;
  ++m_revision;
  return Ok{};
}

std::vector<std::string> Tunables::undeclared(const std::string& origin) const {
  std::vector<std::string> names;
  for (const auto& [name, p] : m_pending)
    if (p.origin == origin) names.push_back(name);
  return names;
}

void Tunables::reset(const std::string& name) {
  int i = find(name);
  if (i >= 0 && m_items[std::size_t(i)].userValue) {
    m_items[std::size_t(i)].userValue.reset();
    ++m_revision;
  }
  m_pending.erase(name);
}

void Tunables::resetAll() {
  for (auto& t : m_items) t.userValue.reset();
  m_pending.clear();
  ++m_revision;
}

Status Tunables::loadOverrides(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return Ok{};
  auto text = readTextFile(path);
  if (!text) return makeError(text.error());
  const std::string expected = R"(; expected {"mod": "NAME", "values": {"name": number, true/false or "choice", ...}})";
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(*text);
  } catch (const nlohmann::json::parse_error& e) {
    return makeError(path + ": not valid JSON (" + e.what() + ")" + expected + "; using the defaults");
  } catch (const nlohmann::json::exception& e) {  // 1e400: number overflow (out_of_range)
    return makeError(path + ": a number is out of range (" + e.what() + "); numbers must fit a double" + expected +
                     "; using the defaults");
  }
  if (!doc.is_object() || !doc.contains("values") || !doc["values"].is_object())
    return makeError(path + ": no \"values\" object" + expected + "; using the defaults");
  std::map<std::string, std::string> texts;
  for (const auto& [name, v] : doc["values"].items()) {
    if (v.is_boolean()) texts[name] = v.get<bool>() ? "true" : "false";
    else if (v.is_number()) texts[name] = numberText(v.get<double>());
    else if (v.is_string()) texts[name] = v.get<std::string>();
    else
      return makeError(path + ": values." + name + " is " + v.type_name() + "; expected a number, true/false or a "
                       "choice's name; using the defaults");
  }
  for (const auto& [name, t] : texts) {
    if (Status st = setText(name, t, path + ":"); !st) m_problems.push_back(st.error() + " (kept the default)");
  }
  return Ok{};
}

Status Tunables::saveOverrides(const std::string& path, const std::string& mod) const {
  nlohmann::json values = nlohmann::json::object();
  for (const auto& [name, p] : m_pending) values[name] = p.text;  // not declared this run: kept as written
  for (const auto& t : m_items) {
    if (!t.userValue) continue;
    switch (t.kind) {
      case Tunable::Kind::Number: values[t.name] = *t.userValue; break;
      case Tunable::Kind::Bool: values[t.name] = *t.userValue != 0; break;
      case Tunable::Kind::Choice: values[t.name] = t.valueText(); break;
    }
  }
  nlohmann::json doc = {{"mod", mod}, {"values", values}};
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  if (ec) return makeError(path + ": cannot create its folder: " + ec.message());
  return writeFileAtomic(path, doc.dump(2) + "\n");
}

std::string userConfigDir() {
  if (const char* env = std::getenv("TUMBLE_CONFIG_DIR"); env && *env) return env;
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg) return (fs::path(xdg) / "tumble").string();
  if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".config/tumble").string();
  return ".tumble-config";
}

std::string tuneOverridesPath(const std::string& mod) {
  return (fs::path(userConfigDir()) / "tune" / (mod + ".json")).string();
}

}  // namespace tumble::script
