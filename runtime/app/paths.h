#pragma once
// Where Tumble finds its own data: mods/, scripts/ and assets/ of the source
// tree the binary was built from, or of TUMBLE_DATA_DIR if set (for
// installed copies).
#include <string>
#include <vector>

namespace tumble::app {

std::string dataDir();
std::string scriptsDir();
/// A file of the runtime's own data (not a mod's), e.g. "models/wheel.obj"
/// -> DATA/assets/models/wheel.obj. Every runtime-owned file is found
/// through here; assets/README.md lists them and the tools that make them.
std::string assetPath(const std::string& relative);
/// The user's mods folder, ~/.local/share/tumble/mods (where the designer
/// saves); empty when HOME is not set.
std::string userModsDir();
/// Built-in mods folder, then the user's (~/.local/share/tumble/mods), then
/// each --mods folder in order (later folders override earlier ones).
std::vector<std::string> modSearchDirs(const std::vector<std::string>& extra);

}  // namespace tumble::app
