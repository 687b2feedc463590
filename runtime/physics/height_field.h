#pragma once
// HeightField: how physics sees terrain (ARCHITECTURE.md: physics never
// includes terrain; the app wires them together). A height field is a static
// surface y = h(x, z) made of triangles, owned by the caller; World keeps a
// pointer (World::setHeightField) and holds no terrain memory of its own.
//
// The world calls, per moving body and step, visitTriangles once over the
// body's swept box (no allocation: the visitor is a function pointer and a
// context), surfaceAt for box vertices, frictionAt for each contact
// manifold, and rayCast for continuous collision and World::rayCast.
#include <cstdint>
#include <type_traits>

#include "core/math.h"

namespace tumble::physics {

/// One triangle of the surface, world space.
struct HeightFieldTriangle {
  Vec3 v[3];                   ///< vertices, counter-clockwise seen from +Y
  Vec3 normal = Vec3::UnitY(); ///< unit face normal, y > 0
  std::uint32_t id = 0;        ///< stable id (e.g. 2 * block + half); not used for adjacency
};

struct HeightFieldHit {
  Real distance_m = 0;         ///< along the unit ray direction
  Vec3 point_m = Vec3::Zero();
  Vec3 normal = Vec3::UnitY(); ///< upward face normal of the triangle hit
};

class HeightField {
 public:
  virtual ~HeightField() = default;

  using TriangleVisitor = void (*)(void* ctx, const HeightFieldTriangle& triangle);
  /// Calls visit(ctx, t) for every triangle whose bounding box overlaps the
  /// box [lo, hi] (m). Must not allocate; it runs every step for every body.
  /// Neighbouring triangles must share bit-identical vertices (a grid does).
  virtual void visitTriangles(const Vec3& lo, const Vec3& hi, TriangleVisitor visit, void* ctx) const = 0;

  /// Height (m) and unit upward face normal of the triangle under (x, z);
  /// false if (x, z) is outside the field (then the outputs are untouched).
  virtual bool surfaceAt(Real x_m, Real z_m, Real* height_m, Vec3* normal) const = 0;

  /// Coulomb friction coefficient of the surface at (x, z) (a drag map). The
  /// contact uses sqrt(body friction * this), the rule for body pairs.
  virtual Real frictionAt(Real x_m, Real z_m) const = 0;

  /// Closest hit along origin + t * unitDir, 0 <= t <= maxDistance_m.
  virtual bool rayCast(const Vec3& origin_m, const Vec3& unitDir, Real maxDistance_m, HeightFieldHit* hit) const = 0;

  /// Axis-aligned bounds of the whole surface (m).
  virtual void bounds(Vec3* lo, Vec3* hi) const = 0;

  /// Convenience wrapper over visitTriangles for a lambda.
  template <typename Fn>
  void forEachTriangle(const Vec3& lo, const Vec3& hi, Fn&& fn) const {
    using F = std::remove_reference_t<Fn>;
    visitTriangles(lo, hi, [](void* ctx, const HeightFieldTriangle& t) { (*static_cast<F*>(ctx))(t); },
                   const_cast<void*>(static_cast<const void*>(&fn)));
  }
};

}  // namespace tumble::physics
