#include "app/paths.h"

#include <cstdlib>
#include <filesystem>

namespace tumble::app {

std::string dataDir() {
  if (const char* env = std::getenv("TUMBLE_DATA_DIR"); env && *env) return env;
  return TUMBLE_DATA_DIR;
}

std::string scriptsDir() { return (std::filesystem::path(dataDir()) / "scripts").string(); }

std::string assetPath(const std::string& relative) {
  return (std::filesystem::path(dataDir()) / "assets" / relative).string();
}

std::string userModsDir() {
  if (const char* home = std::getenv("HOME"); home && *home)
    return (std::filesystem::path(home) / ".local/share/tumble/mods").string();
  return "";
}

std::vector<std::string> modSearchDirs(const std::vector<std::string>& extra) {
  std::vector<std::string> dirs{(std::filesystem::path(dataDir()) / "mods").string()};
  if (std::string user = userModsDir(); !user.empty()) dirs.push_back(std::move(user));
  dirs.insert(dirs.end(), extra.begin(), extra.end());
  return dirs;
}

}  // namespace tumble::app
