#pragma once
// A scenario's `terrain.build(map)`: the height map the scenario makes in Lua
// with the terrain module's generators and filters (bind_terrain.cpp).
// Built only when the terrain module is configured (TUMBLE_HAVE_TERRAIN).
#include "core/result.h"
#include "script/scenario_host.h"
#include "terrain/height_map.h"

namespace tumble::script {

/// Runs the scenario's terrain.build on a flat width x height map and returns
/// it. Errors (a Lua error, a budget, a bad size) name the mod, file and line.
/// Call only when host.hasTerrainBuild().
Result<terrain::HeightMap> buildScenarioTerrain(ScenarioHost& host, int width, int height);

}  // namespace tumble::script
