#pragma once
// GridField: a synthetic height field for tests, a grid of triangles built
// in the test (same split as the terrain module: each cell cut along its
// (i, j)-(i+1, j+1) diagonal), so physics is tested without the terrain module.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "physics/height_field.h"

namespace tumble::physics::test {

class GridField final : public HeightField {
 public:
  using Fn = std::function<Real(Real, Real)>;
  GridField(int nx, int nz, Real spacing, Real x0, Real z0, const Fn& height, Fn friction = nullptr)
      : m_nx(nx), m_nz(nz), m_s(spacing), m_x0(x0), m_z0(z0), m_friction(std::move(friction)) {
    m_h.resize(std::size_t(nx) * nz);
    for (int j = 0; j < nz; ++j)
      for (int i = 0; i < nx; ++i) m_h[std::size_t(j) * nx + i] = height(x0 + i * spacing, z0 + j * spacing);
  }

  Vec3 sample(int i, int j) const { return Vec3(m_x0 + i * m_s, m_h[std::size_t(j) * m_nx + i], m_z0 + j * m_s); }

  HeightFieldTriangle triangle(int bi, int bj, int half) const {
    const Vec3 p00 = sample(bi, bj), p10 = sample(bi + 1, bj), p01 = sample(bi, bj + 1), p11 = sample(bi + 1, bj + 1);
    HeightFieldTriangle t;
    if (half == 0) t.v[0] = p00, t.v[1] = p11, t.v[2] = p10;
    else t.v[0] = p00, t.v[1] = p01, t.v[2] = p11;
    t.normal = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]).normalized();
    t.id = std::uint32_t(2 * (bj * (m_nx - 1) + bi) + half);
    return t;
  }

  void visitTriangles(const Vec3& lo, const Vec3& hi, TriangleVisitor visit, void* ctx) const override {
    const int i0 = std::max(0, int(std::floor((lo.x() - m_x0) / m_s)));
    const int i1 = std::min(m_nx - 2, int(std::floor((hi.x() - m_x0) / m_s)));
    const int j0 = std::max(0, int(std::floor((lo.z() - m_z0) / m_s)));
    const int j1 = std::min(m_nz - 2, int(std::floor((hi.z() - m_z0) / m_s)));
    for (int bj = j0; bj <= j1; ++bj)
      for (int bi = i0; bi <= i1; ++bi)
        for (int half = 0; half < 2; ++half) {
          const HeightFieldTriangle t = triangle(bi, bj, half);
          const Real ylo = std::min({t.v[0].y(), t.v[1].y(), t.v[2].y()});
          const Real yhi = std::max({t.v[0].y(), t.v[1].y(), t.v[2].y()});
          if (ylo <= hi.y() && yhi >= lo.y()) visit(ctx, t);
        }
  }

  bool surfaceAt(Real x, Real z, Real* height, Vec3* normal) const override {
    const Real fx = (x - m_x0) / m_s, fz = (z - m_z0) / m_s;
    if (fx < 0 || fz < 0 || fx > m_nx - 1 || fz > m_nz - 1) return false;
    const int bi = std::min(int(fx), m_nx - 2), bj = std::min(int(fz), m_nz - 2);
    const Real u = fx - bi, v = fz - bj;
    const HeightFieldTriangle t = triangle(bi, bj, u >= v ? 0 : 1);
    // Plane through v[0] with normal n: y = y0 - (nx (x - x0) + nz (z - z0)) / ny.
    *height = t.v[0].y() - (t.normal.x() * (x - t.v[0].x()) + t.normal.z() * (z - t.v[0].z())) / t.normal.y();
    *normal = t.normal;
    return true;
  }

  Real frictionAt(Real x, Real z) const override { return m_friction ? m_friction(x, z) : Real(0.6); }

  bool rayCast(const Vec3& o, const Vec3& d, Real maxT, HeightFieldHit* hit) const override {
    // Brute force (a test): every triangle, Moller-Trumbore, both sides.
    Real best = maxT;
    bool any = false;
    for (int bj = 0; bj < m_nz - 1; ++bj)
      for (int bi = 0; bi < m_nx - 1; ++bi)
        for (int half = 0; half < 2; ++half) {
          const HeightFieldTriangle t = triangle(bi, bj, half);
          const Vec3 e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0], pv = d.cross(e2);
          const Real det = e1.dot(pv);
          if (std::abs(det) < Real(1e-12)) continue;
          const Vec3 tv = o - t.v[0];
          const Real u = tv.dot(pv) / det;
          if (u < 0 || u > 1) continue;
          const Vec3 qv = tv.cross(e1);
          const Real v = d.dot(qv) / det;
          if (v < 0 || u + v > 1) continue;
          const Real tt = e2.dot(qv) / det;
          if (tt < 0 || tt > best) continue;
          best = tt;
          any = true;
          hit->distance_m = tt;
          hit->point_m = o + d * tt;
          hit->normal = t.normal;
        }
    return any;
  }

  void bounds(Vec3* lo, Vec3* hi) const override {
    auto [mn, mx] = std::minmax_element(m_h.begin(), m_h.end());
    *lo = Vec3(m_x0, *mn, m_z0);
    *hi = Vec3(m_x0 + (m_nx - 1) * m_s, *mx, m_z0 + (m_nz - 1) * m_s);
  }

 private:
  int m_nx, m_nz;
  Real m_s, m_x0, m_z0;
  std::vector<Real> m_h;
  Fn m_friction;
};

}  // namespace tumble::physics::test
