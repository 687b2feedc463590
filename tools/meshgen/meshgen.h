#pragma once
// The project's own models, generated in code (`tumble meshgen`, the program
// tumble-meshgen): vehicle bodies, a wheel, a cockpit interior and scenery,
// written as Wavefront .obj + .mtl with small procedural PNG textures, into
// two folders of the source tree:
//
//   assets/models/            the runtime's: the wheel drawn at every
//                             vehicle's hubs (runtime/app/scene.cpp)
//   mods/base/assets/models/  the base mod's: hatchback, truck, buggy,
//                             cockpit, rock, tree, building, barrier, arch
//
// The files are this output, committed; a test regenerates them and compares
// bytes, so the code is the source and nothing is drawn by hand.
//
// Conventions (as glTF): Y up, metres, a vehicle's front faces +Z and its
// left side +X; vehicles and scenery stand on y = 0. Every part is a closed,
// outward-wound surface, or (wheel, truck, buggy) the parts are materials of
// one closed, outward-wound surface, so mass properties can be computed
// from it.
#include <string>
#include <vector>

#include "core/result.h"

namespace CLI {
class App;
}

namespace tumble::tools {

struct GeneratedFile {
  std::string name;   // file name inside its folder
  std::string bytes;  // exact content
};

/// One folder of generated files.
struct GeneratedFolder {
  std::string path;  ///< relative to the source tree's top: "assets/models", "mods/base/assets/models"
  std::vector<GeneratedFile> files;
};

/// Every folder of the generated set and its files, in a fixed order: the
/// runtime's assets/models, then the base mod's models. Each folder holds
/// its models' .obj and .mtl and exactly the textures those use.
/// Deterministic: the same bytes on every run and machine (fixed-precision
/// text, integer-hash noise, stb_image_write PNGs).
std::vector<GeneratedFolder> generateModelFolders();

/// Writes generateModelFolders() under `root` (each folder created if
/// missing, each file atomically). Returns one line per folder,
/// "N files to ROOT/PATH".
Result<std::vector<std::string>> writeModelFolders(const std::string& root);

/// Registers meshgen's options on `cli` (the program's command line):
/// `--out ROOT` (default: the source tree this was built from). Its callback
/// writes the folders and sets exitCode 0, or 1 after printing the error.
void addMeshgenOptions(CLI::App& cli, int& exitCode);

}  // namespace tumble::tools
