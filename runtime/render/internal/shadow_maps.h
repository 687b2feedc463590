#pragma once
// Cascaded shadow maps from the sun. The view frustum up to
// WindowConfig::shadowDistance_m is cut into 1-3 slices (the practical split
// scheme: a blend of uniform and logarithmic splits, so near slices are
// short and sharp); each slice gets its own orthographic depth map looking
// along the sun, fitted to the slice's bounding sphere (a fixed size, so
// the map does not swim as the camera turns) and snapped to whole texels
// (so it does not shimmer as the camera moves). The lit shaders pick the
// slice by view depth and soften the edge with 4 hardware-filtered
// comparisons (bilinear PCF each: 16 depth tests).
#include <array>

#include "core/result.h"
#include "render/internal/camera_math.h"
#include "render/internal/environment.h"
#include "render/internal/gl_util.h"

namespace tumble::render {

inline constexpr int kMaxShadowCascades = 3;

struct ShadowCascades {
  int count = 0;
  // World -> light clip space (x, y, z in -1..1) per cascade.
  std::array<Eigen::Matrix4f, kMaxShadowCascades> lightViewProjection{};
  // Far end of each cascade, m along the view direction.
  std::array<float, kMaxShadowCascades> far_m{};
  // World size of one shadow texel per cascade, m.
  std::array<float, kMaxShadowCascades> texel_m{};
};

/// Fits `count` (1..3) cascades covering the view from the near plane to
/// maxDistance_m, for a light shining along -towardsLight, with square maps
/// of mapSize texels. Casters up to casterReach_m beyond a slice's sphere
/// towards the sun still land in its depth range.
ShadowCascades fitShadowCascades(const FrameView& view, const Eigen::Vector3f& towardsLight, int count,
                                 float maxDistance_m, int mapSize, float casterReach_m = 150.0f);

/// The depth maps on the GPU: one layer of a depth texture array per cascade.
class ShadowMaps {
 public:
  /// (Re)creates the maps; a no-op if the size and count are unchanged.
  Status resize(int mapSize, int cascades);
  /// Binds cascade i's layer as the depth target, clears it and sets the
  /// viewport; front faces are drawn with a slope-scaled depth offset.
  void bindCascade(int i) const;
  /// Restores the state bindCascade changed (the caller rebinds its target).
  void finish() const;
  unsigned texture() const { return m_texture.get(); }
  int size() const { return m_size; }

 private:
  int m_size = 0, m_cascades = 0;
  GlTexture m_texture;
  GlFramebuffer m_framebuffer;
};

}  // namespace tumble::render
