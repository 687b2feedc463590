#pragma once
// Tunables: values a scenario declares for designers to change while playing
// (tune.number / tune.bool / tune.choice in Lua, bind_tune.cpp), shown in
// the tuning panel (F2), set from the command line (--set tune.NAME=VALUE)
// and saved per mod in an overrides file.
//
// Index
//   Tunable                 one declared value: kind, limits, default, user value
//   Tunables                the scenario's set: declare, set, reset, overrides
//   tuneOverridesPath()     <config dir>/tune/<mod>.json
//
// The live value is the user's value (panel, --set, overrides file) when
// there is one, else the default the script declares. A script reads it each
// time it calls tune.number(...) or tune.get(name), so a change applies at
// the next call, without a restart. A default edited in the file and hot
// reloaded applies too, unless the user has set a value (the panel's
// "reset" returns to the default).
//
// Overrides file (JSON, written atomically): {"mod": "mymod", "values":
// {"gravity": 12.5, "fancy": true, "mode": "hard"}}. Values for tunables not
// declared yet wait until the script declares them.
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "core/result.h"

namespace tumble::script {

struct Tunable {
  enum class Kind { Number, Bool, Choice };
  std::string name;
  Kind kind = Kind::Number;
  std::string unit;         ///< Number: unit text shown after the value ("m/s^2"), may be empty
  std::string description;  ///< one line for the panel's tooltip
  // Number: min/max are inclusive limits (infinite: none); step 0 = continuous.
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  double step = 0;
  std::vector<std::string> choices;  ///< Choice: the allowed strings
  // The value: a number, 0/1 for Bool, the index into choices for Choice.
  double defaultValue = 0;
  std::optional<double> userValue;  ///< set by the panel, --set or the overrides file
  double value() const { return userValue ? *userValue : defaultValue; }
  bool isUserSet() const { return userValue.has_value(); }
  /// The value as text: "12.5", "true", "hard".
  std::string valueText() const;
};

class Tunables {
 public:
  /// Declares (or re-declares, e.g. after a hot reload) a tunable; returns
  /// its index. A re-declaration updates limits, unit and default and keeps
  /// the user's value (clamped to new limits). Errors (bad limits, a default
  /// outside them, another kind under the same name) name the tunable.
  Result<int> declare(Tunable spec);
  /// Index of a declared tunable, -1 if none.
  int find(const std::string& name) const;
  const std::vector<Tunable>& items() const { return m_items; }
  const Tunable& operator[](int i) const { return m_items[std::size_t(i)]; }

  /// Sets the user's value of a declared tunable (Number: within its limits;
  /// Bool: 0 or 1; Choice: an index).
  Status set(const std::string& name, double value);
  /// Parses `text` for the tunable (number, true/false, a choice's name) and
  /// sets it; for an undeclared name the text waits for the declaration.
  /// `origin` names where the text came from in error messages ("--set").
  Status setText(const std::string& name, const std::string& text, const std::string& origin);
  /// Back to the declared default.
  void reset(const std::string& name);
  void resetAll();
  /// Bumped by every change of a value: the panel and tests can tell.
  std::uint64_t revision() const { return m_revision; }

  /// Reads the overrides file; a missing file is no error. A corrupt one
  /// leaves every value at its default and the message names the file and
  /// what is wrong.
  Status loadOverrides(const std::string& path);
  /// Writes every user value (declared or still waiting) atomically.
  Status saveOverrides(const std::string& path, const std::string& mod) const;
  /// Problems found when a pending value met its declaration ("--set
  /// tune.gravity=abc: expected a number"); taken (cleared) by the caller.
  std::vector<std::string> takeProblems() { return std::exchange(m_problems, {}); }
  /// Names given a value by `origin` (e.g. "--set") that nothing declared.
  std::vector<std::string> undeclared(const std::string& origin) const;

 private:
  struct Pending {
    std::string text;
    std::string origin;
  };
  Status parseInto(const Tunable& t, const std::string& text, const std::string& origin, double* out) const;
  std::vector<Tunable> m_items;
  std::map<std::string, Pending> m_pending;  ///< user values for names not declared yet
  std::vector<std::string> m_problems;
  std::uint64_t m_revision = 0;
};

/// The folder for user settings: $TUMBLE_CONFIG_DIR, else
/// $XDG_CONFIG_HOME/tumble, else ~/.config/tumble.
std::string userConfigDir();
/// Folder of the mods' save data (save.read / save.write), one subfolder per
/// mod: $TUMBLE_SAVE_DIR, else $XDG_DATA_HOME/tumble/saves, else
/// ~/.local/share/tumble/saves.
std::string savesDir();
/// <userConfigDir()>/tune/<mod>.json
std::string tuneOverridesPath(const std::string& mod);

}  // namespace tumble::script
