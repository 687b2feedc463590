#pragma once
// Where Tumble finds its own data: mods/ and scripts/ of the source tree the
// binary was built from, or TUMBLE_DATA_DIR if set (for installed copies).
#include <string>
#include <vector>

namespace tumble::app {

std::string dataDir();
std::string scriptsDir();
/// Built-in mods folder, then the user's (~/.local/share/tumble/mods), then
/// each --mods folder in order (later folders override earlier ones).
std::vector<std::string> modSearchDirs(const std::vector<std::string>& extra);

}  // namespace tumble::app
