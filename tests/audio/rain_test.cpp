// Rain (AudioSystem::setRain), rendered offline: silent when dry, a
// broadband hiss when it rains, fading in and out with the time constant
// kRainFade_s the audio system defines.
#include <gtest/gtest.h>

#include <cmath>

#include "loopback.h"
#include "signal.h"

namespace tumble::audio {
namespace {

using test::kTestStep_s;
using test::monoSlice;
using test::rms;

TEST(RainSound, SilentWhenDry) {
  auto sys = test::loopbackSystem();
  sys->setRain(0);
  test::runFor(*sys, 3);
  EXPECT_EQ(rms(monoSlice(sys->rendered(), 0, 3)), 0.0);
  EXPECT_EQ(sys->rainLevel(), 0.0f);
}

// A downpour is a broadband hiss, not a tone or a rumble: each octave from
// 500 Hz to 8 kHz carries between 5 % and 60 % of the power, the spectral
// centroid lies between 1.5 and 6 kHz, and the spectrum is flat (spectral
// flatness over 50 Hz..12 kHz above 0.2; the engine note's is below 0.05).
TEST(RainSound, ADownpourIsABroadbandHiss) {
  auto sys = test::loopbackSystem();
  sys->setRain(1);
  test::runFor(*sys, 10);
  const auto x = monoSlice(sys->rendered(), 8, 10);  // five fade time constants in: steady
  const double level = rms(x), centroid = test::spectralCentroid(x), flatness = test::spectralFlatness(x);
  std::printf("rain: rms %.4f, centroid %.0f Hz, flatness %.3f, octaves", level, centroid, flatness);
  for (double lo = 500; lo < 8000; lo *= 2) {
    const double f = test::bandPowerFraction(x, lo, 2 * lo);
    std::printf(" %.0f-%.0f Hz %.1f %%", lo, 2 * lo, 100 * f);
    EXPECT_GT(f, 0.05) << lo << " Hz octave";
    EXPECT_LT(f, 0.60) << lo << " Hz octave";
  }
  std::printf("\n");
  EXPECT_GT(level, 0.05);
  EXPECT_GT(centroid, 1500);
  EXPECT_LT(centroid, 6000);
  EXPECT_GT(flatness, 0.2);

  // For comparison: the engine note is tonal.
  auto engine = test::loopbackSystem();
  VehicleSoundInput car;
  car.position_m = Vec3(0, 0, -2);
  car.rpm = 3000;
  car.load = 1;
  test::runFor(*engine, 1.2, [&] { engine->updateVehicle(1, car); });
  EXPECT_LT(test::spectralFlatness(monoSlice(engine->rendered(), 0.2, 1.2)), 0.05);
}

/// rms over [t - 0.1, t + 0.1] s.
double levelAround(const AudioSystem& sys, double t_s) { return rms(monoSlice(sys.rendered(), t_s - 0.1, t_s + 0.1)); }

// The level follows the intensity as 1 - exp(-t / kRainFade_s) when the rain
// starts and exp(-t / kRainFade_s) when it stops, and falls silent. The
// rain loop is 2 s long, so windows 2 s apart hold the same samples and
// their rms ratio is the gain ratio.
TEST(RainSound, FadesInAndOutWithTheWeather) {
  auto sys = test::loopbackSystem();
  const double tau = AudioSystem::kRainFade_s;
  sys->setRain(1);
  test::runFor(*sys, 12);
  sys->setRain(0);
  test::runFor(*sys, 30);
  // Gain during the update that starts at t: level after it, 1 - exp(-(t + dt) / tau).
  auto gainIn = [&](double t) { return 1 - std::exp(-(t + kTestStep_s) / tau); };
  const double steady = levelAround(*sys, 11);  // 2 s multiple from 1 and 3
  for (double t : {1.0, 3.0}) {
    const double measured = levelAround(*sys, t) / steady, expected = gainIn(t) / gainIn(11);
    std::printf("rain fading in, %.0f s: level %.3f of the downpour (defined %.3f)\n", t, measured, expected);
    EXPECT_NEAR(measured, expected, 0.05) << t << " s";
  }
  // Stopped at 12 s: after t more seconds the level is (1 - exp(-12 / tau)) exp(-t / tau).
  for (double t : {1.0, 3.0}) {
    const double measured = levelAround(*sys, 12 + t) / steady;
    const double expected = gainIn(12 - kTestStep_s) * std::exp(-(t + kTestStep_s) / tau) / gainIn(11);
    std::printf("rain fading out, %.0f s after: level %.3f (defined %.3f)\n", t, measured, expected);
    EXPECT_NEAR(measured, expected, 0.05) << t << " s after";
  }
  EXPECT_EQ(rms(monoSlice(sys->rendered(), 12 + 20, 12 + 30)), 0.0) << "silent once faded below -80 dB";
  EXPECT_EQ(sys->rainLevel(), 0.0f);
}

// The effects volume scales the rain.
TEST(RainSound, FollowsTheEffectsVolume) {
  double level[2];
  for (int i = 0; i < 2; ++i) {
    auto sys = test::loopbackSystem();
    sys->setVolumes({1, i == 0 ? 1.0f : 0.25f, 1});
    sys->setRain(1);
    test::runFor(*sys, 8);
    level[i] = rms(monoSlice(sys->rendered(), 6, 8));
  }
  EXPECT_NEAR(level[1] / level[0], 0.25, 0.01);
}

}  // namespace
}  // namespace tumble::audio
