// The procedural meshes are closed, wound outward, have unit normals that
// agree with their faces, and enclose the volume geometry says they should
// (divergence theorem: V = sum over triangles of p0 . (p1 x p2) / 6).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/math.h"
#include "render/internal/mesh_builder.h"

namespace tumble::render {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Position as the vertex shader places it for a capsule of radius 1 and the
// given half height (other meshes have capOffset 0).
Eigen::Vector3f placed(const MeshVertex& v, float halfHeight) {
  return {v.position[0], v.position[1] + v.capOffset * halfHeight, v.position[2]};
}

Eigen::Vector3f normalOf(const MeshVertex& v) { return {v.normal[0], v.normal[1], v.normal[2]}; }

struct MeshFacts {
  double volume = 0;
  Eigen::Vector3d areaVector = Eigen::Vector3d::Zero();  // zero for a closed surface
  int facesAgainstNormals = 0;
};

MeshFacts examine(const MeshData& mesh, float halfHeight) {
  MeshFacts facts;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const MeshVertex& a = mesh.vertices.at(mesh.indices[t]);
    const MeshVertex& b = mesh.vertices.at(mesh.indices[t + 1]);
    const MeshVertex& c = mesh.vertices.at(mesh.indices[t + 2]);
    const Eigen::Vector3d pa = placed(a, halfHeight).cast<double>();
    const Eigen::Vector3d pb = placed(b, halfHeight).cast<double>();
    const Eigen::Vector3d pc = placed(c, halfHeight).cast<double>();
    const Eigen::Vector3d cross = (pb - pa).cross(pc - pa);
    facts.volume += pa.dot(pb.cross(pc)) / 6.0;
    facts.areaVector += 0.5 * cross;
    const Eigen::Vector3d meanNormal = (normalOf(a) + normalOf(b) + normalOf(c)).cast<double>();
    if (cross.norm() > 1e-9 && cross.dot(meanNormal) <= 0) ++facts.facesAgainstNormals;
  }
  return facts;
}

void expectWellFormed(const MeshData& mesh) {
  ASSERT_FALSE(mesh.indices.empty());
  EXPECT_EQ(mesh.indices.size() % 3, 0u);
  for (std::uint32_t i : mesh.indices) ASSERT_LT(i, mesh.vertices.size());
  for (const MeshVertex& v : mesh.vertices) EXPECT_NEAR(normalOf(v).norm(), 1.0f, 1e-5f);
}

TEST(RenderMeshBuilder, BoxIsTheClosedCubeOfSideTwo) {
  const MeshData box = buildBoxMesh();
  expectWellFormed(box);
  EXPECT_EQ(box.vertices.size(), 24u);  // 4 per face: flat normals need their own vertices
  EXPECT_EQ(box.indices.size(), 36u);
  for (const MeshVertex& v : box.vertices) {
    for (float c : v.position) EXPECT_FLOAT_EQ(std::abs(c), 1.0f);
    // The flat normal is the axis the vertex lies on the face of.
    EXPECT_FLOAT_EQ(placed(v, 0).dot(normalOf(v)), 1.0f);
  }
  const MeshFacts facts = examine(box, 0);
  EXPECT_NEAR(facts.volume, 8.0, 1e-6);
  EXPECT_NEAR(facts.areaVector.norm(), 0.0, 1e-6);
  EXPECT_EQ(facts.facesAgainstNormals, 0);
}

TEST(RenderMeshBuilder, SphereVerticesLieOnTheUnitSphereWithRadialNormals) {
  const MeshData sphere = buildSphereMesh(32, 16);
  expectWellFormed(sphere);
  for (const MeshVertex& v : sphere.vertices) {
    EXPECT_NEAR(placed(v, 0).norm(), 1.0f, 1e-5f);
    EXPECT_NEAR((placed(v, 0) - normalOf(v)).norm(), 0.0f, 1e-5f);
    EXPECT_EQ(v.capOffset, 0.0f);
  }
  const MeshFacts facts = examine(sphere, 0);
  // An inscribed polyhedron: slightly less than 4/3 pi, never more.
  EXPECT_LT(facts.volume, 4.0 / 3.0 * kPi);
  EXPECT_GT(facts.volume, 0.97 * 4.0 / 3.0 * kPi);
  EXPECT_NEAR(facts.areaVector.norm(), 0.0, 1e-4);
  EXPECT_EQ(facts.facesAgainstNormals, 0);
}

TEST(RenderMeshBuilder, CapsuleStretchesToAnyHalfHeight) {
  const MeshData capsule = buildCapsuleMesh(32, 8);
  expectWellFormed(capsule);
  for (const float halfHeight : {0.0f, 0.25f, 1.0f, 3.0f}) {
    SCOPED_TRACE(halfHeight);
    float minY = 1e9f, maxY = -1e9f;
    for (const MeshVertex& v : capsule.vertices) {
      const Eigen::Vector3f p = placed(v, halfHeight);
      minY = std::min(minY, p.y());
      maxY = std::max(maxY, p.y());
      // Upper cap vertices belong to the upper half and vice versa.
      if (v.capOffset > 0) {
        EXPECT_GE(v.position[1], -1e-6f);
      } else {
        EXPECT_LE(v.position[1], 1e-6f);
        EXPECT_LT(v.capOffset, 0.0f) << "every capsule vertex belongs to one cap";
      }
      // Every point is at distance 1 from the core segment.
      const Eigen::Vector3f onAxis(0, std::clamp(p.y(), -halfHeight, halfHeight), 0);
      EXPECT_NEAR((p - onAxis).norm(), 1.0f, 1e-5f);
    }
    EXPECT_NEAR(minY, -1.0f - halfHeight, 1e-5f);
    EXPECT_NEAR(maxY, 1.0f + halfHeight, 1e-5f);
    const MeshFacts facts = examine(capsule, halfHeight);
    const double exact = 4.0 / 3.0 * kPi + kPi * 2.0 * halfHeight;  // sphere + cylinder
    EXPECT_LT(facts.volume, exact);
    EXPECT_GT(facts.volume, 0.97 * exact);
    EXPECT_NEAR(facts.areaVector.norm(), 0.0, 1e-4);
    EXPECT_EQ(facts.facesAgainstNormals, 0);
  }
}

TEST(RenderMeshBuilder, PlaneIsAnUpFacingSquareAtYZero) {
  const MeshData plane = buildPlaneMesh();
  expectWellFormed(plane);
  EXPECT_EQ(plane.indices.size(), 6u);
  for (const MeshVertex& v : plane.vertices) {
    EXPECT_EQ(v.position[1], 0.0f);
    EXPECT_FLOAT_EQ(std::abs(v.position[0]), 1.0f);
    EXPECT_FLOAT_EQ(std::abs(v.position[2]), 1.0f);
    EXPECT_EQ(normalOf(v), Eigen::Vector3f::UnitY());
  }
  const MeshFacts facts = examine(plane, 0);
  EXPECT_NEAR(facts.areaVector.y(), 4.0, 1e-6) << "area 2 x 2, facing +Y";
  EXPECT_EQ(facts.facesAgainstNormals, 0);
}

}  // namespace
}  // namespace tumble::render
