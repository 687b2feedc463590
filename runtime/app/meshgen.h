#pragma once
// The project's own models, generated in code (`tumble meshgen --out DIR`):
// vehicle bodies, a wheel, a cockpit interior and scenery, written as
// Wavefront .obj + .mtl with small procedural PNG textures. The files in
// mods/base/assets/models/ are this output, committed; a test regenerates
// them and compares bytes, so the code is the source and nothing is drawn
// by hand.
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

namespace tumble::app {

struct GeneratedFile {
  std::string name;   // file name inside the output folder
  std::string bytes;  // exact content
};

/// Every file of the generated set, in a fixed order. Deterministic: the
/// same bytes on every run and machine (fixed-precision text, integer-hash
/// noise, stb_image_write PNGs).
std::vector<GeneratedFile> generateModelFiles();

/// Registers `tumble meshgen --out DIR` (default: the base mod's
/// assets/models). Sets exitCode 0 or 1 (error printed).
void addMeshgenCommand(CLI::App& root, int& exitCode);

/// Writes generateModelFiles() into `dir` (created if missing), each file
/// atomically. Returns the names written.
Result<std::vector<std::string>> writeModelFiles(const std::string& dir);

}  // namespace tumble::app
