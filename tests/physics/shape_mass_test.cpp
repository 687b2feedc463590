// Mass properties of meshes, hulls and compounds against textbook answers.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/mass_properties.h"

namespace tumble::physics::test {
namespace {

using Tri = std::array<std::uint32_t, 3>;

// Box [-h, h] as 8 vertices and 12 outward triangles.
void boxMesh(const Vec3& h, std::vector<Vec3>& v, std::vector<Tri>& t) {
  v.clear();
  for (int i = 0; i < 8; ++i) v.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  t = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
       {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
}

Mat3 boxInertia(Real m, const Vec3& h) {
  const Vec3 s = 4 * h.cwiseProduct(h);  // (2h)^2
  return Vec3(s.y() + s.z(), s.x() + s.z(), s.x() + s.y()).asDiagonal() * (m / 12);
}

void expectNear(const Mat3& a, const Mat3& b, Real tol) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(a(i, j), b(i, j), tol) << "(" << i << ", " << j << ")";
}

TEST(MassProperties, BoxMatchesTextbook) {
  std::vector<Vec3> v;
  std::vector<Tri> t;
  const Vec3 h(1, 1.5f, 2);
  boxMesh(h, v, t);
  const MassProperties mp = massPropertiesOfMesh(v, t, 500);
  EXPECT_NEAR(mp.volume_m3, 24, 1e-4);
  EXPECT_NEAR(mp.mass_kg, 12000, 1e-1);
  EXPECT_LT(mp.centreOfMass_m.norm(), 1e-5);
  expectNear(mp.inertia_kgm2, boxInertia(12000, h), 1);  // of ~2e4 kg m^2
}

TEST(MassProperties, ShiftedAndRotatedBoxMovesItsCentreAndTurnsItsTensor) {
  std::vector<Vec3> v;
  std::vector<Tri> t;
  const Vec3 h(0.5f, 1, 0.25f);
  boxMesh(h, v, t);
  const Quat q = Quat(Eigen::AngleAxis<Real>(Real(0.7), Vec3(1, 2, 3).normalized()));
  const Vec3 shift(10, -4, 7);
  for (Vec3& p : v) p = q * p + shift;
  const MassProperties mp = massPropertiesOfMesh(v, t, 1000);
  EXPECT_NEAR(mp.mass_kg, 1000, 1e-2);
  EXPECT_LT((mp.centreOfMass_m - shift).norm(), 1e-4);
  const Mat3 R = q.toRotationMatrix();
  expectNear(mp.inertia_kgm2, R * boxInertia(1000, h) * R.transpose(), Real(1e-2));
}

TEST(MassProperties, TetrahedronMatchesClosedForm) {
  // Unit right tetrahedron: V = 1/6, centre (1/4, 1/4, 1/4); about the
  // centre (density 1) Ixx = 1/80 and the product Ixy = +1/480 (Tonon 2004).
  const std::vector<Vec3> v = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const std::vector<Tri> t = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const MassProperties mp = massPropertiesOfMesh(v, t, 1);
  EXPECT_NEAR(mp.volume_m3, 1.0 / 6, 1e-6);
  EXPECT_LT((mp.centreOfMass_m - Vec3::Constant(0.25f)).norm(), 1e-6);
  Mat3 expected;
  expected << 1.0 / 80, 1.0 / 480, 1.0 / 480, 1.0 / 480, 1.0 / 80, 1.0 / 480, 1.0 / 480, 1.0 / 480, 1.0 / 80;
  expectNear(mp.inertia_kgm2, expected, Real(1e-6));
}

TEST(MassProperties, ManyFacedCylinderApproachesTheCylinder) {
  // A 256-sided prism: its volume is the polygon's area times the height,
  // and its inertia is within 0.1% of the circular cylinder's.
  const int n = 256;
  const Real r = 0.5f, hh = 1;
  std::vector<Vec3> v;
  std::vector<Tri> t;
  for (int i = 0; i < n; ++i) {
    const Real a = 2 * kPi * Real(i) / n;
    v.emplace_back(r * std::cos(a), -hh, r * std::sin(a));
    v.emplace_back(r * std::cos(a), hh, r * std::sin(a));
  }
  const std::uint32_t bottom = std::uint32_t(v.size()), top = bottom + 1;
  v.emplace_back(0, -hh, 0);
  v.emplace_back(0, hh, 0);
  for (int i = 0; i < n; ++i) {
    const std::uint32_t b0 = 2 * i, t0 = 2 * i + 1, b1 = 2 * ((i + 1) % n), t1 = b1 + 1;
    t.push_back({b0, t0, t1});
    t.push_back({b0, t1, b1});
    t.push_back({bottom, b0, b1});
    t.push_back({top, t1, t0});
  }
  const MassProperties mp = massPropertiesOfMesh(v, t, 1);
  const double area = 0.5 * n * r * r * std::sin(2 * M_PI / n);
  EXPECT_NEAR(mp.volume_m3, area * 2 * hh, 1e-5);
  const double m = mp.mass_kg;
  EXPECT_NEAR(mp.inertia_kgm2(1, 1), m * r * r / 2, 1e-3 * m * r * r / 2);
  const double perp = m * (3 * r * r + 4 * hh * hh) / 12;
  EXPECT_NEAR(mp.inertia_kgm2(0, 0), perp, 1e-3 * perp);
  EXPECT_NEAR(mp.inertia_kgm2(2, 2), perp, 1e-3 * perp);
  EXPECT_NEAR(mp.inertia_kgm2(0, 1), 0, 1e-6);
}

TEST(MassProperties, InsideOutWindingGivesNegativeVolumeAndBadIndicesAreCounted) {
  std::vector<Vec3> v;
  std::vector<Tri> t;
  boxMesh(Vec3::Ones(), v, t);
  for (Tri& tri : t) std::swap(tri[1], tri[2]);
  t.push_back({0, 1, 99});
  const MassProperties mp = massPropertiesOfMesh(v, t, 1);
  EXPECT_NEAR(mp.volume_m3, -8, 1e-4);
  EXPECT_EQ(mp.skippedTriangles, 1);
}

TEST(ConvexHull, CubeWithInteriorPointsHasSixQuadFaces) {
  std::vector<Vec3> pts;
  for (int i = 0; i < 8; ++i) pts.emplace_back((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
  for (int i = 0; i < 50; ++i) pts.emplace_back(std::sin(i * 1.3f) * 0.9f, std::cos(i * 0.7f) * 0.9f, std::sin(i * 2.1f) * 0.9f);
  pts.emplace_back(0, 1, 0);  // on a face: not a vertex
  auto hull = computeConvexHull(pts);
  ASSERT_TRUE(hull.ok()) << hull.error();
  EXPECT_EQ(hull->vertices_m.size(), 8u);
  EXPECT_EQ(hull->faces.size(), 6u);
  EXPECT_EQ(hull->edges.size(), 12u);
  for (const HullFace& f : hull->faces) {
    EXPECT_EQ(f.count, 4u);
    EXPECT_NEAR(f.offset_m, 1, 1e-6);
  }
  for (const HullEdge& e : hull->edges) EXPECT_NE(e.face0, e.face1);
  EXPECT_NEAR(hull->volume_m3, 8, 1e-4);
  // Euler: V - E + F = 2.
  EXPECT_EQ(int(hull->vertices_m.size()) - int(hull->edges.size()) + int(hull->faces.size()), 2);
}

TEST(ConvexHull, RandomCloudContainsEveryPointAndSatisfiesEuler) {
  std::vector<Vec3> pts;
  std::uint32_t seed = 12345;
  auto rnd = [&] {
    seed = seed * 1664525u + 1013904223u;
    return Real(seed >> 8) / Real(1 << 24) * 2 - 1;
  };
  for (int i = 0; i < 300; ++i) pts.emplace_back(rnd(), rnd() * 0.5f, rnd() * 2);
  auto hull = computeConvexHull(pts);
  ASSERT_TRUE(hull.ok()) << hull.error();
  for (const Vec3& p : pts)
    for (const HullFace& f : hull->faces) EXPECT_LE(f.normal.dot(p) - f.offset_m, 1e-4);
  EXPECT_EQ(int(hull->vertices_m.size()) - int(hull->edges.size()) + int(hull->faces.size()), 2);
  EXPECT_GT(hull->volume_m3, 0);
}

TEST(ConvexHull, GridWithManyCoplanarAndCollinearPointsIsACube) {
  // 5 x 5 x 5 grid: most points lie on faces and edges of the hull.
  std::vector<Vec3> pts;
  for (int i = 0; i < 125; ++i) pts.emplace_back(Real(i % 5), Real((i / 5) % 5), Real(i / 25));
  auto hull = computeConvexHull(pts);
  ASSERT_TRUE(hull.ok()) << hull.error();
  EXPECT_EQ(hull->faces.size(), 6u);
  EXPECT_NEAR(hull->volume_m3, 64, 1e-3);
  EXPECT_LT((hull->centroid_m - Vec3::Constant(2)).norm(), 1e-5);
}

TEST(ConvexHull, ThousandPointsNearASphereGiveAClosedHullAroundThemAll) {
  std::vector<Vec3> pts;
  std::uint32_t seed = 99;
  auto rnd = [&] {
    seed = seed * 1664525u + 1013904223u;
    return Real(seed >> 8) / Real(1 << 24) * 2 - 1;
  };
  while (pts.size() < 1000) {
    Vec3 p(rnd(), rnd(), rnd());
    if (p.norm() < Real(0.1) || p.norm() > 1) continue;
    pts.push_back(p.normalized() * (1 + Real(1e-4) * rnd()));  // nearly cospherical: many thin triangles
  }
  auto hull = computeConvexHull(pts);
  ASSERT_TRUE(hull.ok()) << hull.error();
  for (const Vec3& p : pts)
    for (const HullFace& f : hull->faces) ASSERT_LE(f.normal.dot(p) - f.offset_m, 1e-4);
  EXPECT_EQ(int(hull->vertices_m.size()) - int(hull->edges.size()) + int(hull->faces.size()), 2);
  // Close to the unit ball's volume 4/3 pi (a polytope inside it).
  EXPECT_NEAR(hull->volume_m3, 4.18879, 0.1);
  EXPECT_LT(hull->volume_m3, 4.19);
}

TEST(ConvexHull, RefusesTooFewCoplanarAndNonFinitePoints) {
  const std::vector<Vec3> three = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  auto a = computeConvexHull(three);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.error().find("at least 4"), std::string::npos) << a.error();
  const std::vector<Vec3> flat = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0.5f, 0, 0.2f)};
  auto b = computeConvexHull(flat);
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.error().find("coplanar"), std::string::npos) << b.error();
  std::vector<Vec3> nan = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, std::nanf(""))};
  auto c = computeConvexHull(nan);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().find("point 4"), std::string::npos) << c.error();
}

TEST(ConvexHull, ShapeIsMovedToItsPrincipalFrame) {
  // Box points, rotated and shifted: the shape's frame is the box's centre
  // and axes; its inertia is the box's.
  const Vec3 h(0.2f, 0.5f, 1);
  const Quat q = Quat(Eigen::AngleAxis<Real>(Real(0.4), Vec3(0, 1, 1).normalized()));
  const Vec3 shift(3, 2, 1);
  std::vector<Vec3> pts;
  for (int i = 0; i < 8; ++i)
    pts.push_back(shift + q * Vec3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()));
  ShapeFrame frame;
  auto shape = makeHullShape(pts, &frame);
  ASSERT_TRUE(shape.ok()) << shape.error();
  EXPECT_LT((frame.centre_m - shift).norm(), 1e-5);
  // The principal axes are the box's axes: the moments are the box's, in its axis order.
  EXPECT_LT((shape->unitInertia() - boxInertia(1, h).diagonal()).norm(), 1e-5);
  EXPECT_LT(frame.rotation.angularDistance(q), 1e-3);
  EXPECT_NEAR(shape->volume(), 8 * h.prod(), 1e-5);
  // Every original point is a vertex of the body-frame hull moved back.
  for (const Vec3& p : pts) {
    const Vec3 local = frame.rotation.conjugate() * (p - frame.centre_m);
    Real best = 1;
    for (const Vec3& v : shape->hull->vertices_m) best = std::min(best, (v - local).norm());
    EXPECT_LT(best, 1e-5);
  }
  EXPECT_NEAR(shape->innerRadius(), h.minCoeff(), 1e-5);
}

TEST(CompoundShape, TwoBoxesUseTheParallelAxisTheorem) {
  // A T of two equal boxes: bar along x at y = 0, stem along y below it.
  const Vec3 hBar(1, 0.1f, 0.1f), hStem(0.1f, 0.5f, 0.1f);
  std::vector<CompoundChild> kids = {{Shape::box(hBar), Vec3(0, 0, 0), Quat::Identity()},
                                     {Shape::box(hStem), Vec3(0, -0.6f, 0), Quat::Identity()}};
  ShapeFrame frame;
  auto shape = makeCompoundShape(kids, &frame);
  ASSERT_TRUE(shape.ok()) << shape.error();
  const Real vBar = 8 * hBar.prod(), vStem = 8 * hStem.prod(), v = vBar + vStem;
  const Real cy = vStem * Real(-0.6) / v;
  EXPECT_NEAR(shape->volume(), v, 1e-6);
  EXPECT_LT((frame.centre_m - Vec3(0, cy, 0)).norm(), 1e-6);
  // Per unit density about the centre: each box's own + m d^2.
  const Vec3 iBar = boxInertia(vBar, hBar).diagonal(), iStem = boxInertia(vStem, hStem).diagonal();
  const Real dBar = -cy, dStem = Real(-0.6) - cy;
  const Vec3 expected(iBar.x() + vBar * dBar * dBar + iStem.x() + vStem * dStem * dStem, iBar.y() + iStem.y(),
                      iBar.z() + vBar * dBar * dBar + iStem.z() + vStem * dStem * dStem);
  // The children's axes are already principal: the frame keeps them.
  EXPECT_LT(frame.rotation.angularDistance(Quat::Identity()), 1e-6);
  const Vec3 got = shape->unitInertia() * v;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], expected[i], 1e-5 * expected.maxCoeff());
  // The children moved into the body frame keep their distance.
  const auto& c = shape->compound->children;
  EXPECT_NEAR((c[0].position_m - c[1].position_m).norm(), 0.6f, 1e-6);
}

TEST(CompoundShape, RefusesEmptyPlaneAndBadChildren) {
  EXPECT_FALSE(makeCompoundShape({}).ok());
  auto plane = makeCompoundShape({{Shape::plane(), Vec3::Zero(), Quat::Identity()}});
  ASSERT_FALSE(plane.ok());
  EXPECT_NE(plane.error().find("child 1"), std::string::npos) << plane.error();
  auto bad = makeCompoundShape({{Shape::sphere(1), Vec3::Zero(), Quat::Identity()},
                                {Shape::sphere(-1), Vec3::Zero(), Quat::Identity()}});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find("child 2"), std::string::npos) << bad.error();
}

}  // namespace
}  // namespace tumble::physics::test
