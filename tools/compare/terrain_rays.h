#pragma once
// terrain_rays: Tumble's height-field ray casts against Bullet's
// btHeightfieldTerrainShape on one batch of rays (see terrain_rays.cpp).
#include <cstdint>
#include <nlohmann/json.hpp>

namespace tumble::compare {

struct TerrainRaysOptions {
  int size = 1025;         ///< samples per side of the generated height field
  int rays = 100000;       ///< rays in the batch
  std::uint64_t seed = 7;  ///< terrain and ray batch
};

/// Runs the batch in both engines; the JSON report (or {"error": ...}).
nlohmann::json runTerrainRays(const TerrainRaysOptions& options);

}  // namespace tumble::compare
