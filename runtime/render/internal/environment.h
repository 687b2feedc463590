#pragma once
// The fixed look of the world: sun, sky and fog. Shared by the sky pass and
// the shape pass so that fogged geometry fades into exactly the sky's horizon
// colour. Linear RGB.
#include <array>

#include "core/math.h"

namespace tumble::render {

struct Environment {
  // Towards the sun: high and from behind the default camera's right
  // shoulder, so the faces the default view sees are lit.
  Eigen::Vector3f lightDirection = Eigen::Vector3f(0.45f, 0.80f, 0.40f).normalized();
  Eigen::Vector3f lightColor{1.00f, 0.96f, 0.88f};
  Eigen::Vector3f skyAmbient{0.30f, 0.34f, 0.42f};
  Eigen::Vector3f groundAmbient{0.14f, 0.12f, 0.10f};
  Eigen::Vector3f zenithColor{0.12f, 0.28f, 0.62f};
  Eigen::Vector3f horizonColor{0.62f, 0.72f, 0.85f};
  Eigen::Vector3f groundColor{0.30f, 0.30f, 0.32f};  // sky below the horizon
  // Fog reaches 63 % at 1 / density = 250 m: invisible in a typical 10-50 m
  // scene, hides the plane's edge at kPlaneHalfSize_m.
  float fogDensity_per_m = 1.0f / 250.0f;
  // Clouds (sky pass): fraction covered 0..1 and how far the wind has moved
  // them (m at cloud height, world X / Z) since the scene started.
  float cloudCover = 0.0f;
  Eigen::Vector2f cloudOffset_m{0, 0};
  Eigen::Vector3f cloudColor{1.0f, 1.0f, 1.0f};    // lit side of the clouds
  Eigen::Vector3f cloudShadowColor{0.55f, 0.6f, 0.68f};  // their dark underside
  // Sun disc brightness 0..1 (0 at night and in overcast weather).
  float sunDisc = 1.0f;
  // Sun shadows this frame (shadow_maps.h; set by the renderer): cascades in
  // use (0: none), world -> shadow texture (0..1) per cascade, each
  // cascade's far end along the view direction and its texel size (m), the
  // depth texture array.
  int shadowCascades = 0;
  std::array<Eigen::Matrix4f, 3> shadowMatrices{};
  Eigen::Vector3f shadowFar_m{0, 0, 0};
  Eigen::Vector3f shadowTexel_m{0, 0, 0};
  Eigen::Vector3f viewForward{0, 0, -1};
  unsigned shadowTexture = 0;
};

}  // namespace tumble::render
