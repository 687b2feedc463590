#pragma once
// Procedural meshes for the drawable shapes, built once on the CPU at start-up
// and shared by every instance. Each mesh is the shape at unit size; the
// vertex shader scales it per instance:
//
//   local = position * scale + (0, capOffset * halfHeight, 0)
//
// Box: unit cube [-1, 1]^3, scale = half extents. Sphere: unit sphere, scale =
// radius. Capsule: a unit sphere split at the equator whose upper half has
// capOffset +1 and lower half -1, so one mesh serves every radius/length
// ratio (the equator ring is duplicated and the two copies form the
// cylinder). Plane: the square [-1, 1]^2 in XZ with normal +Y.
//
// Triangles wind counter-clockwise seen from outside; normals are per vertex
// and unit length (flat per face for the box, smooth for the round shapes).
#include <cstdint>
#include <vector>

namespace tumble::render {

struct MeshVertex {
  float position[3];
  float normal[3];
  float capOffset;  // -1, 0 or +1; only the capsule uses non-zero values
};

struct MeshData {
  std::vector<MeshVertex> vertices;
  std::vector<std::uint32_t> indices;  // triangle list
};

MeshData buildBoxMesh();
/// slices around Y (>= 3), stacks from pole to pole (>= 2).
MeshData buildSphereMesh(int slices, int stacks);
/// slices around Y (>= 3), stacksPerCap from pole to equator (>= 1).
MeshData buildCapsuleMesh(int slices, int stacksPerCap);
/// Unit cylinder (radius 1, y from -1 to 1; scale = radius, half height,
/// radius): slices around Y (>= 3), smooth side, flat caps.
MeshData buildCylinderMesh(int slices);
MeshData buildPlaneMesh();

}  // namespace tumble::render
