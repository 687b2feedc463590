// Point, ray, box and frustum queries against slow reference answers.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "terrain/generators.h"
#include "terrain/terrain.h"
#include "test_util.h"

using namespace tumble;
using namespace tumble::terrain;
using namespace tumble::terrain::test;

namespace {

using Vec3d = Eigen::Vector3d;

TerrainDesc oddDesc() {
  TerrainDesc d;
  d.spacing_m = 2.5;
  d.heightScale_m = 0.003;
  d.baseHeight_m = -40;
  d.originX_m = -123.25;
  d.originZ_m = 77.5;
  return d;
}

// The reference: world vertices from the documented mapping, in double.
Vec3d vertex(const Terrain& t, int i, int j) {
  const TerrainDesc& d = t.desc();
  return {d.originX_m + i * d.spacing_m, d.baseHeight_m + t.heights().at(i, j) * d.heightScale_m,
          d.originZ_m + j * d.spacing_m};
}

bool rayTriangle(const Vec3d& o, const Vec3d& dir, const Vec3d& a, const Vec3d& b, const Vec3d& c, double& t) {
  const Vec3d e1 = b - a, e2 = c - a, p = dir.cross(e2);
  const double det = e1.dot(p);
  if (det == 0) return false;
  const Vec3d s = o - a;
  const double u = s.dot(p) / det;
  if (u < 0 || u > 1) return false;
  const Vec3d q = s.cross(e1);
  const double v = dir.dot(q) / det;
  if (v < 0 || u + v > 1) return false;
  t = e2.dot(q) / det;
  return true;
}

// Every triangle of the terrain, no tree.
std::optional<double> bruteRay(const Terrain& t, const Vec3d& o, Vec3d dir, double maxT) {
  dir.normalize();
  std::optional<double> best;
  for (int bj = 0; bj < t.blocksZ(); ++bj)
    for (int bi = 0; bi < t.blocksX(); ++bi) {
      const Vec3d p00 = vertex(t, bi, bj), p10 = vertex(t, bi + 1, bj), p01 = vertex(t, bi, bj + 1),
                  p11 = vertex(t, bi + 1, bj + 1);
      double s;
      if (rayTriangle(o, dir, p00, p11, p10, s) && s >= 0 && s <= maxT && (!best || s < *best)) best = s;
      if (rayTriangle(o, dir, p00, p01, p11, s) && s >= 0 && s <= maxT && (!best || s < *best)) best = s;
    }
  return best;
}

}  // namespace

TEST(PointQueries, HeightAtSamplePointsEqualsTheSample) {
  auto t = Terrain::create(generatePlasma(65, 33, {3, 0.5}), oddDesc());
  ASSERT_TRUE(t.ok());
  for (int j = 0; j < 33; ++j)
    for (int i = 0; i < 65; ++i) {
      const Vec3 p = t->samplePosition(i, j);
      ASSERT_NEAR(t->heightAt(p.x(), p.z()), vertex(*t, i, j).y(), 1e-4) << i << "," << j;
    }
}

TEST(PointQueries, NormalOnAPlaneIsTheAnalyticNormal) {
  // y = base + scale * (5000 + 40 i - 25 j): slopes 40*scale/spacing along X, -25*scale/spacing along Z.
  const TerrainDesc d = oddDesc();
  HeightMap plane(40, 30);
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 40; ++i) plane.set(i, j, std::uint16_t(5000 + 40 * i - 25 * j));
  auto t = Terrain::create(plane, d);
  ASSERT_TRUE(t.ok());
  const Vec3d expected = Vec3d(-40 * d.heightScale_m / d.spacing_m, 1, 25 * d.heightScale_m / d.spacing_m).normalized();
  Rng rng(4);
  for (int k = 0; k < 500; ++k) {
    const double x = d.originX_m + rng.unit() * 39 * d.spacing_m, z = d.originZ_m + rng.unit() * 29 * d.spacing_m;
    const Vec3 n = t->normalAt(Real(x), Real(z));
    EXPECT_NEAR(n.x(), expected.x(), 1e-6);
    EXPECT_NEAR(n.y(), expected.y(), 1e-6);
    EXPECT_NEAR(n.z(), expected.z(), 1e-6);
    // And the height is the plane's.
    const double gx = (Real(x) - d.originX_m) / d.spacing_m, gz = (Real(z) - d.originZ_m) / d.spacing_m;
    EXPECT_NEAR(t->heightAt(Real(x), Real(z)), d.baseHeight_m + d.heightScale_m * (5000 + 40 * gx - 25 * gz), 1e-3);
  }
}

TEST(PointQueries, HeightAndNormalFollowTheDocumentedSplit) {
  // One block with only the far corner p11 raised: along the p00-p11 diagonal
  // split, half 0 (u >= v) is (p00, p11, p10) so the point (u, v) = (0.75, 0.25)
  // has height 0.25 * h11 (not 0 as the other diagonal would give).
  HeightMap m(2, 2, 0);
  m.set(1, 1, 4000);
  auto t = Terrain::create(m, {});
  ASSERT_TRUE(t.ok());
  EXPECT_NEAR(t->heightAt(0.75f, 0.25f), 0.25 * 40.0, 1e-4);
  EXPECT_NEAR(t->heightAt(0.25f, 0.75f), 0.25 * 40.0, 1e-4);
  EXPECT_NEAR(t->heightAt(0.5f, 0.5f), 0.5 * 40.0, 1e-4);
  const TerrainTriangle a = t->triangle(0, 0), b = t->triangle(0, 1);
  for (const TerrainTriangle& tri : {a, b}) {
    const Vec3 n = (tri.vertices[1] - tri.vertices[0]).cross(tri.vertices[2] - tri.vertices[0]).normalized();
    EXPECT_GT(n.y(), 0);  // counter-clockwise from above
    EXPECT_NEAR((n - tri.normal).norm(), 0, 1e-5);
  }
  EXPECT_NEAR((t->normalAt(0.75f, 0.25f) - a.normal).norm(), 0, 1e-6);
  EXPECT_NEAR((t->normalAt(0.25f, 0.75f) - b.normal).norm(), 0, 1e-6);
}

TEST(RayCast, AgreesWithBruteForceOnRandomRays) {
  for (int leaf : {8, 1}) {
    SCOPED_TRACE(leaf);
    HeightMap m = generatePlasma(129, 97, {17, 0.55});
    auto t = Terrain::create(std::move(m), oddDesc(), leaf);
    ASSERT_TRUE(t.ok());
    const Aabb box = t->bounds();
    Rng rng(2024);
    int hits = 0, misses = 0;
    const int kRays = 1200;
    for (int k = 0; k < kRays; ++k) {
      const auto lerp = [&](double a, double b) { return a + (b - a) * rng.unit(); };
      Vec3d o, dir;
      const int kind = k % 4;
      if (kind == 0) {  // from above, steeply down
        o = {lerp(box.min.x() - 20, box.max.x() + 20), lerp(box.max.y(), box.max.y() + 100),
             lerp(box.min.z() - 20, box.max.z() + 20)};
        dir = {rng.symmetric(), -1 - rng.unit(), rng.symmetric()};
      } else if (kind == 1) {  // grazing, nearly horizontal, inside the height range
        o = {lerp(box.min.x(), box.max.x()), lerp(box.min.y(), box.max.y()), lerp(box.min.z(), box.max.z())};
        dir = {rng.symmetric(), 0.05 * rng.symmetric(), rng.symmetric()};
      } else if (kind == 2) {  // any direction from anywhere around
        o = {lerp(box.min.x() - 50, box.max.x() + 50), lerp(box.min.y() - 20, box.max.y() + 50),
             lerp(box.min.z() - 50, box.max.z() + 50)};
        dir = {rng.symmetric(), rng.symmetric(), rng.symmetric()};
      } else {  // straight down, or axis-parallel
        o = {lerp(box.min.x() - 5, box.max.x() + 5), box.max.y() + 10, lerp(box.min.z() - 5, box.max.z() + 5)};
        dir = (k % 8 == 3) ? Vec3d(0, -1, 0) : Vec3d(0, -1, 0.5);
      }
      const double maxT = (k % 5 == 0) ? lerp(1, 100) : 1e4;
      const Vec3d oRounded = o.cast<Real>().cast<double>(), dirRounded = dir.cast<Real>().cast<double>();
      const auto expected = bruteRay(*t, oRounded, dirRounded, Real(maxT));
      const auto got = t->rayCast(oRounded.cast<Real>(), dirRounded.cast<Real>(), Real(maxT));
      ASSERT_EQ(got.has_value(), expected.has_value()) << "ray " << k;
      if (!got) {
        ++misses;
        continue;
      }
      ++hits;
      EXPECT_NEAR(got->distance_m, *expected, 1e-4 * std::max(1.0, *expected)) << "ray " << k;
      const Vec3d p = oRounded + *expected * dirRounded.normalized();
      EXPECT_NEAR((got->point.cast<double>() - p).norm(), 0, 1e-3) << "ray " << k;
      const TerrainTriangle tri = t->triangle(got->block, got->half);
      EXPECT_NEAR((tri.normal - got->normal).norm(), 0, 1e-5);
    }
    EXPECT_GT(hits, kRays / 4);
    EXPECT_GT(misses, kRays / 10);
  }
}

TEST(RayCast, VerticalRayHitsAtHeightAt) {
  auto t = Terrain::create(generatePlasma(65, 65, {5, 0.5}), oddDesc());
  ASSERT_TRUE(t.ok());
  Rng rng(8);
  for (int k = 0; k < 300; ++k) {
    const Real x = Real(t->desc().originX_m + rng.unit() * 64 * t->desc().spacing_m);
    const Real z = Real(t->desc().originZ_m + rng.unit() * 64 * t->desc().spacing_m);
    const auto hit = t->rayCast(Vec3(x, 1000, z), Vec3(0, -1, 0), 5000);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->point.y(), t->heightAt(x, z), 1e-3);
    EXPECT_NEAR((hit->normal - t->normalAt(x, z)).norm(), 0, 1e-5);
  }
  EXPECT_FALSE(t->rayCast(Vec3(0, 1000, 0), Vec3(0, 0, 0), 10).has_value());  // zero direction
  EXPECT_FALSE(t->rayCast(Vec3(0, 1000, 100), Vec3(0, 1, 0), 1e6).has_value());  // pointing away
  // A NaN position gives NaN back, never an out-of-range read.
  EXPECT_TRUE(std::isnan(t->heightAt(NAN, 100)));
  EXPECT_FALSE(t->rayCast(Vec3(NAN, 1000, 100), Vec3(0, -1, 0), 1e6).has_value());
}

TEST(BoxOverlap, ReturnsExactlyTheTrianglesWhoseBoundsTouchTheBox) {
  auto t = Terrain::create(generatePlasma(97, 81, {12, 0.6}), oddDesc(), 4);
  ASSERT_TRUE(t.ok());
  Rng rng(77);
  const Aabb all = t->bounds();
  std::vector<TerrainTriangle> tris;
  tris.reserve(4096);
  for (int k = 0; k < 60; ++k) {
    const auto lerp = [&](double a, double b) { return Real(a + (b - a) * rng.unit()); };
    const Vec3 c(lerp(all.min.x() - 5, all.max.x() + 5), lerp(all.min.y(), all.max.y()),
                 lerp(all.min.z() - 5, all.max.z() + 5));
    const Vec3 half(lerp(0.1, 12), lerp(0.1, 8), lerp(0.1, 12));
    const Aabb box{c - half, c + half};
    t->overlapBox(box, tris);
    std::set<std::pair<std::uint32_t, int>> got, expected;
    for (const auto& tri : tris) got.insert({tri.block, tri.half});
    EXPECT_EQ(got.size(), tris.size());  // no duplicates
    for (std::uint32_t b = 0; b < std::uint32_t(t->blocksX() * t->blocksZ()); ++b)
      for (int h = 0; h < 2; ++h) {
        const TerrainTriangle tri = t->triangle(b, h);
        Aabb tb{tri.vertices[0], tri.vertices[0]};
        for (const Vec3& v : tri.vertices) tb.min = tb.min.cwiseMin(v), tb.max = tb.max.cwiseMax(v);
        if (tb.overlaps(box)) expected.insert({b, h});
      }
    EXPECT_EQ(got, expected) << "box " << k;
  }
  // The callback form visits the same triangles without a container.
  int count = 0;
  const Aabb box{Vec3(-100, -1000, 100), Vec3(-90, 1000, 110)};
  t->forEachTriangleInBox(box, [&count](const TerrainTriangle&) { ++count; });
  t->overlapBox(box, tris);
  EXPECT_EQ(count, int(tris.size()));
  EXPECT_GT(count, 0);
}

TEST(FrustumCull, MatchesBruteForceForABoxShapedFrustum) {
  auto t = Terrain::create(generatePlasma(257, 193, {6, 0.5}), {});
  ASSERT_TRUE(t.ok());
  const HeightTree& tree = t->tree();
  // Planes bounding 40 <= x <= 150, 0 <= y <= 300, 20 <= z <= 90 (inside: n.p + d >= 0).
  Frustum f;
  f.planes = {Vec4(1, 0, 0, -40), Vec4(-1, 0, 0, 150), Vec4(0, 1, 0, 0),
              Vec4(0, -1, 0, 300), Vec4(0, 0, 1, -20), Vec4(0, 0, -1, 90)};
  for (int level = 0; level <= tree.leafLevel() + 1; ++level) {
    std::vector<std::uint32_t> visible;
    t->frustumCull(f, level, visible);
    const int l = std::min(level, tree.leafLevel());
    std::set<std::uint32_t> expected;
    for (int z = 0; z < tree.levelHeight(l); ++z)
      for (int x = 0; x < tree.levelWidth(l); ++x) {
        const Aabb b = t->nodeBounds(tree.index(l, x, z));
        if (b.max.x() >= 40 && b.min.x() <= 150 && b.max.z() >= 20 && b.min.z() <= 90 && b.max.y() >= 0 &&
            b.min.y() <= 300)
          expected.insert(tree.index(l, x, z));
      }
    EXPECT_EQ(std::set<std::uint32_t>(visible.begin(), visible.end()), expected) << "level " << level;
    EXPECT_EQ(visible.size(), expected.size());
  }
}

TEST(FrustumCull, PerspectiveCameraSeesWhatIsInFrontOnly) {
  TerrainDesc desc;
  desc.heightScale_m = 0.001;  // 0..65 m of relief on 256 m
  auto t = Terrain::create(generatePlasma(257, 257, {6, 0.5}), desc);
  ASSERT_TRUE(t.ok());
  // Camera at (128, 80, 40) looking along +Z and a little down; 60 degree fov.
  const Eigen::Vector3f eye(128, 80, 40), target(128, 30, 140), up(0, 1, 0);
  const Eigen::Vector3f fwd = (target - eye).normalized(), right = fwd.cross(up).normalized(), u = right.cross(fwd);
  Eigen::Matrix4f view = Eigen::Matrix4f::Identity();
  view.row(0) << right.transpose(), -right.dot(eye);
  view.row(1) << u.transpose(), -u.dot(eye);
  view.row(2) << -fwd.transpose(), fwd.dot(eye);
  const float n = 1, fa = 2000, tanHalf = std::tan(0.5f * 60 * kPi / 180);
  Eigen::Matrix4f proj = Eigen::Matrix4f::Zero();
  proj(0, 0) = 1 / tanHalf, proj(1, 1) = 1 / tanHalf;
  proj(2, 2) = -(fa + n) / (fa - n), proj(2, 3) = -2 * fa * n / (fa - n), proj(3, 2) = -1;
  const Eigen::Matrix4f vp = proj * view;
  const Frustum f = Frustum::fromViewProjection(vp.cast<Real>());
  std::vector<std::uint32_t> visible;
  const int level = t->tree().leafLevel();
  t->frustumCull(f, level, visible);
  const std::set<std::uint32_t> seen(visible.begin(), visible.end());
  ASSERT_FALSE(seen.empty());
  EXPECT_LT(seen.size(), std::size_t(t->tree().levelWidth(level) * t->tree().levelHeight(level)));
  // Every leaf with a corner that projects inside the clip volume is listed.
  for (int z = 0; z < t->tree().levelHeight(level); ++z)
    for (int x = 0; x < t->tree().levelWidth(level); ++x) {
      const Aabb b = t->nodeBounds(t->tree().index(level, x, z));
      bool anyInside = false;
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector4f p((c & 1) ? b.max.x() : b.min.x(), (c & 2) ? b.max.y() : b.min.y(),
                                (c & 4) ? b.max.z() : b.min.z(), 1);
        const Eigen::Vector4f clip = vp * p;
        if (clip.w() > 0 && std::abs(clip.x()) <= clip.w() && std::abs(clip.y()) <= clip.w() &&
            std::abs(clip.z()) <= clip.w())
          anyInside = true;
      }
      if (anyInside) {
        EXPECT_TRUE(seen.count(t->tree().index(level, x, z))) << x << "," << z;
      }
    }
}

TEST(Friction, ComesFromTheDragMapOrTheDefault) {
  auto t = Terrain::create(HeightMap(9, 9, 0), oddDesc());
  ASSERT_TRUE(t.ok());
  EXPECT_FLOAT_EQ(t->frictionAt(0, 100), 0.6f);
  EXPECT_EQ(t->materials(), nullptr);
  MaterialMaps& mat = t->createMaterials();
  mat.set(MaterialLayer::Friction, 2, 3, 25);  // a puddle
  const Vec3 inside = t->samplePosition(2, 3) + Vec3(1.0f, 0, 1.0f);
  EXPECT_FLOAT_EQ(t->frictionAt(inside.x(), inside.z()), 0.25f);
  const Vec3 next = t->samplePosition(3, 3) + Vec3(1.0f, 0, 1.0f);
  EXPECT_FLOAT_EQ(t->frictionAt(next.x(), next.z()), 0.6f);
}

// Softness (rolling drag on soft ground) is a layer of its own: a block of
// ice keeps the default softness when only its friction is painted low, and
// a block of mud gets its softness from the softness layer.
TEST(Softness, ComesFromItsOwnLayerNotFromFriction) {
  auto t = Terrain::create(HeightMap(9, 9, 0), oddDesc());
  ASSERT_TRUE(t.ok());
  EXPECT_FLOAT_EQ(t->softnessAt(0, 100), 0.4f);  // no material maps: grass
  MaterialMaps& mat = t->createMaterials();
  mat.set(MaterialLayer::Friction, 2, 3, 10);  // ice: slippery...
  mat.set(MaterialLayer::Softness, 2, 3, 0);   // ...and hard
  mat.set(MaterialLayer::Friction, 3, 3, 30);  // mud
  mat.set(MaterialLayer::Softness, 3, 3, 70);
  const Vec3 ice = t->samplePosition(2, 3) + Vec3(1.0f, 0, 1.0f), mud = t->samplePosition(3, 3) + Vec3(1.0f, 0, 1.0f);
  EXPECT_FLOAT_EQ(t->frictionAt(ice.x(), ice.z()), 0.1f);
  EXPECT_FLOAT_EQ(t->softnessAt(ice.x(), ice.z()), 0.0f);
  EXPECT_FLOAT_EQ(t->softnessAt(mud.x(), mud.z()), 0.7f);
  const Vec3 grass = t->samplePosition(4, 3) + Vec3(1.0f, 0, 1.0f);
  EXPECT_FLOAT_EQ(t->softnessAt(grass.x(), grass.z()), 0.4f);
}
