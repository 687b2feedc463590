#pragma once
// The project's own terrain textures, generated in code on first use (no
// image files, nothing third-party): tileable fractal value noise tinted per
// material. Deterministic (integer hashing, no std random), so the same
// build always makes the same pixels.
//
// Layer order is the public texture index (TerrainSurface::textureIndex):
// 0 grass, 1 rock, 2 sand, 3 mud, 4 snow, 5 gravel, 6 dirt, 7 moss.
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "render/renderer.h"

namespace tumble::render {

/// Side of each square texture layer, texels; it tiles every
/// kTerrainTextureSize_m metres of ground.
inline constexpr int kTerrainTextureSize = 256;
inline constexpr float kTerrainTextureSize_m = 4.0f;

/// Mean linear colour of each layer (tests use it to tell materials apart).
Eigen::Vector3f terrainTextureMeanColor(int layer);
const char* terrainTextureName(int layer);

/// One layer as RGBA8 rows (sRGB-encoded colour, alpha 255), size^2 texels,
/// tileable with period `size`.
std::vector<std::uint8_t> generateTerrainTexture(int layer, int size = kTerrainTextureSize);

}  // namespace tumble::render
