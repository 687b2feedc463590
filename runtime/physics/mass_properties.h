#pragma once
// Mass properties of a closed triangle mesh of uniform density: mass, volume,
// centre of mass and the inertia tensor about the centre of mass.
//
// Method: Mirtich, "Fast and Accurate Computation of Polyhedral Mass
// Properties" (1996). The divergence theorem turns the volume integrals of
// 1, x, y, z, x^2, y^2, z^2, xy, yz, zx into sums over the faces; for
// triangles those face integrals have the closed form Eberly gives
// ("Polyhedral Mass Properties (Revisited)"), which is what is summed here,
// in double whatever Real is. Exact for any closed, consistently wound mesh
// (convex or not); an inside-out mesh (all faces wound inwards) is turned
// around. An open mesh gives a meaningless answer: check isClosedMesh first.
#include <array>
#include <cstdint>
#include <span>

#include "core/math.h"

namespace tumble::physics {

struct MassProperties {
  Real mass_kg = 0;
  Real volume_m3 = 0;
  Vec3 centerOfMass_m = Vec3::Zero();   ///< in the mesh's frame
  Mat3 inertia_kgm2 = Mat3::Zero();     ///< about the centre of mass, axes of the mesh's frame
  /// False for an empty or flat mesh (|volume| < 1e-12 m^3), a triangle index
  /// out of range, a non-finite vertex or a density that is not positive and
  /// finite; then every other field is zero.
  bool valid = false;
};

/// Triangles counter-clockwise seen from outside (outward normals).
MassProperties massPropertiesOfMesh(std::span<const Vec3> vertices_m,
                                    std::span<const std::array<std::uint32_t, 3>> triangles,
                                    Real density_kg_m3);

/// True when every edge is shared by exactly two triangles that run along it
/// in opposite directions (a closed, consistently wound surface). Vertices
/// at the same position count as one, so a mesh split at hard edges (one
/// vertex per face corner, as model files store flat-shaded boxes) passes.
bool isClosedMesh(std::span<const Vec3> vertices_m, std::span<const std::array<std::uint32_t, 3>> triangles);

}  // namespace tumble::physics
