#pragma once
// Contacts between one body and the height field (height_field_collision.cpp
// explains the method and how triangle seams are handled).
#include <cstdint>
#include <vector>

#include "physics/body.h"
#include "physics/height_field.h"
#include "physics/internal/manifold.h"

namespace tumble::physics {

/// Body index used as side b of manifolds against the height field. It is
/// never a valid body slot; the solver maps it to a static, unmoving side.
constexpr std::uint32_t kHeightFieldBody = 0xFFFFFFFFu;
/// At most this many manifolds (distinct contact normals) per body.
constexpr int kMaxHeightFieldManifolds = 4;

/// One contact point before grouping: n points from the surface to the body.
struct SurfaceContact {
  Vec3 normal = Vec3::UnitY();
  Vec3 point_m = Vec3::Zero();  ///< midway between the surfaces
  Real separation_m = 0;
  std::uint32_t id = 0;
};

/// Arrays reused between calls (no allocation per step once warm).
struct HeightFieldScratch {
  std::vector<HeightFieldTriangle> triangles;
  struct Candidate {
    Vec3 closest, normal;
    Real separation;
    std::uint32_t triangle;
    bool face;
  };
  std::vector<Candidate> candidates;
  std::vector<SurfaceContact> contacts;
};

/// Fills out[0..k) with manifolds of `body` (side a) against the field
/// (side b = kHeightFieldBody): normals from the body to the surface, points
/// with separation <= margin_m. [lo, hi] is the body's swept box. Friction,
/// restitution and warm-start impulses are left to the caller.
int collideHeightField(const Body& body, const HeightField& field, const Vec3& lo, const Vec3& hi, Real margin_m,
                       HeightFieldScratch& scratch, Manifold* out);

}  // namespace tumble::physics
