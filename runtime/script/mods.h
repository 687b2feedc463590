#pragma once
// Mods: discovery in search folders, manifests (mod.lua) and `tumble check`.
//
// A manifest returns {name, version, title, api, depends = {"base >= 1.0"}}.
// `name` must match the folder name; `version` is semver (MAJOR.MINOR.PATCH);
// `api` is the Lua API version the mod was written for (kApiVersion now).
#include <string>
#include <vector>

#include "core/result.h"

namespace tumble::script {

constexpr int kApiVersion = 1;

struct ModDependency {
  std::string name;
  std::string op;       ///< ">=", "=", ">", "<", "<=" or "" (any version)
  std::string version;  ///< semver or ""
};

struct ModInfo {
  std::string name;
  std::string version;
  std::string title;
  int api = kApiVersion;
  std::string dir;  ///< absolute folder
  std::vector<ModDependency> depends;
};

struct ModProblem {
  std::string file;  ///< path as given (folder/file)
  int line = 0;
  std::string message;
  std::string text() const;  ///< "file:line: message"
};

/// Reads and validates <dir>/mod.lua.
Result<ModInfo> loadManifest(const std::string& dir);

/// Every problem in a mod folder at once: manifest fields, every .lua file
/// compiles, scenario files return a table.
std::vector<ModProblem> checkMod(const std::string& dir);

class ModRegistry {
 public:
  /// Mods in each search folder (each subfolder with a mod.lua). Later
  /// folders override earlier ones with the same mod name. Broken manifests
  /// are kept as problems, not fatal.
  static ModRegistry discover(const std::vector<std::string>& searchDirs);

  const ModInfo* find(const std::string& name) const;
  const std::vector<ModInfo>& mods() const { return m_mods; }
  const std::vector<ModProblem>& problems() const { return m_problems; }
  /// Names (without .lua) of files in <mod>/<folder>/, sorted.
  static std::vector<std::string> listLua(const ModInfo& mod, const std::string& folder);

 private:
  std::vector<ModInfo> m_mods;
  std::vector<ModProblem> m_problems;
};

/// Splits "mod:scenario" (or "scenario", meaning base). Error names the form.
Result<std::pair<std::string, std::string>> parseScenarioRef(const std::string& ref);

}  // namespace tumble::script
