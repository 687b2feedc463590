#pragma once
// The fixed look of the world: sun, sky and fog. Shared by the sky pass and
// the shape pass so that fogged geometry fades into exactly the sky's horizon
// colour. Linear RGB.
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
};

}  // namespace tumble::render
