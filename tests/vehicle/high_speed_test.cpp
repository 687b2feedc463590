// 300 km/h over rolling terrain: no tunnelling, no NaN, no flips.
#include <limits>

#include "physics/height_field.h"
#include "vehicle_fixture.h"

namespace tumble::vehicle::test {
namespace {

/// Rolling hills on a 1 m grid: 0.25 m swells every 90 m along z plus 5 cm
/// bumps; cells split along their p00-p11 diagonal like the terrain's.
class RollingField final : public physics::HeightField {
 public:
  static constexpr int kNx = 101, kNz = 1201;
  static constexpr Real kX0 = -50, kZ0 = -100;
  static Real heightAt(int i, int j) {
    const Real x = kX0 + Real(i), z = kZ0 + Real(j);
    return Real(0.25) * std::sin(2 * kPi * z / 90) + Real(0.05) * std::sin(2 * kPi * x / 7 + z / 11);
  }
  Vec3 vertex(int i, int j) const { return Vec3(kX0 + Real(i), heightAt(i, j), kZ0 + Real(j)); }
  static physics::HeightFieldTriangle make(const Vec3& a, const Vec3& b, const Vec3& c, std::uint32_t id) {
    physics::HeightFieldTriangle t;
    t.v[0] = a, t.v[1] = b, t.v[2] = c;
    t.normal = (b - a).cross(c - a).normalized();
    if (t.normal.y() < 0) std::swap(t.v[1], t.v[2]), t.normal = -t.normal;
    t.id = id;
    return t;
  }
  template <typename F>
  void cells(Real x0, Real z0, Real x1, Real z1, F&& f) const {
    const int i0 = std::max(0, int(std::floor(x0 - kX0))), i1 = std::min(kNx - 2, int(std::floor(x1 - kX0)));
    const int j0 = std::max(0, int(std::floor(z0 - kZ0))), j1 = std::min(kNz - 2, int(std::floor(z1 - kZ0)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Vec3 p00 = vertex(i, j), p10 = vertex(i + 1, j), p01 = vertex(i, j + 1), p11 = vertex(i + 1, j + 1);
        const std::uint32_t id = std::uint32_t(j * kNx + i) * 2;
        f(make(p00, p11, p10, id));
        f(make(p00, p01, p11, id + 1));
      }
  }
  void visitTriangles(const Vec3& lo, const Vec3& hi, TriangleVisitor visit, void* ctx) const override {
    cells(lo.x(), lo.z(), hi.x(), hi.z(), [&](const physics::HeightFieldTriangle& t) { visit(ctx, t); });
  }
  static bool rayTriangle(const Vec3& o, const Vec3& d, const physics::HeightFieldTriangle& t, Real* dist) {
    const Vec3 e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0], p = d.cross(e2);
    const Real det = e1.dot(p);
    if (std::abs(det) < Real(1e-9)) return false;
    const Vec3 s = o - t.v[0];
    const Real u = s.dot(p) / det;
    if (u < 0 || u > 1) return false;
    const Vec3 q = s.cross(e1);
    const Real v = d.dot(q) / det;
    if (v < 0 || u + v > 1) return false;
    *dist = e2.dot(q) / det;
    return *dist >= 0;
  }
  bool rayCast(const Vec3& o, const Vec3& d, Real maxDistance, physics::HeightFieldHit* hit) const override {
    const Vec3 e = o + d * maxDistance;
    bool found = false;
    Real best = maxDistance;
    cells(std::min(o.x(), e.x()) - 1, std::min(o.z(), e.z()) - 1, std::max(o.x(), e.x()) + 1,
          std::max(o.z(), e.z()) + 1, [&](const physics::HeightFieldTriangle& t) {
            Real dist;
            if (rayTriangle(o, d, t, &dist) && dist <= best) {
              best = dist, found = true;
              hit->distance_m = dist, hit->point_m = o + d * dist, hit->normal = t.normal;
            }
          });
    return found;
  }
  bool surfaceAt(Real x, Real z, Real* height, Vec3* normal) const override {
    physics::HeightFieldHit hit;
    if (!rayCast(Vec3(x, 100, z), -Vec3::UnitY(), 200, &hit)) return false;
    *height = hit.point_m.y(), *normal = hit.normal;
    return true;
  }
  Real frictionAt(Real, Real) const override { return 1; }
  void bounds(Vec3* lo, Vec3* hi) const override {
    *lo = Vec3(kX0, -1, kZ0);
    *hi = Vec3(kX0 + kNx - 1, 1, kZ0 + kNz - 1);
  }
};

TEST(Vehicle, ThreeHundredKmhOverTerrainWithoutTunnellingNanOrFlips) {
  RollingField field;
  physics::World w;
  w.setHeightField(&field);
  VehicleSystem s(w);
  VehicleDef d = testCar();
  d.chassis.dragArea_m2 = 0;  // hold the speed: coast at 300 km/h
  Real h0;
  Vec3 n;
  ASSERT_TRUE(field.surfaceAt(0, 0, &h0, &n));
  VehicleId car = s.spawn(d, Vec3(0, h0, 0), 0).value();
  run(s, 1);
  const Real v0 = Real(300.0 / 3.6);
  w.setLinearVelocity(s.chassis(car), Vec3(0, 0, v0));
  VehicleControls c;
  c.gear = 0;
  s.setControls(car, c);
  Real minUp = 1, minClearance = std::numeric_limits<Real>::max(), minHub = std::numeric_limits<Real>::max();
  for (int i = 0; i < 60 * 8; ++i) {
    s.step(kDt);
    const physics::Body& b = w.body(s.chassis(car));
    ASSERT_TRUE(b.position_m.allFinite() && b.linearVelocity_mps.allFinite()) << "step " << i;
    minUp = std::min(minUp, (b.orientation * Vec3::UnitY()).y());
    Real h;
    if (field.surfaceAt(b.position_m.x(), b.position_m.z(), &h, &n)) minClearance = std::min(minClearance, b.position_m.y() - h);
    for (int k = 0; k < s.wheelCount(car); ++k) {
      const Vec3& hub = s.wheel(car, k).hub_m;
      if (field.surfaceAt(hub.x(), hub.z(), &h, &n)) minHub = std::min(minHub, hub.y() - h);
    }
  }
  const physics::Body& b = w.body(s.chassis(car));
  EXPECT_GT(b.position_m.z(), 600 - 150) << "covered the track";  // ~660 m in 8 s
  EXPECT_EQ(w.errorStats().nanEvents, 0);
  EXPECT_GT(minUp, Real(0.9)) << "the chassis tipped";
  EXPECT_GT(minClearance, Real(0.2)) << "the chassis centre came within 0.2 m of the ground";
  EXPECT_GT(minHub, 0) << "a wheel hub went below the surface";
  EXPECT_GT(b.linearVelocity_mps.z(), Real(0.9) * v0) << "lost speed: something caught";
  // The side slopes of the bumps may drift it a little, but it must not spin.
  const Vec3 f = b.orientation * Vec3::UnitZ();
  EXPECT_LT(std::abs(std::atan2(f.x(), f.z())), Real(0.1)) << "yawed more than 0.1 rad";
}

}  // namespace
}  // namespace tumble::vehicle::test
