#pragma once
// `tumble terrain ...` (the program tumble-terrain): make and inspect height
// maps from the command line.
//
//   terrain gen      --size N | --width W --height H  --seed S [--roughness R] --out FILE.png
//   terrain smooth   IN --out OUT [--passes K]
//   terrain sharpen  IN --out OUT [--amount A]
//   terrain convolve IN --kernel w,w,... --out OUT [--normalize]
//   terrain resample IN --size N | --width W --height H  --out OUT
//   terrain ridge    IN --from X,Z --to X,Z [--height M] [--width M] [--jaggedness J] [--seed S] [--ditch] --out OUT
//   terrain bump     IN --region X,Z,W,H --amplitude M [--seed S] [--roughness R] --out OUT
//   terrain import   IN --out OUT                 (8-bit / RGB image -> 16-bit height map)
//   terrain preview  IN --out OUT.png [--azimuth DEG] [--elevation DEG] [--grey]
//   terrain info     FILE [--json]
//   terrain materials IN [--island] [--force] [--spacing M] [--height M]
//
// Coordinates and lengths (--from, --to, --width, --region, --height,
// --amplitude) are world metres, converted with the input's sidecar
// (IN.png.json, see terrain/terrain_desc.h) or the defaults (1 m spacing,
// 0.01 m per unit). Outputs are written atomically; an input's sidecar is
// copied next to the output (resample scales its spacing to keep the extent).
// Errors print one line naming the file and what was expected, and set exitCode = 1.
namespace CLI {
class App;
}

namespace tumble::tools {

/// Registers gen, smooth, ... info, materials as subcommands of `terrain`
/// (the program's own command line, or a `terrain` subcommand of another)
/// and requires one of them. Each command's callback sets `exitCode` (0 on
/// success, 1 on error); `exitCode` must outlive terrain's parse().
void addTerrainCommands(CLI::App& terrain, int& exitCode);

}  // namespace tumble::tools
