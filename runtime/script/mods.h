#pragma once
// Mods: discovery in search folders, manifests (mod.lua), dependencies and
// load order, and `tumble check`.
//
// A manifest returns {name, version, title, api, depends = {"base >= 1.0"}}.
// `name` must match the folder name; `version` is semver (MAJOR.MINOR.PATCH);
// `api` is the Lua API version the mod was written for (1..kApiVersion).
//
// A dependency is "name", "name CONSTRAINTS" or either with a `?` after the
// name (or at the end) for an optional one: "physics_extras?" or
// "physics_extras? >= 2". Constraints, comma-separated, all must hold:
//   >= 1.2   > 1.2   <= 2   < 2.0.0   = 1.2.3   (missing parts are 0)
//   ^1.2.3   same major: >= 1.2.3, < 2.0.0 (for 0.x: same minor; 0.0.x: same patch)
//   ~1.2.3   same minor: >= 1.2.3, < 1.3.0 (~1: >= 1.0.0, < 2.0.0)
// A pre-release (1.0.0-beta) sorts before its release. A required dependency
// must be present with a matching version; an optional one may be absent,
// but if present its version must match. Mods load in dependency order, ties
// by name; a mod with a missing or mismatched dependency, or in a cycle, is
// not loaded and each reason is a problem naming mod.lua and the line.
#include <cstddef>
#include <string>
#include <vector>

#include "core/result.h"

namespace tumble::script {

constexpr int kApiVersion = 1;
/// Longest manifest strings accepted (longer ones are a problem of that mod,
/// which is then not loaded; every other mod still loads).
constexpr std::size_t kMaxModNameChars = 64;
constexpr std::size_t kMaxVersionChars = 64;
constexpr std::size_t kMaxTitleChars = 200;
constexpr std::size_t kMaxDependencyChars = 200;

struct VersionConstraint {
  std::string op;       ///< ">=", ">", "<=", "<", "=", "^" or "~"
  std::string version;  ///< "1", "1.2" or "1.2.3", optionally with -prerelease
};

struct ModDependency {
  std::string name;
  bool optional = false;                       ///< written "name?"
  std::vector<VersionConstraint> constraints;  ///< empty: any version
  std::string text;                            ///< as written in mod.lua
};

/// Parses one `depends` entry; the error says what form is expected.
Result<ModDependency> parseDependency(const std::string& text);
/// Compares two semver strings (build metadata ignored): <0, 0, >0.
/// Missing minor/patch count as 0. Returns 0 for unparsable input.
int compareVersions(const std::string& a, const std::string& b);
/// Whether `version` (semver) satisfies every constraint.
bool satisfies(const std::string& version, const std::vector<VersionConstraint>& constraints);

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
  std::string mod;           ///< the mod it concerns, when known
  std::string text() const;  ///< "file:line: message"
};

/// Reads and validates <dir>/mod.lua.
Result<ModInfo> loadManifest(const std::string& dir);

/// Every problem in a mod folder at once: manifest fields, dependencies
/// (resolved against the mods in searchDirs; without them, against the mod's
/// sibling folders), every .lua file compiles, every emitters/*.lua file
/// is a valid emitter definition (each bad field: file:line: field 'x': ...).
std::vector<ModProblem> checkMod(const std::string& dir);
std::vector<ModProblem> checkMod(const std::string& dir, const std::vector<std::string>& searchDirs);

class ModRegistry {
 public:
  /// Mods in each search folder (each subfolder with a mod.lua). Later
  /// folders override earlier ones with the same mod name. Broken manifests,
  /// missing or mismatched dependencies and cycles are kept as problems, not
  /// fatal; the mods they concern are left out of mods().
  static ModRegistry discover(const std::vector<std::string>& searchDirs);

  const ModInfo* find(const std::string& name) const;
  /// Loadable mods in load order: every mod after its dependencies (optional
  /// ones too, when present), ties broken by name.
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
