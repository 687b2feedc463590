// Friction and softness are separate properties of a surface (docs/vehicles.md
// "Surfaces"): friction limits grip, softness adds rolling drag
// (tyre.soft_ground_drag * s). A car runs up on hard dry ground, shifts to
// neutral and coasts onto the surface under test; its coast-down there must
// follow the analytic answer for the rolling resistance that surface gives:
//   dv/dt = -(C_rr m g + k v^2) / M,  k = 1/2 rho Cd A,  M = m + sum I_w / r^2
//   v(t) = sqrt(a / b) tan(atan(v0 sqrt(b / a)) - sqrt(a b) t),  a = C_rr m g / M, b = k / M
// Ice (friction 0.1, softness 0) coasts as on asphalt; mud (0.3, 0.7) with
// C_rr + 0.7 soft_ground_drag. Checked on a terrain height field (softness
// through vehicle::GroundSoftness) and on static bodies (setSurfaceSoftness).
#include <algorithm>
#include <cmath>
#include <limits>

#include "vehicle_fixture.h"

#include "physics/height_field.h"
#include "vehicle/ground_softness.h"

namespace tumble::vehicle::test {
namespace {

constexpr Real kTestFromZ = 120;  // m: dry hard ground before, the surface under test after
constexpr Real kCoast_s = 6;

struct Surface {
  Real friction = 1, softness = 0;
};

/// Flat ground y = 0 over x in [-50, 50], z in [-50, 950] in 10 m cells:
/// dry and hard (friction 1, softness 0) before z = kTestFromZ, `test` after.
class FlatField final : public physics::HeightField, public GroundSoftness {
 public:
  explicit FlatField(Surface test) : m_test(test) {}
  static constexpr Real kX0 = -50, kX1 = 50, kZ0 = -50, kZ1 = 950, kCell = 10;
  void visitTriangles(const Vec3& lo, const Vec3& hi, TriangleVisitor visit, void* ctx) const override {
    if (lo.y() > 0 || hi.y() < 0) return;
    const int i0 = std::max(0, int(std::floor((lo.x() - kX0) / kCell))), i1 = std::min(9, int(std::floor((hi.x() - kX0) / kCell)));
    const int j0 = std::max(0, int(std::floor((lo.z() - kZ0) / kCell))), j1 = std::min(99, int(std::floor((hi.z() - kZ0) / kCell)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Real x = kX0 + i * kCell, z = kZ0 + j * kCell;
        const Vec3 p00(x, 0, z), p10(x + kCell, 0, z), p01(x, 0, z + kCell), p11(x + kCell, 0, z + kCell);
        physics::HeightFieldTriangle a, b;
        a.v[0] = p00, a.v[1] = p11, a.v[2] = p10, a.id = std::uint32_t(j * 10 + i) * 2;
        b.v[0] = p00, b.v[1] = p01, b.v[2] = p11, b.id = a.id + 1;
        visit(ctx, a);
        visit(ctx, b);
      }
  }
  bool surfaceAt(Real x, Real z, Real* height, Vec3* normal) const override {
    if (x < kX0 || x > kX1 || z < kZ0 || z > kZ1) return false;
    *height = 0, *normal = Vec3::UnitY();
    return true;
  }
  Real frictionAt(Real, Real z) const override { return z < kTestFromZ ? 1 : m_test.friction; }
  Real softnessAt(Real, Real z) const override { return z < kTestFromZ ? 0 : m_test.softness; }
  bool rayCast(const Vec3& o, const Vec3& d, Real maxDistance, physics::HeightFieldHit* hit) const override {
    if (d.y() >= 0 || o.y() < 0) return false;
    const Real t = -o.y() / d.y();
    const Vec3 p = o + d * t;
    if (t > maxDistance || !surfaceAt(p.x(), p.z(), &hit->point_m.y(), &hit->normal)) return false;
    hit->distance_m = t, hit->point_m = Vec3(p.x(), 0, p.z());
    return true;
  }
  void bounds(Vec3* lo, Vec3* hi) const override {
    *lo = Vec3(kX0, -1, kZ0);
    *hi = Vec3(kX1, 1, kZ1);
  }

 private:
  Surface m_test;
};

struct Coast {
  Real v0_mps = 0, v1_mps = 0;  ///< at the start and the end of the coast on the test surface
  Real friction = 0, softness = 0;  ///< what the tyres reported there
};

/// Drives testCar() up to speed on the dry part, shifts to neutral, and
/// measures kCoast_s seconds of coasting once all four wheels are on the
/// test surface (z > kTestFromZ + 2 m).
Coast coast(physics::World& w, VehicleSystem& s) {
  w.settings().enableSleep = false;
  VehicleId car = s.spawn(testCar(), Vec3::Zero(), 0).value();
  VehicleControls c;
  c.throttle = 1;
  s.setControls(car, c);
  for (int i = 0; i < 3000 && position(s, w, car).z() < kTestFromZ - 40; ++i) {
    autoShift(s, car);
    s.step(kDt);
  }
  c = s.controls(car);
  c.throttle = 0, c.gear = 0;
  s.setControls(car, c);
  for (int i = 0; i < 3000 && position(s, w, car).z() < kTestFromZ + 4; ++i) s.step(kDt);
  Coast out;
  out.v0_mps = s.telemetry(car).speed_mps;
  run(s, kCoast_s);
  out.v1_mps = s.telemetry(car).speed_mps;
  out.friction = s.wheel(car, 0).surfaceFriction;
  out.softness = s.wheel(car, 0).surfaceSoftness;
  return out;
}

/// The analytic coast-down speed after kCoast_s from v0 with rolling
/// resistance coefficient crr (testCar(): drag, mass and wheels).
Real analytic(Real v0, Real crr) {
  const VehicleDef d = testCar();
  Real M = d.chassis.mass_kg;
  for (const AxleDef& a : d.axles) M += 2 * a.wheelInertia_kgm2 / (a.wheelRadius_m * a.wheelRadius_m);
  const Real a = crr * d.chassis.mass_kg * kStandardGravity / M;
  const Real b = Real(0.5) * d.chassis.airDensity_kgpm3 * d.chassis.dragArea_m2 / M;
  return std::sqrt(a / b) * std::tan(std::atan(v0 * std::sqrt(b / a)) - std::sqrt(a * b) * kCoast_s);
}

Coast coastOnField(Surface test) {
  FlatField field(test);
  physics::World w;
  w.setHeightField(&field);
  VehicleSystem s(w);
  return coast(w, s);
}

/// The same on static slabs (top at y = 0): dry before kTestFromZ, the test
/// surface after, its softness given to the vehicle system.
Coast coastOnBodies(Surface test) {
  physics::World w;
  auto slab = [&](Real z0, Real z1, Real friction) {
    physics::BodyDef g;
    g.type = physics::BodyType::Static;
    g.shape = physics::Shape::box(Vec3(20, Real(0.5), (z1 - z0) / 2));
    g.position_m = Vec3(0, Real(-0.5), (z0 + z1) / 2);
    g.friction = friction;
    return w.createBody(g).value();
  };
  slab(-50, kTestFromZ, 1);
  const physics::BodyId testSlab = slab(kTestFromZ, 950, test.friction);
  VehicleSystem s(w);
  EXPECT_TRUE(s.setSurfaceSoftness(testSlab, test.softness));
  return coast(w, s);
}

const Real kCrr = testCar().tyre.rollingResistance;
const Real kSoftDrag = testCar().tyre.softGroundDrag;
constexpr Surface kAsphalt{1, 0}, kIce{Real(0.1), 0}, kMud{Real(0.3), Real(0.7)};

// The coast-down matches the analytic answer within 1 % of the speed lost
// (tyre slip and the suspension take a little more; measured: 0.2 %).
void expectAnalytic(const Coast& c, Real crr, const char* what) {
  ASSERT_GT(c.v0_mps, 15) << what << ": the run-up reached speed";
  const Real expected = analytic(c.v0_mps, crr);
  EXPECT_NEAR(c.v1_mps, expected, Real(0.01) * (c.v0_mps - expected)) << what << " from " << c.v0_mps << " m/s";
}

TEST(Surface, IceIsSlipperyButCoastsAsFarAsAsphalt) {
  const Coast ice = coastOnField(kIce), asphalt = coastOnField(kAsphalt);
  EXPECT_NEAR(ice.friction, 0.1, 1e-6);
  EXPECT_EQ(ice.softness, 0);
  expectAnalytic(ice, kCrr, "ice");
  expectAnalytic(asphalt, kCrr, "asphalt");
  // Before softness was its own property, ice (friction 0.1) took the soft
  // drag of 1 - 0.1 = 0.9: 20 -> 14.6 m/s in these 6 s instead of 18.5.
  EXPECT_LT(std::abs((ice.v0_mps - ice.v1_mps) - (asphalt.v0_mps - asphalt.v1_mps)), 0.1);
}

TEST(Surface, MudDragsWithItsSoftness) {
  const Coast mud = coastOnField(kMud);
  EXPECT_NEAR(mud.friction, 0.3, 1e-6);
  EXPECT_NEAR(mud.softness, 0.7, 1e-6);
  expectAnalytic(mud, kCrr + kSoftDrag * Real(0.7), "mud");
  const Coast ice = coastOnField(kIce);
  EXPECT_GT(mud.v0_mps - mud.v1_mps, 2 * (ice.v0_mps - ice.v1_mps)) << "mud slows a car far more than ice";
}

TEST(Surface, BodiesAreHardUnlessGivenASoftness) {
  const Coast ice = coastOnBodies(kIce);
  EXPECT_EQ(ice.softness, 0);
  expectAnalytic(ice, kCrr, "an icy slab");
  const Coast mud = coastOnBodies(kMud);
  EXPECT_NEAR(mud.softness, 0.7, 1e-6);
  expectAnalytic(mud, kCrr + kSoftDrag * Real(0.7), "a slab of mud");
}

TEST(Surface, SoftnessMustBeFiniteAndNotNegative) {
  physics::World w;
  const physics::BodyId ground = addGround(w);
  VehicleSystem s(w);
  EXPECT_FALSE(s.setSurfaceSoftness(ground, -1));
  EXPECT_FALSE(s.setSurfaceSoftness(ground, std::numeric_limits<Real>::quiet_NaN()));
  EXPECT_EQ(s.surfaceSoftness(ground), 0);
  EXPECT_TRUE(s.setSurfaceSoftness(ground, Real(0.4)));
  EXPECT_EQ(s.surfaceSoftness(ground), Real(0.4));
  EXPECT_TRUE(s.setSurfaceSoftness(ground, 0));
  EXPECT_EQ(s.surfaceSoftness(ground), 0);
}

}  // namespace
}  // namespace tumble::vehicle::test
