#pragma once
// Image filters on height maps: convolution (smooth, sharpen, any odd
// square kernel), bicubic resampling, shaded-relief preview. Outputs are
// rounded to the nearest 16-bit value and clamped to 0..65535; edges are
// handled by clamping to the nearest sample (no dark/bright border).
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "terrain/height_map.h"
#include "terrain/terrain_desc.h"

namespace tumble::terrain {

/// Square kernel, odd size, weights row-major (row = Z offset, column = X offset).
struct Kernel {
  int size = 1;
  std::vector<double> weights;
};

/// Validates user-supplied kernels (a mod or the CLI): odd size 1..15,
/// size*size finite weights. `what` names the source in the error.
Result<Kernel> makeKernel(int size, std::vector<double> weights, const std::string& what);

HeightMap convolve(const HeightMap& map, const Kernel& kernel);

/// `passes` times the 3x3 binomial kernel [1 2 1]^T [1 2 1] / 16.
HeightMap smooth(const HeightMap& map, int passes = 1);

/// Laplacian sharpening: centre 1 + 4a, edge neighbours -a (sum 1, flat stays flat).
HeightMap sharpen(const HeightMap& map, double amount = 0.5);

/// Bicubic (Keys / Catmull-Rom, a = -0.5) resampling to newWidth x newHeight.
/// Corner samples stay at the corners: destination sample i reads the source
/// at i * (w - 1) / (newWidth - 1), so the world extent is preserved when the
/// spacing is scaled by the same ratio. Outside the map the source is
/// extended linearly, so a linear ramp stays linear up to the border.
HeightMap resampleBicubic(const HeightMap& map, int newWidth, int newHeight);

struct ReliefParams {
  /// Direction towards the light, world space (need not be unit). Default:
  /// from the north-west (-X, -Z) at about 45 degrees.
  Vec3 towardLight = Vec3(-1.0f, 1.41f, -1.0f);
  double ambient = 0.25;        ///< brightness of faces turned away from the light, 0..1
  bool elevationTint = true;    ///< colour by height (green, brown, rock, snow) or plain grey
};

/// Shaded relief (hill shade) as interleaved RGB8, width x height pixels,
/// using world-space slopes from `desc` so the shading matches the game.
std::vector<std::uint8_t> shadedRelief(const HeightMap& map, const TerrainDesc& desc, const ReliefParams& params = {});
Status saveShadedReliefPng(const HeightMap& map, const TerrainDesc& desc, const std::string& path,
                           const ReliefParams& params = {});

}  // namespace tumble::terrain
