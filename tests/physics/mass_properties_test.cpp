// Mass properties of closed triangle meshes (Mirtich / Eberly) against the
// analytic answers for a box and a cylinder, and how they move with the mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics/mass_properties.h"

namespace tumble::physics {
namespace {

using Tri = std::array<std::uint32_t, 3>;
struct Mesh {
  std::vector<Vec3> v;
  std::vector<Tri> t;
};

// A box split at its hard edges, as model files store it: 4 vertices per
// face (24 in all), two triangles per face, counter-clockwise from outside.
Mesh box(const Vec3& size) {
  Mesh m;
  const Vec3 h = size / 2;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {-1, 1}) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      const auto base = std::uint32_t(m.v.size());
      for (auto [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        Vec3 p;
        p[axis] = Real(sign) * h[axis];
        p[u] = Real(a) * h[u];
        p[w] = Real(b) * h[w];
        m.v.push_back(p);
      }
      // (u, w, axis) is right-handed, so u-then-w runs counter-clockwise seen from +axis.
      if (sign > 0) m.t.insert(m.t.end(), {Tri{base, base + 1, base + 2}, Tri{base, base + 2, base + 3}});
      else m.t.insert(m.t.end(), {Tri{base, base + 2, base + 1}, Tri{base, base + 3, base + 2}});
    }
  }
  return m;
}

// A prism over a regular n-gon of circumradius r, axis along Y, y in [0, h].
Mesh prism(Real r, Real h, int n) {
  Mesh m;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    m.v.emplace_back(Real(r * std::cos(a)), 0, Real(r * std::sin(a)));
    m.v.emplace_back(Real(r * std::cos(a)), h, Real(r * std::sin(a)));
  }
  const auto bottom = std::uint32_t(m.v.size()), top = bottom + 1;
  m.v.emplace_back(0, 0, 0);
  m.v.emplace_back(0, h, 0);
  for (int i = 0; i < n; ++i) {
    const std::uint32_t b0 = 2 * i, t0 = 2 * i + 1, b1 = 2 * ((i + 1) % n), t1 = b1 + 1;
    // Angle grows from +X towards +Z, i.e. clockwise seen from +Y.
    m.t.insert(m.t.end(), {Tri{b0, t0, t1}, Tri{b0, t1, b1}, Tri{top, t1, t0}, Tri{bottom, b0, b1}});
  }
  return m;
}

TEST(MassProperties, BoxMatchesTheAnalyticAnswer) {
  const Vec3 size(2, 0.5, 1.5);
  const Mesh m = box(size);
  ASSERT_TRUE(isClosedMesh(m.v, m.t));
  const Real density = 700;  // kg/m^3, pine
  const MassProperties p = massPropertiesOfMesh(m.v, m.t, density);
  ASSERT_TRUE(p.valid);
  const Real volume = size.prod();
  const Real mass = density * volume;
  EXPECT_NEAR(p.volume_m3, volume, 1e-5);
  EXPECT_NEAR(p.mass_kg, mass, 1e-3);
  EXPECT_NEAR(p.centreOfMass_m.norm(), 0, 1e-6);
  const Vec3 s2 = size.cwiseProduct(size);
  EXPECT_NEAR(p.inertia_kgm2(0, 0), mass * (s2.y() + s2.z()) / 12, 1e-3);
  EXPECT_NEAR(p.inertia_kgm2(1, 1), mass * (s2.z() + s2.x()) / 12, 1e-3);
  EXPECT_NEAR(p.inertia_kgm2(2, 2), mass * (s2.x() + s2.y()) / 12, 1e-3);
  EXPECT_NEAR(p.inertia_kgm2(0, 1), 0, 1e-4);
  EXPECT_NEAR(p.inertia_kgm2(1, 2), 0, 1e-4);
  EXPECT_NEAR(p.inertia_kgm2(0, 2), 0, 1e-4);
}

TEST(MassProperties, FineCylinderApproachesTheSolidCylinder) {
  const Real r = 0.4, h = 0.3, density = 1000;
  const int n = 256;
  const Mesh m = prism(r, h, n);
  ASSERT_TRUE(isClosedMesh(m.v, m.t));
  const MassProperties p = massPropertiesOfMesh(m.v, m.t, density);
  ASSERT_TRUE(p.valid);
  // Exact for the prism: area of the n-gon times h.
  const double area = 0.5 * n * r * r * std::sin(2 * M_PI / n);
  EXPECT_NEAR(p.volume_m3, area * h, 1e-6);
  EXPECT_NEAR(p.centreOfMass_m.y(), h / 2, 1e-5);
  EXPECT_NEAR(p.centreOfMass_m.x(), 0, 1e-5);
  // The solid cylinder: I_axis = m r^2 / 2, I_perp = m (3 r^2 + h^2) / 12;
  // a 256-gon is within 1e-4 relative.
  const double mass = p.mass_kg;
  EXPECT_NEAR(p.inertia_kgm2(1, 1) / (mass * r * r / 2), 1.0, 2e-4);
  EXPECT_NEAR(p.inertia_kgm2(0, 0) / (mass * (3 * r * r + h * h) / 12), 1.0, 2e-4);
  EXPECT_NEAR(p.inertia_kgm2(2, 2) / (mass * (3 * r * r + h * h) / 12), 1.0, 2e-4);
}

TEST(MassProperties, MovingTheMeshMovesTheCentreAndRotatesTheInertia) {
  const Mesh base = box(Vec3(1, 2, 3));
  const Quat q(Eigen::AngleAxis<Real>(Real(0.7), Vec3(1, 2, 0.5).normalized()));
  const Vec3 shift(5, -3, 2);
  Mesh moved = base;
  for (Vec3& p : moved.v) p = q * p + shift;
  const MassProperties a = massPropertiesOfMesh(base.v, base.t, 1);
  const MassProperties b = massPropertiesOfMesh(moved.v, moved.t, 1);
  ASSERT_TRUE(b.valid);
  EXPECT_NEAR(b.mass_kg, a.mass_kg, 1e-4);
  EXPECT_LT((b.centreOfMass_m - shift).norm(), 1e-4);
  const Mat3 expected = q.toRotationMatrix() * a.inertia_kgm2 * q.toRotationMatrix().transpose();
  EXPECT_LT((b.inertia_kgm2 - expected).norm(), 2e-3 * expected.norm());
}

TEST(MassProperties, InsideOutMeshIsTurnedAroundAndBadInputIsRefused) {
  Mesh m = box(Vec3(1, 1, 1));
  const MassProperties outward = massPropertiesOfMesh(m.v, m.t, 2);
  for (Tri& t : m.t) std::swap(t[1], t[2]);
  const MassProperties inward = massPropertiesOfMesh(m.v, m.t, 2);
  EXPECT_NEAR(inward.mass_kg, outward.mass_kg, 1e-6);
  EXPECT_LT((inward.inertia_kgm2 - outward.inertia_kgm2).norm(), 1e-6);

  EXPECT_FALSE(massPropertiesOfMesh(m.v, m.t, 0).valid);
  EXPECT_FALSE(massPropertiesOfMesh(m.v, m.t, std::nanf("")).valid);
  std::vector<Tri> bad = m.t;
  bad[0][0] = 999;
  EXPECT_FALSE(massPropertiesOfMesh(m.v, bad, 1).valid);
  EXPECT_FALSE(massPropertiesOfMesh(m.v, std::span<const Tri>{}, 1).valid);

  // One face missing: not closed.
  std::vector<Tri> open(m.t.begin() + 2, m.t.end());
  EXPECT_FALSE(isClosedMesh(m.v, open));
  // Two faces wound against the rest: not consistently oriented.
  std::vector<Tri> mixed = m.t;
  std::swap(mixed[0][1], mixed[0][2]);
  std::swap(mixed[1][1], mixed[1][2]);
  EXPECT_FALSE(isClosedMesh(m.v, mixed));
}

}  // namespace
}  // namespace tumble::physics
