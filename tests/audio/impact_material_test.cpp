// Impacts by material (synth.h ImpactMaterial), rendered offline: what the
// materials are defined to sound like (synth.cpp materialHit) shows in the
// spectral centroid and the decay time, and the loudness still grows with
// the impulse whatever the materials.
#include <gtest/gtest.h>

#include <cmath>

#include "loopback.h"
#include "signal.h"

namespace tumble::audio {
namespace {

using test::monoSlice;

struct HitFeatures {
  double centroid_hz, decay40_s, rms;
};

/// One impact of a on b, 2 m in front of the listener, 3.5 s rendered.
HitFeatures hit(ImpactMaterial a, ImpactMaterial b, float impulse_Ns = 1000) {
  auto sys = test::loopbackSystem();
  sys->impact(Vec3(0, 0, -2), impulse_Ns, a, b);
  test::runFor(*sys, 3.5);
  const auto x = monoSlice(sys->rendered(), 0, 3.5);
  return {test::spectralCentroid(x), test::decayTime(x, 40), test::rms(x)};
}

// Each material struck on itself. Metal rings (its slowest mode decays
// with tau = 0.45 s, so 40 dB takes about 2 s) and is bright (modes up to
// 5.6 kHz); wood knocks (modes of tau <= 35 ms) with a lower spectrum;
// rubber is lower still (85 Hz and noise below 300 Hz). On the ground, rock
// clicks (noise above 1.5 kHz, modes of tau <= 12 ms) while soil (grass,
// sand, snow) thumps (60 Hz and noise below 400 Hz). Stated as: decay metal
// > 5 x wood; centroid metal > 1.5 x wood > 1.5 x rubber; rock > 3 x soil;
// wood and rock fall 40 dB within ln(100) tau of their slowest mode, plus
// two 5 ms measuring windows.
TEST(ImpactMaterialSound, CentroidAndDecayFollowTheMaterial) {
  HitFeatures f[kImpactMaterialCount];
  for (int m = 0; m < kImpactMaterialCount; ++m) {
    f[m] = hit(ImpactMaterial(m), ImpactMaterial(m));
    std::printf("%-7s centroid %6.0f Hz, 40 dB decay %.3f s\n", impactMaterialName(ImpactMaterial(m)), f[m].centroid_hz,
                f[m].decay40_s);
    EXPECT_GT(f[m].decay40_s, 0) << impactMaterialName(ImpactMaterial(m)) << " dies away within the render";
  }
  const auto& metal = f[int(ImpactMaterial::Metal)];
  const auto& wood = f[int(ImpactMaterial::Wood)];
  const auto& rubber = f[int(ImpactMaterial::Rubber)];
  const auto& rock = f[int(ImpactMaterial::Rock)];
  const auto& soil = f[int(ImpactMaterial::Soil)];
  EXPECT_GT(metal.decay40_s, 5 * wood.decay40_s);
  EXPECT_GT(metal.centroid_hz, 1.5 * wood.centroid_hz);
  EXPECT_GT(wood.centroid_hz, 1.5 * rubber.centroid_hz);
  EXPECT_GT(rock.centroid_hz, 3 * soil.centroid_hz);
  EXPECT_LT(wood.decay40_s, std::log(100.0) * 0.035 + 0.01);
  EXPECT_LT(rock.decay40_s, std::log(100.0) * 0.012 + 0.01);
}

// Two materials sound as both: metal on soil has metal's ring (decays like
// metal) and soil's thump (a centroid between the two).
TEST(ImpactMaterialSound, APairSoundsAsBoth) {
  const auto metal = hit(ImpactMaterial::Metal, ImpactMaterial::Metal);
  const auto soil = hit(ImpactMaterial::Soil, ImpactMaterial::Soil);
  const auto both = hit(ImpactMaterial::Metal, ImpactMaterial::Soil);
  const auto swapped = hit(ImpactMaterial::Soil, ImpactMaterial::Metal);
  EXPECT_GT(both.decay40_s, 0.5 * metal.decay40_s);
  EXPECT_GT(both.centroid_hz, soil.centroid_hz);
  EXPECT_LT(both.centroid_hz, metal.centroid_hz);
  EXPECT_EQ(both.rms, swapped.rms) << "the order of the two does not matter";
}

// Whatever the materials, the amplitude is proportional to the impulse up to
// kImpactFull_Ns (rms ratio = impulse ratio within 3 %), full beyond.
TEST(ImpactMaterialSound, LoudnessGrowsWithImpulseForEveryMaterial) {
  for (int m = 0; m < kImpactMaterialCount; ++m) {
    const ImpactMaterial mat = ImpactMaterial(m);
    SCOPED_TRACE(impactMaterialName(mat));
    const double l100 = hit(mat, ImpactMaterial::Rock, 100).rms;
    const double l1000 = hit(mat, ImpactMaterial::Rock, 1000).rms;
    const double l9000 = hit(mat, ImpactMaterial::Rock, 9000).rms;
    EXPECT_NEAR(l1000 / l100, 10, 0.3);
    EXPECT_NEAR(l9000 / l1000, AudioSystem::kImpactFull_Ns / 1000, 0.09);
    EXPECT_EQ(hit(mat, ImpactMaterial::Rock, 2).rms, 0.0) << "nothing below kImpactMin_Ns";
  }
}

TEST(ImpactMaterialSound, NamesRoundTrip) {
  for (int m = 0; m < kImpactMaterialCount; ++m)
    EXPECT_EQ(parseImpactMaterial(impactMaterialName(ImpactMaterial(m))), ImpactMaterial(m));
  EXPECT_FALSE(parseImpactMaterial("jelly"));
  EXPECT_FALSE(parseImpactMaterial(""));
}

}  // namespace
}  // namespace tumble::audio
