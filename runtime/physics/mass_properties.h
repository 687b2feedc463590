#pragma once
// Mass properties of closed triangle meshes and the principal frame.
//
// Index
//   MassProperties          mass, volume, centre of mass, inertia tensor
//   massPropertiesOfMesh    from a closed, outward-wound triangle mesh
//   PrincipalFrame          principal moments and the rotation to them
//   principalFrame          diagonalises an inertia tensor
//
// massPropertiesOfMesh integrates 1, x, y, z, x^2, y^2, z^2, xy, yz, zx over
// the solid with the divergence theorem, one triangle at a time (Eberly,
// "Polyhedral Mass Properties (Revisited)", 2002, a simplification of
// Mirtich's 1996 algorithm; Eberly, Game Physics 2nd ed., ch. 2). It is exact
// for any closed polyhedron (convex or not) whose triangles are wound
// counter-clockwise seen from outside; accumulated in double.
#include <array>
#include <cstdint>
#include <span>

#include "core/math.h"

namespace tumble::physics {

struct MassProperties {
  Real mass_kg = 0;
  Real volume_m3 = 0;  ///< negative if the triangles are wound inside out
  Vec3 centreOfMass_m = Vec3::Zero();       ///< in the frame of the vertices
  Mat3 inertia_kgm2 = Mat3::Zero();         ///< about the centre of mass, axes of the vertex frame
  int skippedTriangles = 0;  ///< triangles with an index past the vertex array (left out)
  /// False for an empty or flat mesh (|volume| < 1e-12 m^3), a triangle index
  /// out of range, a non-finite vertex or a density that is not positive and
  /// finite. An inside-out mesh is valid: its volume is negative but its mass
  /// and inertia are those of the solid (the winding is turned around).
  bool valid = false;
};

/// Mass properties of the solid bounded by `triangles` (indices into
/// `vertices_m`, counter-clockwise seen from outside) at uniform density.
/// Triangles with an out-of-range index are skipped and counted. A mesh that
/// is not closed gives a meaningless answer (check volume_m3 > 0).
MassProperties massPropertiesOfMesh(std::span<const Vec3> vertices_m,
                                    std::span<const std::array<std::uint32_t, 3>> triangles, Real density_kgpm3);

/// A symmetric inertia tensor I = R diag(moments) R^T.
/// True if every edge of the mesh (vertices at identical positions welded)
/// is used exactly once in each direction: a closed, consistently wound
/// surface, the condition for massPropertiesOfMesh to mean a solid.
bool isClosedMesh(std::span<const Vec3> vertices_m, std::span<const std::array<std::uint32_t, 3>> triangles);

struct PrincipalFrame {
  Vec3 moments_kgm2 = Vec3::Zero();  ///< principal moments about the axes R e_x, R e_y, R e_z
  Quat rotation = Quat::Identity();  ///< columns of R: the principal axes (right-handed)
};

/// Principal axes ordered and signed to be as close to the given axes as
/// possible; a tensor that is already diagonal keeps them exactly (R = E).
PrincipalFrame principalFrame(const Mat3& inertia_kgm2);

/// Inertia of a body with principal moments `moments` rotated by q and
/// shifted so its centre of mass sits at `offset_m` from the reference point
/// (parallel-axis theorem: I + m (|d|^2 E - d d^T)).
Mat3 shiftedInertia(const Vec3& moments_kgm2, const Quat& q, Real mass_kg, const Vec3& offset_m);

}  // namespace tumble::physics
