#include "render/internal/mesh_builder.h"

#include <cmath>
#include <numbers>

#include "core/assert.h"

namespace tumble::render {

namespace {

struct V3 {
  float x, y, z;
};

V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(V3 a) { return {-a.x, -a.y, -a.z}; }

MeshVertex vertex(V3 p, V3 n, float capOffset = 0.0f) {
  return MeshVertex{{p.x, p.y, p.z}, {n.x, n.y, n.z}, capOffset};
}

// A flat square centred on `normal` spanned by u and v, with u x v == normal
// so that the corner order -u-v, +u-v, +u+v, -u+v is counter-clockwise seen
// from the side the normal points to.
void addQuad(MeshData& mesh, V3 normal, V3 u, V3 v) {
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.push_back(vertex(normal + -u + -v, normal));
  mesh.vertices.push_back(vertex(normal + u + -v, normal));
  mesh.vertices.push_back(vertex(normal + u + v, normal));
  mesh.vertices.push_back(vertex(normal + -u + v, normal));
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
}

struct Ring {
  float polar_rad;  // angle from +Y: 0 at the north pole, pi at the south pole
  float capOffset;
};

// Rings of a unit sphere joined by triangle strips. Ring i, slice j sits at
// (sin p cos t, cos p, sin p sin t) with t = 2 pi j / slices; slice `slices`
// repeats slice 0 so the seam has its own vertices. Going down a ring and
// along +t (which is towards the viewer's left seen from outside), the
// counter-clockwise triangles of the quad a=(i,j) b=(i+1,j) c=(i+1,j+1)
// d=(i,j+1) are (a, c, b) and (a, d, c). The triangle touching a pole
// degenerates to a line and is left out.
MeshData buildRings(const std::vector<Ring>& rings, int slices) {
  MeshData mesh;
  const int columns = slices + 1;
  for (const Ring& ring : rings) {
    const float sp = std::sin(ring.polar_rad), cp = std::cos(ring.polar_rad);
    for (int j = 0; j < columns; ++j) {
      const float t = 2.0f * std::numbers::pi_v<float> * static_cast<float>(j) /
                      static_cast<float>(slices);
      const V3 n{sp * std::cos(t), cp, sp * std::sin(t)};
      mesh.vertices.push_back(vertex(n, n, ring.capOffset));
    }
  }
  const auto at = [columns](std::size_t i, int j) {
    return static_cast<std::uint32_t>(i * static_cast<std::size_t>(columns) +
                                      static_cast<std::size_t>(j));
  };
  constexpr float kPoleEpsilon = 1e-6f;
  for (std::size_t i = 0; i + 1 < rings.size(); ++i) {
    const bool topIsPole = std::sin(rings[i].polar_rad) < kPoleEpsilon;
    const bool bottomIsPole = std::sin(rings[i + 1].polar_rad) < kPoleEpsilon;
    for (int j = 0; j < slices; ++j) {
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (!bottomIsPole) mesh.indices.insert(mesh.indices.end(), {a, c, b});
      if (!topIsPole) mesh.indices.insert(mesh.indices.end(), {a, d, c});
    }
  }
  return mesh;
}

}  // namespace

MeshData buildBoxMesh() {
  MeshData mesh;
  const V3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  addQuad(mesh, x, y, z);
  addQuad(mesh, -x, z, y);
  addQuad(mesh, y, z, x);
  addQuad(mesh, -y, x, z);
  addQuad(mesh, z, x, y);
  addQuad(mesh, -z, y, x);
  return mesh;
}

MeshData buildSphereMesh(int slices, int stacks) {
  TUMBLE_ASSERT(slices >= 3 && stacks >= 2, "buildSphereMesh needs slices >= 3 and stacks >= 2");
  std::vector<Ring> rings;
  for (int i = 0; i <= stacks; ++i) {
    rings.push_back({std::numbers::pi_v<float> * static_cast<float>(i) / static_cast<float>(stacks),
                     0.0f});
  }
  return buildRings(rings, slices);
}

MeshData buildCapsuleMesh(int slices, int stacksPerCap) {
  TUMBLE_ASSERT(slices >= 3 && stacksPerCap >= 1,
                "buildCapsuleMesh needs slices >= 3 and stacksPerCap >= 1");
  std::vector<Ring> rings;
  const float step = 0.5f * std::numbers::pi_v<float> / static_cast<float>(stacksPerCap);
  for (int i = 0; i <= stacksPerCap; ++i) rings.push_back({step * static_cast<float>(i), 1.0f});
  for (int i = stacksPerCap; i <= 2 * stacksPerCap; ++i) {
    rings.push_back({step * static_cast<float>(i), -1.0f});
  }
  return buildRings(rings, slices);
}

MeshData buildCylinderMesh(int slices) {
  TUMBLE_ASSERT(slices >= 3, "buildCylinderMesh needs slices >= 3");
  MeshData mesh;
  const float step = 2.0f * std::numbers::pi_v<float> / static_cast<float>(slices);
  // Side: two rings (y = +1 above y = -1) with radial normals; going along +t
  // is to the viewer's left seen from outside, as in buildRings.
  for (float y : {1.0f, -1.0f})
    for (int j = 0; j <= slices; ++j) {
      const float t = step * static_cast<float>(j);
      const V3 n{std::cos(t), 0.0f, std::sin(t)};
      mesh.vertices.push_back(vertex({n.x, y, n.z}, n));
    }
  const auto columns = static_cast<std::uint32_t>(slices + 1);
  for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(slices); ++j) {
    const std::uint32_t a = j, b = columns + j, c = columns + j + 1, d = j + 1;
    mesh.indices.insert(mesh.indices.end(), {a, c, b, a, d, c});
  }
  // Caps: a fan around the centre, normal +Y on top and -Y below.
  for (float y : {1.0f, -1.0f}) {
    const auto centre = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back(vertex({0.0f, y, 0.0f}, {0.0f, y, 0.0f}));
    for (int j = 0; j <= slices; ++j) {
      const float t = step * static_cast<float>(j);
      mesh.vertices.push_back(vertex({std::cos(t), y, std::sin(t)}, {0.0f, y, 0.0f}));
    }
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(slices); ++j) {
      // Seen from above (+Y), increasing t runs clockwise (x towards z), so
      // the top cap takes (centre, j + 1, j) and the bottom (centre, j, j + 1).
      if (y > 0) mesh.indices.insert(mesh.indices.end(), {centre, centre + 2 + j, centre + 1 + j});
      else mesh.indices.insert(mesh.indices.end(), {centre, centre + 1 + j, centre + 2 + j});
    }
  }
  return mesh;
}

MeshData buildPlaneMesh() {
  MeshData mesh;
  // Same corner construction as a box face, then pushed back down onto y = 0.
  addQuad(mesh, {0, 1, 0}, {0, 0, 1}, {1, 0, 0});
  for (MeshVertex& v : mesh.vertices) v.position[1] = 0.0f;
  return mesh;
}

}  // namespace tumble::render
