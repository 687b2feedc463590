#pragma once
// The mesh pass's CPU half (no GL, so tests can check it): model instances
// -> view culling with each model's node tree -> one draw per visible
// (instance, node, mesh), sorted so that draws with the same material are
// adjacent and the GPU state changes once per material, not once per draw.
#include <vector>

#include "render/model.h"
#include "render/renderer.h"

namespace tumble::render {

struct MeshDraw {
  const Model* model = nullptr;
  int node = 0, mesh = 0, material = 0;
  Eigen::Matrix4f toWorld = Eigen::Matrix4f::Identity();  // node frame -> world
  Eigen::Vector3f tint{1, 1, 1};
};

/// translate(position) * rotate(orientation) * scale(scale); a zero or NaN
/// quaternion counts as identity, non-finite or zero scales as 1.
Eigen::Matrix4f instanceMatrix(const ModelInstance& instance);

/// Fills `draws` (cleared first) sorted by material and sets the stats'
/// instances, nodesTested, nodesCulled, drawCalls, triangles and
/// materialSwitches. Instances with no model are skipped.
void buildMeshDrawList(const std::vector<ModelInstance>& instances, const Eigen::Matrix4f& viewProjection,
                       std::vector<MeshDraw>& draws, MeshStats& stats);

/// Times the material (model, material index, tint) changes along the list,
/// the first one included.
int countMaterialSwitches(const std::vector<MeshDraw>& draws);

}  // namespace tumble::render
