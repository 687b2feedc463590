#include "render/internal/mesh_draw_list.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace tumble::render {

namespace {

auto materialKey(const MeshDraw& d) {
  return std::make_tuple(d.model, d.material, d.tint.x(), d.tint.y(), d.tint.z());
}

}  // namespace

Eigen::Matrix4f instanceMatrix(const ModelInstance& instance) {
  Eigen::Quaternionf q = instance.orientation;
  const float norm = q.norm();
  q = (std::isfinite(norm) && norm > 1e-6f) ? Eigen::Quaternionf(q.coeffs() / norm) : Eigen::Quaternionf::Identity();
  Eigen::Vector3f scale = instance.scale;
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(scale[i]) || std::abs(scale[i]) < 1e-9f) scale[i] = 1.0f;
  }
  const Eigen::Vector3f position = instance.position.allFinite() ? instance.position : Eigen::Vector3f::Zero();
  Eigen::Affine3f m = Eigen::Translation3f(position) * q * Eigen::Scaling(scale);
  return m.matrix();
}

void buildMeshDrawList(const std::vector<ModelInstance>& instances, const Eigen::Matrix4f& viewProjection,
                       std::vector<MeshDraw>& draws, MeshStats& stats) {
  draws.clear();
  stats.instances = static_cast<int>(instances.size());
  stats.nodesTested = stats.nodesCulled = stats.drawCalls = stats.materialSwitches = 0;
  stats.triangles = 0;
  std::vector<int> visible;
  for (const ModelInstance& instance : instances) {
    if (!instance.model) continue;
    const Model& model = *instance.model;
    const Eigen::Matrix4f toWorld = instanceMatrix(instance);
    int tested = 0;
    cullModel(model, toWorld, viewProjection, visible, &tested);
    stats.nodesTested += tested;
    int withMeshes = 0;
    for (const ModelNode& node : model.nodes) withMeshes += !node.meshes.empty();
    stats.nodesCulled += withMeshes - static_cast<int>(visible.size());
    for (int nodeIndex : visible) {
      const ModelNode& node = model.nodes[nodeIndex];
      for (int meshIndex : node.meshes) {
        MeshDraw d;
        d.model = &model;
        d.node = nodeIndex;
        d.mesh = meshIndex;
        d.material = model.meshes[meshIndex].material;
        d.toWorld = toWorld * node.toModel;
        d.tint = instance.tint.allFinite() ? instance.tint : Eigen::Vector3f::Ones();
        draws.push_back(d);
        stats.triangles += static_cast<std::int64_t>(model.meshes[meshIndex].triangles.size());
      }
    }
  }
  // Stable: within one material, draws keep instance and tree order.
  std::stable_sort(draws.begin(), draws.end(),
                   [](const MeshDraw& a, const MeshDraw& b) { return materialKey(a) < materialKey(b); });
  stats.drawCalls = static_cast<int>(draws.size());
  stats.materialSwitches = countMaterialSwitches(draws);
}

int countMaterialSwitches(const std::vector<MeshDraw>& draws) {
  int switches = 0;
  for (std::size_t i = 0; i < draws.size(); ++i) {
    if (i == 0 || materialKey(draws[i]) != materialKey(draws[i - 1])) ++switches;
  }
  return switches;
}

}  // namespace tumble::render
