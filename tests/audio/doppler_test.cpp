// Doppler shift of a passing source, heard by a listener standing still or
// driving the other way (AudioSystem::setListener's velocity, setVelocity),
// against OpenAL's formula
//   f' = f (c - v_l) / (c - v_s),  c = 343.3 m/s,
// v_l and v_s the listener's and source's velocities along the line from the
// source to the listener. ListenerMotion: the listener's velocity from its
// movement.
#include <gtest/gtest.h>

#include <cmath>

#include "audio/listener_motion.h"
#include "loopback.h"
#include "signal.h"

namespace tumble::audio {
namespace {

using test::kTestStep_s;
using test::monoSlice;

constexpr double kToneHz = 400;

/// OpenAL's Doppler factor for a source and a listener at these positions and velocities.
double dopplerFactor(const Vec3& source, const Vec3& vSource, const Vec3& listener, const Vec3& vListener) {
  const Vec3 sl = (listener - source).normalized();
  const double c = AudioSystem::kOpenAlSpeedOfSound_mps;
  return (c - vListener.dot(sl)) / (c - vSource.dot(sl));
}

struct Pass {
  double measured, predicted;
};

/// A 400 Hz tone on a car driving +X at 30 m/s along z = -10 m, from x = -200
/// m; the listener drives along z = 0 at listenerSpeed (m/s, +X). Returns the
/// tone's frequency heard in [from_s, to_s) and OpenAL's prediction averaged
/// over the steps of that window.
Pass pass(double listenerSpeed_mps, double from_s, double to_s) {
  auto sys = test::loopbackSystem();
  std::vector<float> tone(kSampleRate_hz);  // 1 s, 400 whole cycles: loops cleanly
  for (std::size_t i = 0; i < tone.size(); ++i) tone[i] = 0.5f * float(std::sin(2 * M_PI * kToneHz * double(i) / kSampleRate_hz));
  const Vec3 vSource(30, 0, 0), vListener(Real(listenerSpeed_mps), 0, 0);
  const Vec3 start(-200, 0, -10);
  const SoundId id = *sys->play({.clip = sys->addClip(clipFromFloat(tone, kSampleRate_hz)), .position_m = start,
                                 .loop = true, .referenceDistance_m = 6});
  double sum = 0;
  int n = 0;
  test::runFor(*sys, to_s + 0.1, [&] {
    const double t = sys->time_s();
    const Vec3 s = start + vSource * Real(t), l = vListener * Real(t);
    sys->setPosition(id, s);
    sys->setVelocity(id, vSource);
    sys->setListener(l, Vec3(1, 0, 0), Vec3(0, 1, 0), vListener);
    if (t >= from_s && t < to_s) sum += dopplerFactor(s, vSource, l, vListener), ++n;
  });
  return {test::peakFrequency(monoSlice(sys->rendered(), from_s, to_s), 100, 1000), kToneHz * sum / n};
}

// Approaching (x from -170 to -140 m) and going away after the pass, for a
// listener standing still and one driving towards the car at 15 m/s
// (closing at 45 m/s). Tolerance 0.2 %: the FFT's peak, refined by a
// parabola, is good to about 0.03 % on a 0.5 s window; OpenAL Soft's
// pitch is a fixed-point step (1/16384 per sample), 0.006 %.
TEST(Doppler, PassingCarMatchesOpenAlsFormula) {
  struct Case {
    const char* name;
    double listener_mps, from_s, to_s;
  };
  const Case cases[] = {{"standing, approaching", 0, 1.0, 1.5},
                        {"standing, going away", 0, 11.5, 12.0},
                        {"driving towards it, approaching", -15, 0.5, 1.0},
                        {"driving towards it, going away", -15, 9.0, 9.5}};
  double heard[4];
  for (int i = 0; i < 4; ++i) {
    const Pass p = pass(cases[i].listener_mps, cases[i].from_s, cases[i].to_s);
    heard[i] = p.measured;
    std::printf("%-32s heard %.2f Hz, OpenAL's formula %.2f Hz (%+.3f %%)\n", cases[i].name, p.measured, p.predicted,
                100 * (p.measured - p.predicted) / p.predicted);
    EXPECT_NEAR(p.measured, p.predicted, 0.002 * p.predicted) << cases[i].name;
  }
  // The listener's own motion counts: driving towards the car raises the
  // approaching note and lowers the departing one further.
  EXPECT_GT(heard[2], heard[0] * 1.03);
  EXPECT_LT(heard[3], heard[1] * 0.97);
}

TEST(ListenerMotion, VelocityIsTheMovementOverTheTimeBetweenChanges) {
  ListenerMotion m;
  EXPECT_EQ(m.update(Vec3(0, 0, 0), 0.0), Vec3::Zero()) << "nothing known yet";
  const double dt = 1.0 / 60;
  EXPECT_TRUE(m.update(Vec3(0.25, 0, 0), dt).isApprox(Vec3(15, 0, 0), 1e-4f));
  // Two steps in one frame: the second sees the same position and keeps the velocity.
  EXPECT_TRUE(m.update(Vec3(0.25, 0, 0), 2 * dt).isApprox(Vec3(15, 0, 0), 1e-4f));
  // The next frame moved 2 steps' worth over the 2 steps since the last change.
  EXPECT_TRUE(m.update(Vec3(0.75, 0, 0), 3 * dt).isApprox(Vec3(15, 0, 0), 1e-4f));
  // A camera cut (100 m in one step, 6000 m/s) is not motion.
  EXPECT_EQ(m.update(Vec3(100.75, 0, 0), 4 * dt), Vec3::Zero());
  EXPECT_TRUE(m.update(Vec3(100.75, 0, -0.5), 5 * dt).isApprox(Vec3(0, 0, -30), 1e-4f));
  EXPECT_TRUE(m.update(Vec3(std::nan(""), 0, 0), 6 * dt).isApprox(Vec3(0, 0, -30), 1e-4f)) << "a NaN is ignored";
}

}  // namespace
}  // namespace tumble::audio
