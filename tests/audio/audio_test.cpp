// The audio system rendered offline (OpenAL Soft's loopback device), checked
// against what the sounds are defined to be: synth.h and audio_system.h.
#include <gtest/gtest.h>

#include "audio/audio_system.h"
#include "signal.h"

namespace tumble::audio {
namespace {

using test::monoSlice;
using test::rms;

constexpr double kStep_s = 1.0 / 60.0;

std::unique_ptr<AudioSystem> loopback() {
  auto sys = AudioSystem::create(AudioOutput::Loopback);
  EXPECT_TRUE(sys) << sys.error();
  return std::move(*sys);
}

/// A vehicle 2 m in front of the listener, standing still.
VehicleSoundInput car(float rpm, float load, int cylinders) {
  VehicleSoundInput in;
  in.position_m = Vec3(0, 0, -2);
  in.rpm = rpm;
  in.load = load;
  in.cylinders = cylinders;
  return in;
}

void run(AudioSystem& sys, double seconds, const VehicleSoundInput* vehicle = nullptr) {
  for (int i = 0; i < int(std::lround(seconds / kStep_s)); ++i) {
    if (vehicle) sys.updateVehicle(1, *vehicle);
    sys.update(kStep_s);
  }
}

// The firing frequency rpm / 60 * cylinders / 2 is the strongest line of
// the engine note, at every rpm and load, for 4 and 6 cylinders.
TEST(EngineSound, FundamentalIsTheFiringFrequency) {
  for (int cylinders : {4, 6}) {
    for (float rpm : {1000.0f, 2500.0f, 4000.0f, 6500.0f}) {
      for (float load : {0.0f, 1.0f}) {
        auto sys = loopback();
        const VehicleSoundInput in = car(rpm, load, cylinders);
        run(*sys, 1.3, &in);
        const double expected = rpm / 60.0 * cylinders / 2.0;
        const double f = test::peakFrequency(monoSlice(sys->rendered(), 0.2, 1.2), 15, 2000);
        std::printf("%d cylinders %5.0f rpm load %.0f: fundamental %7.2f Hz, defined %7.2f Hz (%+.2f %%)\n", cylinders,
                    rpm, load, f, expected, 100 * (f - expected) / expected);
        EXPECT_NEAR(f, expected, 0.02 * expected) << cylinders << " cylinders at " << rpm << " rpm, load " << load;
      }
    }
  }
}

// A vehicle's own engine sample plays at pitch rpm / sample_rpm: a 200 Hz
// tone recorded at 2000 rpm sounds at 300 Hz at 3000 rpm.
TEST(EngineSound, SamplePlaysAtRpmOverSampleRpm) {
  auto sys = loopback();
  std::vector<float> tone(kSampleRate_hz);  // 1 s, 200 whole cycles: loops cleanly
  for (std::size_t i = 0; i < tone.size(); ++i) tone[i] = 0.5f * float(std::sin(2 * M_PI * 200.0 * double(i) / kSampleRate_hz));
  VehicleSoundInput in = car(3000, 0.5f, 4);
  in.engineSample = sys->addClip(clipFromFloat(tone, kSampleRate_hz));
  in.sampleRpm = 2000;
  run(*sys, 1.2, &in);
  EXPECT_NEAR(test::peakFrequency(monoSlice(sys->rendered(), 0.2, 1.2), 15, 2000), 300, 3);
}

// Load makes the note louder and brighter (more power in upper harmonics).
TEST(EngineSound, LoadMakesItLouderAndBrighter) {
  double level[2], centroid[2];
  for (int i = 0; i < 2; ++i) {
    auto sys = loopback();
    const VehicleSoundInput in = car(3000, float(i), 4);
    run(*sys, 1.2, &in);
    const auto x = monoSlice(sys->rendered(), 0.2, 1.2);
    level[i] = rms(x);
    centroid[i] = test::spectralCentroid(x);
  }
  EXPECT_GT(level[1], 1.3 * level[0]);
  EXPECT_GT(centroid[1], 1.5 * centroid[0]);
}

// A gear change (clutch open) dips the engine's level.
TEST(EngineSound, GearChangeDips) {
  auto sys = loopback();
  VehicleSoundInput in = car(3000, 0.5f, 4);
  run(*sys, 0.5, &in);
  in.shifting = true;
  run(*sys, 0.25, &in);
  const double before = rms(monoSlice(sys->rendered(), 0.25, 0.5));
  const double during = rms(monoSlice(sys->rendered(), 0.6, 0.75));
  EXPECT_LT(during, 0.6 * before);
  EXPECT_GT(during, 0.3 * before);
}

/// Only the tyres: engine volume 0, standing still (no wind).
VehicleSoundInput sliding(float slip_mps, TyreSurface surface) {
  VehicleSoundInput in = car(0, 0, 4);
  in.volume = 0;
  in.tyreSlipThreshold_mps = 1.5f;
  for (int w = 0; w < 4; ++w) in.wheels.push_back({true, slip_mps, surface});
  return in;
}

TEST(TyreSound, SilentBelowTheSlipThresholdAndGrowingAbove) {
  for (int s = 0; s < kTyreSurfaceCount; ++s) {
    double level[3];
    const float slips[3] = {1.4f, 3.0f, 6.0f};  // threshold 1.5 m/s
    for (int i = 0; i < 3; ++i) {
      auto sys = loopback();
      const VehicleSoundInput in = sliding(slips[i], TyreSurface(s));
      run(*sys, 0.6, &in);
      level[i] = rms(monoSlice(sys->rendered(), 0.1, 0.6));
    }
    SCOPED_TRACE(tyreSurfaceName(TyreSurface(s)));
    EXPECT_LT(level[0], 1e-6);
    EXPECT_GT(level[1], 0.02);
    EXPECT_GT(level[2], 1.5 * level[1]);
  }
}

// Wind grows with the dynamic pressure, the square of the speed through
// the air, up to full level at 40 m/s; a car at rest hears none.
TEST(WindSound, GrowsWithTheSquareOfTheSpeed) {
  auto level = [](float speed_mps) {
    auto sys = loopback();
    VehicleSoundInput in = car(0, 0, 4);
    in.volume = 0;  // no engine note
    in.speed_mps = speed_mps;
    run(*sys, 1.0, &in);
    return rms(monoSlice(sys->rendered(), 0.2, 1.0));
  };
  const double still = level(0), slow = level(10), twice = level(20), full = level(40), beyond = level(60);
  EXPECT_LT(still, 1e-6);
  EXPECT_GT(slow, 1e-4);
  // x2 speed -> x4 level, give or take the pitch rising with speed (the
  // loop's band moves up by 0.8 + v / 80).
  EXPECT_NEAR(twice / slow, 4.0, 1.0);
  EXPECT_NEAR(full / twice, 4.0, 1.0);
  EXPECT_NEAR(beyond / full, 1.0, 0.25) << "full level from 40 m/s on";
}

// Each surface sounds different: every pair differs by at least 30 % in
// spectral centroid or by a factor 2 in spectral flatness (tonal squeal vs
// noise).
TEST(TyreSound, SpectrumDiffersBySurface) {
  double centroid[kTyreSurfaceCount], flatness[kTyreSurfaceCount];
  for (int s = 0; s < kTyreSurfaceCount; ++s) {
    auto sys = loopback();
    const VehicleSoundInput in = sliding(6, TyreSurface(s));
    run(*sys, 1.2, &in);
    const auto x = monoSlice(sys->rendered(), 0.1, 1.1);
    centroid[s] = test::spectralCentroid(x);
    flatness[s] = test::spectralFlatness(x);
    std::printf("%-8s centroid %7.0f Hz  flatness %.4f\n", tyreSurfaceName(TyreSurface(s)), centroid[s], flatness[s]);
  }
  for (int a = 0; a < kTyreSurfaceCount; ++a) {
    for (int b = a + 1; b < kTyreSurfaceCount; ++b) {
      const double dc = std::max(centroid[a], centroid[b]) / std::min(centroid[a], centroid[b]);
      const double df = std::max(flatness[a], flatness[b]) / std::min(flatness[a], flatness[b]);
      EXPECT_TRUE(dc > 1.3 || df > 2) << tyreSurfaceName(TyreSurface(a)) << " vs " << tyreSurfaceName(TyreSurface(b));
    }
  }
  // The squeal is the tonal one; mud the lowest, grass the highest.
  EXPECT_LT(flatness[int(TyreSurface::Asphalt)], 0.5 * flatness[int(TyreSurface::Gravel)]);
  EXPECT_LT(centroid[int(TyreSurface::Mud)], centroid[int(TyreSurface::Asphalt)]);
  EXPECT_GT(centroid[int(TyreSurface::Grass)], centroid[int(TyreSurface::Gravel)]);
}

// The impact's amplitude is proportional to the impulse up to
// kImpactFull_Ns (gain = impulse / kImpactFull_Ns), and nothing below kImpactMin_Ns.
TEST(ImpactSound, LoudnessGrowsWithImpulse) {
  const float impulses[] = {2, 100, 300, 1000, 3000, 9000};
  double level[6];
  for (int i = 0; i < 6; ++i) {
    auto sys = loopback();
    sys->impact(Vec3(0, 0, -2), impulses[i]);
    run(*sys, 0.5);
    level[i] = rms(monoSlice(sys->rendered(), 0, 0.5));
  }
  for (int i = 0; i < 6; ++i) std::printf("impulse %5.0f N s: rms %.5f\n", impulses[i], level[i]);
  EXPECT_LT(level[0], 1e-6);  // below kImpactMin_Ns
  for (int i = 2; i <= 4; ++i) {
    EXPECT_GT(level[i], level[i - 1]);
    EXPECT_NEAR(level[i] / level[1], impulses[i] / impulses[1], 0.03 * impulses[i] / impulses[1]);
  }
  EXPECT_NEAR(level[5], level[4], 0.01 * level[4]);  // full loudness from kImpactFull_Ns on
}

/// First time (s) the render's magnitude exceeds `threshold`.
double onset(const std::vector<float>& stereo, float threshold) {
  for (std::size_t i = 0; i < stereo.size(); ++i)
    if (std::fabs(stereo[i]) > threshold) return double(i / 2) / kSampleRate_hz;
  return -1;
}

// Thunder is heard distance / 343 m/s after the flash, to within a millisecond.
TEST(Thunder, ArrivesAfterDistanceOverSpeedOfSound) {
  for (double distance_m : {343.0, 1000.0, 1715.0}) {
    auto sys = loopback();
    run(*sys, 0.25);  // the flash comes a quarter second in
    const double flash_s = sys->time_s();
    const double delay = sys->thunder(Vec3(0.6 * distance_m, 0, -0.8 * distance_m));
    EXPECT_NEAR(delay, distance_m / 343.0, 1e-9);
    run(*sys, delay + 0.5);
    const double heard = onset(sys->rendered(), 1e-4f);
    std::printf("%6.0f m: heard %.4f s after the flash (distance / 343 m/s = %.4f s)\n", distance_m, heard - flash_s,
                distance_m / 343.0);
    EXPECT_NEAR(heard, flash_s + distance_m / 343.0, 0.001) << distance_m << " m";
  }
}

// The listener's position matters: a source to the right is louder in the right channel.
TEST(Positional, SourceToTheRightIsLouderOnTheRight) {
  auto sys = loopback();
  sys->setListener(Vec3::Zero(), Vec3(0, 0, -1), Vec3(0, 1, 0), Vec3::Zero());
  sys->impact(Vec3(3, 0, 0), 3000);
  run(*sys, 0.3);
  double left = 0, right = 0;
  for (std::size_t i = 0; i + 1 < sys->rendered().size(); i += 2) {
    left += std::pow(sys->rendered()[i], 2);
    right += std::pow(sys->rendered()[i + 1], 2);
  }
  EXPECT_GT(right, 4 * left);
}

TEST(Volumes, MasterAndEffectsScaleTheMix) {
  double level[3];
  const AudioVolumes volumes[3] = {{1, 1, 1}, {0.5f, 1, 1}, {0.5f, 0.5f, 1}};
  for (int i = 0; i < 3; ++i) {
    auto sys = loopback();
    sys->setVolumes(volumes[i]);
    sys->impact(Vec3(0, 0, -2), 1000);
    run(*sys, 0.4);
    level[i] = rms(sys->rendered());
  }
  EXPECT_NEAR(level[1] / level[0], 0.5, 0.01);
  EXPECT_NEAR(level[2] / level[0], 0.25, 0.01);
}

// Without a device nothing is mixed, but sounds are tracked in time and capped.
TEST(SilentOutput, TracksSoundsAndCapsThem) {
  auto sys = AudioSystem::create(AudioOutput::Silent);
  ASSERT_TRUE(sys) << sys.error();
  AudioSystem& a = **sys;
  Clip clip = clipFromFloat(std::vector<float>(kSampleRate_hz / 2, 0.1f), kSampleRate_hz);  // 0.5 s
  const ClipId c = a.addClip(clip);
  auto once = a.play({.clip = c, .pitch = 2});  // lasts 0.25 s
  ASSERT_TRUE(once);
  EXPECT_TRUE(a.isPlaying(*once));
  run(a, 0.3);
  EXPECT_FALSE(a.isPlaying(*once));
  for (int i = 0; i < AudioSystem::kMaxSounds; ++i) ASSERT_TRUE(a.play({.clip = c, .loop = true}));
  auto over = a.play({.clip = c});
  ASSERT_FALSE(over);
  EXPECT_NE(over.error().find("limit"), std::string::npos);
  EXPECT_TRUE(a.rendered().empty());
  EXPECT_FALSE(a.play({.clip = c, .pitch = std::nanf("")}));
}

}  // namespace
}  // namespace tumble::audio
