#pragma once
// What the main menu offers: the mods found in the mod folders, each mod's
// scenarios (title, the opening comment of the file as description, whether
// it takes a vehicle), and the vehicle definitions a scenario can spawn with
// the figures the picker shows. Read from the mods' files, lazily (a mod's
// scenarios when the player opens it), never by running a scenario.
//
// A driving scenario is one that declares a string parameter `car` in its
// `params` (docs/lua-api.md, "The vehicle picker"): the menu then asks for a
// vehicle and starts the scenario with `--set car=MOD:NAME`.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "script/mods.h"

namespace tumble::app {

/// The scenario parameter through which the vehicle picker hands the chosen
/// vehicle definition (MOD:NAME) to a scenario.
inline constexpr const char* kVehicleParam = "car";

struct ScenarioEntry {
  std::string ref;          ///< MOD:NAME
  std::string name;         ///< file name without .lua
  std::string title;        ///< the scenario's `title` field (its name when it has none)
  std::string description;  ///< the first paragraph of the comment at the top of the file
  std::string file;         ///< absolute path of the scenario file
  bool takesVehicle = false;   ///< declares the `car` parameter
  std::string defaultVehicle;  ///< its declared default (MOD:NAME)
  std::string problem;      ///< why it cannot be read (shown in the menu); empty: fine
};

struct VehicleEntry {
  std::string ref;          ///< MOD:NAME
  std::string name;         ///< the definition's `name` ("Buggy")
  std::string description;
  double mass_kg = 0;       ///< chassis mass
  double peakPower_kW = 0;  ///< from the torque curve
  std::string drive;        ///< "rear-wheel drive", "front-wheel drive", "all-wheel drive", "2 of 3 axles driven"
  double grip = 0;          ///< peak friction coefficient of the tyre's lateral curve (dry tarmac)
  double gripLongitudinal = 0;  ///< peak of the longitudinal curve
  std::string problem;      ///< why the definition does not load; empty: fine
};

class GameCatalog {
 public:
  explicit GameCatalog(std::vector<std::string> modSearchDirs);

  const std::vector<script::ModInfo>& mods() const { return m_registry.mods(); }
  const std::vector<script::ModProblem>& problems() const { return m_registry.problems(); }
  /// The scenarios of one mod (read on first call, then kept). Unknown mod: empty.
  const std::vector<ScenarioEntry>& scenarios(const std::string& mod);
  /// Finds a scenario by MOD:NAME (reads its mod's scenarios if needed).
  const ScenarioEntry* scenario(const std::string& ref);
  /// The vehicles a scenario of `mod` can spawn: those of base, of the mod
  /// and of its dependencies, in load order.
  const std::vector<VehicleEntry>& vehiclesFor(const std::string& mod);

  /// The first paragraph of the leading `--` comment of a Lua file's text.
  static std::string leadingComment(const std::string& luaText);
  /// "rear-wheel drive" etc. from which axles are driven (+Z is forward).
  static std::string driveLayout(const std::vector<bool>& driven, const std::vector<double>& axleZ_m);

 private:
  std::vector<std::string> m_dirs;
  script::ModRegistry m_registry;
  std::map<std::string, std::vector<ScenarioEntry>> m_scenarios;
  std::map<std::string, std::vector<VehicleEntry>> m_vehiclesOfMod, m_vehiclesFor;
  const std::vector<VehicleEntry>& vehiclesOf(const script::ModInfo& mod);
};

}  // namespace tumble::app
