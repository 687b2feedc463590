// Generators and filters: deterministic per seed, and each one does what its
// name says (smoothing lowers variance, a ramp stays a ramp, ...).
#include <gtest/gtest.h>

#include <cmath>

#include "terrain/filters.h"
#include "terrain/generators.h"
#include "terrain/height_map.h"
#include "test_util.h"

using namespace tumble;
using namespace tumble::terrain;
using namespace tumble::terrain::test;

namespace {

double variance(const HeightMap& m) {
  double sum = 0, sum2 = 0;
  for (auto v : m.samples()) sum += v, sum2 += double(v) * v;
  const double n = double(m.sampleCount());
  return sum2 / n - (sum / n) * (sum / n);
}

double meanNeighbourDifference(const HeightMap& m) {
  double sum = 0;
  for (int j = 0; j < m.height(); ++j)
    for (int i = 0; i + 1 < m.width(); ++i) sum += std::abs(double(m.at(i + 1, j)) - m.at(i, j));
  return sum / double((m.width() - 1) * m.height());
}

}  // namespace

TEST(Plasma, SameSeedSameBytesDifferentSeedDifferentMap) {
  const HeightMap a = generatePlasma(129, 129, {42, 0.5});
  const HeightMap b = generatePlasma(129, 129, {42, 0.5});
  const HeightMap c = generatePlasma(129, 129, {43, 0.5});
  EXPECT_TRUE(a == b);
  EXPECT_FALSE(a == c);
  // The PNG bytes too, not just the samples.
  EXPECT_EQ(*encodeHeightMapPng(a), *encodeHeightMapPng(b));
}

TEST(Plasma, BytesArePinnedAcrossMachines) {
  // The generator uses only splitmix64 and IEEE double arithmetic, so the
  // hash is the same on every machine and compiler. If it changes, old seeds
  // produce new maps: bump this constant only on purpose.
  EXPECT_EQ(hashMap(generatePlasma(65, 65, {42, 0.5})), 0x27731ed38d81e4c5ull) << std::hex << hashMap(generatePlasma(65, 65, {42, 0.5}));
}

TEST(Plasma, AnySizeUsesTheFullRangeAndIsACropOfTheCoveringGrid) {
  const HeightMap m = generatePlasma(100, 37, {7, 0.5});
  ASSERT_EQ(m.width(), 100);
  ASSERT_EQ(m.height(), 37);
  const auto [lo, hi] = std::minmax_element(m.samples().begin(), m.samples().end());
  EXPECT_EQ(*lo, 0);
  EXPECT_EQ(*hi, 65535);
  // Cropping keeps the feature scale: the same seed on 129^2 (the covering
  // grid) has the same shape in that corner, up to the renormalisation.
  const HeightMap big = generatePlasma(129, 129, {7, 0.5});
  double corr = 0, na = 0, nb = 0, ma = 0, mb = 0;
  for (int j = 0; j < 37; ++j)
    for (int i = 0; i < 100; ++i) ma += m.at(i, j), mb += big.at(i, j);
  ma /= 3700, mb /= 3700;
  for (int j = 0; j < 37; ++j)
    for (int i = 0; i < 100; ++i) {
      const double a = m.at(i, j) - ma, b = big.at(i, j) - mb;
      corr += a * b, na += a * a, nb += b * b;
    }
  EXPECT_GT(corr / std::sqrt(na * nb), 0.9999);
}

TEST(Plasma, HigherRoughnessMeansRougherGround) {
  const double smoothish = meanNeighbourDifference(generatePlasma(257, 257, {3, 0.35}));
  const double rough = meanNeighbourDifference(generatePlasma(257, 257, {3, 0.75}));
  EXPECT_GT(rough, 3 * smoothish);
}

TEST(Plasma, RegionAddsInsideAndFadesToNothingAtItsBorder) {
  HeightMap m(65, 65, 10000);
  addPlasmaRegion(m, 10, 20, 33, 25, 5000, {11, 0.5});
  bool raised = false;
  for (int j = 0; j < 65; ++j)
    for (int i = 0; i < 65; ++i) {
      const bool inside = i > 10 && i < 42 && j > 20 && j < 44;
      if (!inside) {
        EXPECT_EQ(m.at(i, j), 10000) << i << "," << j;
      }
      if (inside && m.at(i, j) > 10000) raised = true;
      EXPECT_LE(m.at(i, j), 15000);
    }
  EXPECT_TRUE(raised);
}

TEST(Ridge, RaisesTheCrestLeavesFarGroundAndDitchDigs) {
  HeightMap m(101, 101, 20000);
  RidgeParams p;
  p.fromX = 10, p.fromZ = 50, p.toX = 90, p.toZ = 50;
  p.height = 3000;
  p.halfWidth = 6;
  p.jaggedness = 0;  // straight: the crest is on z = 50
  addRidge(m, p);
  EXPECT_EQ(m.at(50, 50), 23000);
  EXPECT_EQ(m.at(50, 56), 20000);  // profile reaches 0 at the half-width
  EXPECT_GT(m.at(50, 53), 20000);
  EXPECT_LT(m.at(50, 53), 23000);
  EXPECT_EQ(m.at(50, 80), 20000);

  HeightMap d(101, 101, 20000);
  p.height = -4000;
  p.jaggedness = 0.3;
  p.seed = 5;
  addRidge(d, p);
  const auto lowest = *std::min_element(d.samples().begin(), d.samples().end());
  EXPECT_LT(lowest, 17000);
  EXPECT_EQ(d.at(50, 5), 20000);
  // Same seed, same ditch.
  HeightMap again(101, 101, 20000);
  addRidge(again, p);
  EXPECT_TRUE(again == d);
}

TEST(Filters, SmoothingReducesVarianceAndKeepsFlatFlat) {
  const HeightMap noisy = generatePlasma(129, 129, {9, 0.8});
  const HeightMap once = smooth(noisy, 1);
  const HeightMap many = smooth(noisy, 8);
  EXPECT_LT(variance(once), variance(noisy));
  EXPECT_LT(variance(many), variance(once));
  EXPECT_LT(meanNeighbourDifference(many), 0.5 * meanNeighbourDifference(noisy));
  const HeightMap flat(17, 9, 1234);
  EXPECT_TRUE(smooth(flat, 3) == flat);
  EXPECT_TRUE(sharpen(flat, 1.0) == flat);
}

TEST(Filters, SharpenIncreasesLocalContrast) {
  // A step edge 1000 | 3000 along X: the Laplacian kernel overshoots by
  // amount * step on both sides and leaves the flat parts alone.
  HeightMap step(10, 5);
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 10; ++i) step.set(i, j, i < 5 ? 1000 : 3000);
  const HeightMap s = sharpen(step, 0.5);
  EXPECT_EQ(s.at(4, 2), 0);
  EXPECT_EQ(s.at(5, 2), 4000);
  EXPECT_EQ(s.at(2, 2), 1000);
  EXPECT_EQ(s.at(8, 2), 3000);
  const HeightMap plasma = generatePlasma(129, 129, {9, 0.5});
  EXPECT_GT(meanNeighbourDifference(sharpen(plasma, 1.0)), 1.3 * meanNeighbourDifference(plasma));
}

TEST(Filters, CustomKernels) {
  const HeightMap m = generatePlasma(33, 21, {2, 0.5});
  auto identity = makeKernel(3, {0, 0, 0, 0, 1, 0, 0, 0, 0}, "test");
  ASSERT_TRUE(identity.ok());
  EXPECT_TRUE(convolve(m, *identity) == m);
  // A shift kernel: output(i, j) = input(i + 1, j) (row = Z offset, column = X offset).
  auto shift = makeKernel(3, {0, 0, 0, 0, 0, 1, 0, 0, 0}, "test");
  const HeightMap shifted = convolve(m, *shift);
  EXPECT_EQ(shifted.at(4, 7), m.at(5, 7));
  EXPECT_EQ(shifted.at(32, 7), m.at(32, 7));  // clamped at the edge
  EXPECT_FALSE(makeKernel(4, std::vector<double>(16, 1.0), "k").ok());
  EXPECT_FALSE(makeKernel(3, std::vector<double>(8, 1.0), "k").ok());
  auto bad = makeKernel(3, {0, 0, 0, 0, NAN, 0, 0, 0, 0}, "--kernel");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find("--kernel"), std::string::npos);
}

TEST(Filters, BicubicResampleKeepsALinearRampLinear) {
  // h = 1000 + 300 i + 170 j on a 65 x 49 grid.
  HeightMap ramp(65, 49);
  for (int j = 0; j < 49; ++j)
    for (int i = 0; i < 65; ++i) ramp.set(i, j, std::uint16_t(1000 + 300 * i + 170 * j));
  for (auto [w, h] : {std::pair{129, 33}, std::pair{40, 97}, std::pair{65, 49}, std::pair{2, 2}}) {
    const HeightMap out = resampleBicubic(ramp, w, h);
    ASSERT_EQ(out.width(), w);
    ASSERT_EQ(out.height(), h);
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const double x = double(i) * 64 / (w - 1), z = double(j) * 48 / (h - 1);
        EXPECT_NEAR(out.at(i, j), 1000 + 300 * x + 170 * z, 0.5 + 1e-9) << w << "x" << h << " at " << i << "," << j;
      }
  }
  EXPECT_TRUE(resampleBicubic(ramp, 65, 49) == ramp);
}

TEST(Filters, BicubicResampleOfAPlasmaKeepsItsShape) {
  const HeightMap m = generatePlasma(65, 65, {4, 0.4});
  const HeightMap up = resampleBicubic(m, 129, 129);
  for (int j = 0; j < 65; ++j)
    for (int i = 0; i < 65; ++i) EXPECT_EQ(up.at(2 * i, 2 * j), m.at(i, j));  // interpolating
  const HeightMap back = resampleBicubic(up, 65, 65);
  EXPECT_TRUE(back == m);
}

TEST(Filters, ShadedReliefLightsSlopesFacingTheLight) {
  // Ramp rising towards +X: its normal leans to -X, towards a light at -X.
  HeightMap ramp(16, 16);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) ramp.set(i, j, std::uint16_t(100 * i));
  ReliefParams fromMinusX;
  fromMinusX.towardLight = Vec3(-1, 1, 0);
  fromMinusX.elevationTint = false;
  ReliefParams fromPlusX = fromMinusX;
  fromPlusX.towardLight = Vec3(1, 1, 0);
  const TerrainDesc desc;  // 1 m spacing, 0.01 m per unit: slope 1
  const auto lit = shadedRelief(ramp, desc, fromMinusX);
  const auto dark = shadedRelief(ramp, desc, fromPlusX);
  ASSERT_EQ(lit.size(), 16u * 16u * 3u);
  const std::size_t mid = (8 * 16 + 8) * 3;
  EXPECT_EQ(lit[mid], 255);  // facing the light exactly: full brightness
  EXPECT_NEAR(dark[mid], 0.25 * 255, 1.0);  // turned 90 degrees away: ambient only
  EXPECT_TRUE(saveShadedReliefPng(ramp, desc, tempFile("relief.png")).ok());
}
