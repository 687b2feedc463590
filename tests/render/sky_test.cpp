// The sky model (CPU, no GL): where the sun stands at a time of day, the
// colours a scene gets, the horizon meeting the fog, and the generated
// cloud plasma.
#include <gtest/gtest.h>

#include <cmath>

#include "render/internal/sky_model.h"

namespace tumble::render {
namespace {

constexpr float kDegree = 3.14159265f / 180.0f;

TEST(SkyModel, TheSunRisesInTheEastStandsHighAtNoonAndSetsInTheWest) {
  const Eigen::Vector3f dawn = sunDirectionAt(6.0f), noon = sunDirectionAt(12.0f), dusk = sunDirectionAt(18.0f);
  EXPECT_NEAR(dawn.x(), 1.0f, 1e-5f);
  EXPECT_NEAR(dawn.y(), 0.0f, 1e-5f);
  EXPECT_NEAR(dusk.x(), -1.0f, 1e-5f);
  EXPECT_NEAR(std::asin(noon.y()), 65.0f * kDegree, 1e-4f);
  EXPECT_GT(noon.z(), 0.0f) << "the noon sun stands towards +Z";
  EXPECT_LT(sunDirectionAt(0.0f).y(), -0.9f) << "midnight: far below the horizon";
  EXPECT_NEAR((sunDirectionAt(30.0f) - sunDirectionAt(6.0f)).norm(), 0.0f, 1e-5f) << "wraps at 24 h";
  for (float t = 0; t < 24; t += 0.5f) EXPECT_NEAR(sunDirectionAt(t).norm(), 1.0f, 1e-5f) << t;
}

TEST(SkyModel, DefaultSettingsKeepTheLabSunAndSky) {
  const Environment lab;
  const Environment e = environmentFor(SkySettings{}, 0.0);
  EXPECT_TRUE(e.lightDirection.isApprox(lab.lightDirection));
  EXPECT_TRUE(e.horizonColor.isApprox(lab.horizonColor));
  EXPECT_TRUE(e.zenithColor.isApprox(lab.zenithColor));
  EXPECT_NEAR(e.fogDensity_per_m, 1.0f / 250.0f, 1e-7f);
  EXPECT_EQ(e.cloudCover, 0.0f) << "a lab scene's sky is clear";
}

TEST(SkyModel, NightIsDarkSunsetIsWarmAndAStormIsDimWithDenseFog) {
  SkySettings s;
  s.timeOfDay_h = 13.0f;
  const Environment day = environmentFor(s, 0.0);
  s.timeOfDay_h = 1.0f;
  const Environment night = environmentFor(s, 0.0);
  s.timeOfDay_h = 18.2f;
  const Environment sunset = environmentFor(s, 0.0);
  EXPECT_LT(night.horizonColor.sum(), 0.2f * day.horizonColor.sum());
  EXPECT_LT(night.lightColor.sum(), 0.25f * day.lightColor.sum()) << "moonlight";
  EXPECT_GT(night.lightDirection.y(), 0.0f) << "the moon lights from above";
  EXPECT_GT(sunset.horizonColor.x(), sunset.horizonColor.z()) << "a red-orange horizon at sunset";
  s = SkySettings{};
  s.weather = Weather::Storm;
  const Environment storm = environmentFor(s, 0.0);
  EXPECT_LT(storm.lightColor.sum(), 0.3f * Environment{}.lightColor.sum());
  EXPECT_NEAR(1.0f / storm.fogDensity_per_m, 70.0f, 1e-3f);
  EXPECT_EQ(storm.cloudCover, 1.0f);
  s.fogDistance_m = 0.0f;
  EXPECT_EQ(environmentFor(s, 0.0).fogDensity_per_m, 0.0f) << "fog distance 0: no fog";
}

TEST(SkyModel, TheWindMovesTheCloudsWithTime) {
  SkySettings s;
  s.wind_mps = {4.0f, -1.0f};
  const Environment e = environmentFor(s, 10.0);
  EXPECT_NEAR(e.cloudOffset_m.x(), 40.0f, 1e-4f);
  EXPECT_NEAR(e.cloudOffset_m.y(), -10.0f, 1e-4f);
}

TEST(SkyModel, TheHorizonAwayFromTheSunIsExactlyTheFogColour) {
  for (float t : {7.0f, 12.0f, 18.3f, 23.0f}) {
    SkySettings s;
    s.timeOfDay_h = t;
    const Environment e = environmentFor(s, 0.0);
    // Horizontal, at right angles to the sun's bearing.
    const Eigen::Vector3f away = Eigen::Vector3f::UnitY().cross(e.lightDirection).normalized();
    EXPECT_TRUE(clearSkyColor(e, away).isApprox(e.horizonColor, 1e-3f)) << "time " << t;
  }
}

TEST(SkyModel, TheCubeShowsTheSunDiscWhereTheSunIs) {
  Environment e;
  e.lightDirection = Eigen::Vector3f(0, 0, 1);  // the centre of the +Z face
  const int n = 64;
  const std::vector<float> cube = buildSkyCube(e, n);
  ASSERT_EQ(cube.size(), std::size_t(6 * n * n * 3));
  auto texel = [&](int face, int x, int y) {
    const float* p = &cube[((std::size_t(face) * n + y) * n + x) * 3];
    return Eigen::Vector3f(p[0], p[1], p[2]);
  };
  const Eigen::Vector3f centre = texel(4, n / 2, n / 2);
  EXPECT_GT(centre.minCoeff(), 1.0f) << "the disc is brighter than white";
  EXPECT_LT(texel(5, n / 2, n / 2).maxCoeff(), 1.0f) << "nothing bright behind";
  EXPECT_GT(texel(2, n / 2, n / 2).z(), texel(2, n / 2, n / 2).x()) << "the zenith (+Y face) is blue";
}

TEST(SkyModel, ThePlasmaTilesIsRepeatableAndUsesTheWholeRange) {
  const int n = 128;
  const std::vector<std::uint8_t> a = buildPlasma(n, 7), b = buildPlasma(n, 7), c = buildPlasma(n, 8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_EQ(*std::min_element(a.begin(), a.end()), 0);
  EXPECT_EQ(*std::max_element(a.begin(), a.end()), 255);
  // Tiling: the step across the wrap is no larger than steps inside.
  double inside = 0, across = 0;
  for (int y = 0; y < n; ++y) {
    inside += std::abs(int(a[std::size_t(y * n + n / 2)]) - int(a[std::size_t(y * n + n / 2 - 1)]));
    across += std::abs(int(a[std::size_t(y * n)]) - int(a[std::size_t(y * n + n - 1)]));
  }
  EXPECT_LT(across, 2.0 * inside + n) << "no seam where the texture repeats";
}

}  // namespace
}  // namespace tumble::render
