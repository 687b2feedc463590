#pragma once
// TerrainDesc: how the integer samples of a height map become world space.
//
// World mapping (Y up, SI units):
//   sample (i, j), i in [0, width), j in [0, height)
//   x_m = originX_m + i * spacing_m
//   z_m = originZ_m + j * spacing_m
//   y_m = baseHeight_m + value * heightScale_m      (value: the uint16 sample)
// so the image's columns run along +X and its rows along +Z.
//
// Sidecar file: a height map "name.png" may have "name.png.json" next to it:
//   {
//     "spacing_m": 1.0,          // metres between neighbouring samples (> 0, <= 1000)
//     "height_scale_m": 0.01,    // metres per unit of the 16-bit value (> 0, <= 15)
//     "base_height_m": 0.0,      // world Y of sample value 0 (within +-1e6 m, as the origins)
//     "origin_x_m": 0.0,         // world X of sample column 0
//     "origin_z_m": 0.0          // world Z of sample row 0
//   }
// Every field is optional; unknown fields are an error (typos would be
// silently ignored otherwise). 8-bit images are widened to 16 bit (v * 257)
// on read, so the same height scale covers the same range for both.
#include <string>

#include "core/result.h"

namespace tumble::terrain {

struct TerrainDesc {
  double spacing_m = 1.0;         ///< metres between neighbouring samples along X and Z
  double heightScale_m = 0.01;    ///< metres per unit of a 16-bit sample (0..655.35 m by default)
  double baseHeight_m = 0.0;      ///< world Y of sample value 0
  double originX_m = 0.0;         ///< world X of sample column 0
  double originZ_m = 0.0;         ///< world Z of sample row 0
};

/// The sidecar path for a height map: "<pngPath>.json".
std::string sidecarPath(const std::string& pngPath);

/// Parse sidecar JSON text; `fileName` is only used in error messages.
Result<TerrainDesc> parseTerrainDesc(const std::string& jsonText, const std::string& fileName);

/// Read "<pngPath>.json" if it exists, else return `defaults` unchanged.
Result<TerrainDesc> loadSidecar(const std::string& pngPath, const TerrainDesc& defaults = {});

std::string terrainDescToJson(const TerrainDesc& desc);

/// Write "<pngPath>.json" atomically.
Status saveSidecar(const std::string& pngPath, const TerrainDesc& desc);

}  // namespace tumble::terrain
