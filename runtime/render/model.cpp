// Model bounds, view culling and flattening (plain data, no GL, no assimp).
#include "render/model.h"

#include <algorithm>
#include <cmath>

#include "render/internal/terrain_mesh.h"

namespace tumble::render {

void BoundingBox::add(const Eigen::Vector3f& p) {
  if (empty) {
    min = max = p;
    empty = false;
    return;
  }
  min = min.cwiseMin(p);
  max = max.cwiseMax(p);
}

void BoundingBox::add(const BoundingBox& other) {
  if (other.empty) return;
  add(other.min);
  add(other.max);
}

bool BoundingBox::contains(const BoundingBox& other, float tolerance_m) const {
  if (other.empty) return true;
  if (empty) return false;
  return (other.min.array() >= min.array() - tolerance_m).all() &&
         (other.max.array() <= max.array() + tolerance_m).all();
}

void BoundingSphere::add(const BoundingSphere& other) {
  if (other.empty()) return;
  if (empty()) {
    *this = other;
    return;
  }
  const Eigen::Vector3f d = other.center - center;
  const float dist = d.norm();
  if (dist + other.radius_m <= radius_m) return;  // already inside
  if (dist + radius_m <= other.radius_m) {        // swallowed by the other
    *this = other;
    return;
  }
  // The smallest sphere around both touches each at the far side.
  const float r = 0.5f * (dist + radius_m + other.radius_m);
  center += d * ((r - radius_m) / dist);
  radius_m = r;
}

bool BoundingSphere::contains(const BoundingSphere& other, float tolerance_m) const {
  if (other.empty()) return true;
  if (empty()) return false;
  return (other.center - center).norm() + other.radius_m <= radius_m + tolerance_m * std::max(1.0f, radius_m);
}

std::size_t Model::triangleCount() const {
  std::size_t n = 0;
  for (const ModelMesh& mesh : meshes) n += mesh.triangles.size();
  return n;
}

namespace {

Eigen::Vector3f transformPoint(const Eigen::Matrix4f& m, const Eigen::Vector3f& p) {
  return (m * p.homogeneous()).head<3>();
}

// Tight bounds of one node's meshes in model space. The sphere is centred on
// the box centre with the farthest vertex on its surface: within a few
// percent of the minimal sphere for the elongated parts models are made of,
// and exact to compute (Ritter's sphere can be larger).
void tightBounds(const Model& model, ModelNode& node) {
  node.tightBox = BoundingBox{};
  node.tightSphere = BoundingSphere{};
  for (int meshIndex : node.meshes) {
    for (const Eigen::Vector3f& p : model.meshes[meshIndex].positions) node.tightBox.add(transformPoint(node.toModel, p));
  }
  if (node.tightBox.empty) return;
  const Eigen::Vector3f c = node.tightBox.center();
  float r2 = 0;
  for (int meshIndex : node.meshes) {
    for (const Eigen::Vector3f& p : model.meshes[meshIndex].positions) {
      r2 = std::max(r2, (transformPoint(node.toModel, p) - c).squaredNorm());
    }
  }
  node.tightSphere.center = c;
  node.tightSphere.radius_m = std::sqrt(r2);
}

// Is the sphere entirely outside one plane? Planes are in world space.
bool sphereOutside(const FrustumPlanes& planes, const Eigen::Vector3f& c, float r) {
  for (const Eigen::Vector4f& plane : planes) {
    const float len = plane.head<3>().norm();
    if (plane.head<3>().dot(c) + plane.w() < -r * len) return true;
  }
  return false;
}

}  // namespace

void computeBounds(Model& model) {
  // Parents come before children, so one forward pass fills toModel and one
  // backward pass gathers the covering volumes.
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    ModelNode& node = model.nodes[i];
    node.toModel = node.parent < 0 ? node.local : Eigen::Matrix4f(model.nodes[node.parent].toModel * node.local);
    tightBounds(model, node);
  }
  for (std::size_t i = model.nodes.size(); i-- > 0;) {
    ModelNode& node = model.nodes[i];
    node.coverBox = node.tightBox;
    node.coverSphere = node.tightSphere;
    for (int child : node.children) {
      node.coverBox.add(model.nodes[child].coverBox);
      node.coverSphere.add(model.nodes[child].coverSphere);
    }
  }
}

void cullModel(const Model& model, const Eigen::Matrix4f& modelToWorld, const Eigen::Matrix4f& viewProjection,
               std::vector<int>& visibleNodes, int* nodesTested) {
  visibleNodes.clear();
  if (model.nodes.empty()) return;
  // Testing in model space: the planes of (viewProjection * modelToWorld)
  // are the world planes pulled back through the model transform, so a
  // scaled or rotated instance needs no transformed bounds.
  const FrustumPlanes planes = frustumPlanes(viewProjection * modelToWorld);
  int tested = 0;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const int index = stack.back();
    stack.pop_back();
    const ModelNode& node = model.nodes[index];
    ++tested;
    if (node.coverSphere.empty()) continue;
    if (sphereOutside(planes, node.coverSphere.center, node.coverSphere.radius_m)) continue;
    if (!boxInFrustum(planes, ChunkBounds{node.coverBox.min, node.coverBox.max})) continue;
    if (!node.meshes.empty() && !sphereOutside(planes, node.tightSphere.center, node.tightSphere.radius_m) &&
        boxInFrustum(planes, ChunkBounds{node.tightBox.min, node.tightBox.max})) {
      visibleNodes.push_back(index);
    }
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back(*it);
  }
  if (nodesTested != nullptr) *nodesTested = tested;
}

namespace {

// Squared distance from a point to a box (0 inside).
float distanceSquared(const BoundingBox& box, const Eigen::Vector3f& p) {
  const Eigen::Vector3f d = (box.min - p).cwiseMax(p - box.max).cwiseMax(Eigen::Vector3f::Zero());
  return d.squaredNorm();
}

}  // namespace

void overlapModel(const Model& model, const Eigen::Matrix4f& modelToWorld, const BoundingBox& worldBox,
                  std::vector<int>& nodes, int* nodesTested) {
  nodes.clear();
  int tested = 0;
  if (!model.nodes.empty() && !worldBox.empty) {
    // Spheres go to world space whole: centre transformed, radius scaled by
    // the largest axis scale (exact for rigid and uniform-scale placements,
    // conservative otherwise).
    const Eigen::Matrix3f linear = modelToWorld.topLeftCorner<3, 3>();
    const float scale = std::max({linear.col(0).norm(), linear.col(1).norm(), linear.col(2).norm()});
    auto misses = [&](const BoundingSphere& sphere) {
      if (sphere.empty()) return true;
      const Eigen::Vector3f c = transformPoint(modelToWorld, sphere.center);
      const float r = sphere.radius_m * scale;
      return distanceSquared(worldBox, c) > r * r;
    };
    std::vector<int> stack{0};
    while (!stack.empty()) {
      const int index = stack.back();
      stack.pop_back();
      const ModelNode& node = model.nodes[index];
      ++tested;
      if (misses(node.coverSphere)) continue;
      if (!node.meshes.empty() && !misses(node.tightSphere)) nodes.push_back(index);
      for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back(*it);
    }
  }
  if (nodesTested != nullptr) *nodesTested = tested;
}

FlatMesh flattenModel(const Model& model) {
  FlatMesh flat;
  for (const ModelNode& node : model.nodes) {
    for (int meshIndex : node.meshes) {
      const ModelMesh& mesh = model.meshes[meshIndex];
      const auto base = static_cast<std::uint32_t>(flat.positions.size());
      for (const Eigen::Vector3f& p : mesh.positions) flat.positions.push_back(transformPoint(node.toModel, p));
      // A mirroring transform (negative determinant) turns the winding over.
      const bool mirrored = node.toModel.topLeftCorner<3, 3>().determinant() < 0;
      for (const auto& t : mesh.triangles) {
        if (mirrored) flat.triangles.push_back({base + t[0], base + t[2], base + t[1]});
        else flat.triangles.push_back({base + t[0], base + t[1], base + t[2]});
      }
    }
  }
  return flat;
}

}  // namespace tumble::render
