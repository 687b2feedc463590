#include "audio/synth.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/random.h"

namespace tumble::audio {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRate = kSampleRate_hz;

/// Uniform in [-1, 1) from a splitmix64 stream.
struct Noise {
  std::uint64_t state;
  double next() { return double(splitmix64(state) >> 11) * (2.0 / 9007199254740992.0) - 1.0; }
  double unit() { return 0.5 * (next() + 1.0); }
};

/// One-pole low-pass, cut-off fc (Hz).
struct LowPass {
  double a, y = 0;
  explicit LowPass(double fc_hz) : a(1.0 - std::exp(-2.0 * kPi * fc_hz / kRate)) {}
  double operator()(double x) { return y += a * (x - y); }
};

/// Band-pass biquad (constant 0 dB peak gain; R. Bristow-Johnson's cookbook).
struct BandPass {
  double b0, b2, a1, a2, x1 = 0, x2 = 0, y1 = 0, y2 = 0;
  BandPass(double fc_hz, double q) {
    const double w = 2.0 * kPi * fc_hz / kRate, alpha = std::sin(w) / (2.0 * q), a0 = 1.0 + alpha;
    b0 = alpha / a0;
    b2 = -alpha / a0;
    a1 = -2.0 * std::cos(w) / a0;
    a2 = (1.0 - alpha) / a0;
  }
  double operator()(double x) {
    const double y = b0 * x + b2 * x2 - a1 * y1 - a2 * y2;
    x2 = x1;
    x1 = x;
    y2 = y1;
    y1 = y;
    return y;
  }
};

void normalise(std::vector<float>& v, float peak = 0.9f) {
  float m = 0;
  for (float x : v) m = std::max(m, std::fabs(x));
  if (m > 0)
    for (float& x : v) x *= peak / m;
}

/// A loop of `length` samples from a generator run for length + fade
/// samples: the tail is cross-faded into the head, so the loop joins smoothly.
template <typename Gen>
std::vector<float> seamlessLoop(std::size_t length, Gen&& gen) {
  const std::size_t fade = length / 8;
  std::vector<float> raw(length + fade);
  for (float& x : raw) x = float(gen());
  std::vector<float> out(raw.begin(), raw.begin() + std::ptrdiff_t(length));
  for (std::size_t i = 0; i < fade; ++i) {
    const float w = float(i) / float(fade);
    out[i] = raw[i] * w + raw[length + i] * (1 - w);
  }
  normalise(out);
  return out;
}

}  // namespace

const char* tyreSurfaceName(TyreSurface s) {
  switch (s) {
    case TyreSurface::Asphalt: return "asphalt";
    case TyreSurface::Gravel: return "gravel";
    case TyreSurface::Grass: return "grass";
    case TyreSurface::Mud: return "mud";
  }
  return "?";
}

std::vector<float> engineLoop(bool bright) {
  // 25 whole cycles (0.5 s): exactly periodic, so the loop needs no fade.
  const int perCycle = int(kRate / kEngineLoopBase_hz), cycles = 25;
  std::vector<float> out(std::size_t(perCycle * cycles));
  Noise noise{bright ? 0xE2u : 0xE1u};
  std::vector<double> cycleGain(cycles);
  for (double& g : cycleGain) g = 1.0 + 0.08 * noise.next();  // cycle-to-cycle combustion variation
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double phase = 2.0 * kPi * kEngineLoopBase_hz * double(i) / kRate;
    const int cycle = int(i) / perCycle;
    double s = 0;
    if (!bright) {
      for (int k = 1; k <= 6; ++k) s += std::sin(k * phase + 0.3 * k) / k;
    } else {
      for (int k = 2; k <= 20; ++k) s += 0.6 * std::sin(k * phase + 0.7 * k) / std::pow(double(k), 0.6);
      // a burst of combustion noise at the start of each firing cycle
      const double inCycle = double(int(i) % perCycle) / perCycle;
      s += 0.8 * noise.next() * std::exp(-inCycle * 12.0);
    }
    out[i] = float(s * cycleGain[std::size_t(cycle)]);
  }
  normalise(out);
  return out;
}

std::vector<float> tyreLoop(TyreSurface surface) {
  const std::size_t length = std::size_t(kRate);  // 1 s
  Noise noise{0x7E0u + std::uint64_t(surface)};
  std::size_t i = 0;
  switch (surface) {
    case TyreSurface::Asphalt: {
      BandPass hiss(1400, 2);
      return seamlessLoop(length, [&] {
        const double t = double(i++) / kRate;
        // 1.1 kHz with a 6 Hz vibrato of +-3 %: f(t) = 1100 (1 + 0.03 sin(2 pi 6 t))
        const double phase = 2 * kPi * 1100.0 * t - 1100.0 * 0.03 / 6.0 * std::cos(2 * kPi * 6.0 * t);
        return std::sin(phase) + 0.35 * std::sin(2 * phase + 0.5) + 0.15 * std::sin(3 * phase + 1) +
               0.6 * hiss(noise.next());
      });
    }
    case TyreSurface::Gravel: {
      BandPass band(2500, 1.2);
      double env = 0;
      return seamlessLoop(length, [&] {
        if (noise.unit() < 400.0 / kRate) env = 0.4 + 0.6 * noise.unit();  // ~400 stones a second
        env *= std::exp(-1.0 / (0.004 * kRate));                            // each a 4 ms click
        return band(noise.next() * env) + 0.05 * noise.next();
      });
    }
    case TyreSurface::Grass: {
      LowPass lp(4000);
      return seamlessLoop(length, [&] {
        const double t = double(i++) / kRate;
        const double x = noise.next();
        return (x - lp(x)) * (0.7 + 0.3 * std::sin(2 * kPi * 3.0 * t));
      });
    }
    case TyreSurface::Mud: {
      LowPass lp1(250), lp2(250);
      return seamlessLoop(length, [&] {
        const double t = double(i++) / kRate;
        const double bubble = std::sin(2 * kPi * (120.0 + 60.0 * std::sin(2 * kPi * 2.0 * t)) * t);
        return lp2(lp1(noise.next())) * 8.0 + 0.3 * bubble * (0.5 + 0.5 * std::sin(2 * kPi * 4.0 * t));
      });
    }
  }
  return {};
}

std::vector<float> windLoop() {
  Noise noise{0x3D1u};
  BandPass band(500, 0.7);
  std::size_t i = 0;
  return seamlessLoop(std::size_t(2 * kRate), [&] {
    const double t = double(i++) / kRate;
    const double gust = 0.7 + 0.3 * std::sin(2 * kPi * 0.4 * t) * std::sin(2 * kPi * 0.13 * t + 1);
    return band(noise.next()) * gust;
  });
}

std::vector<float> impactClip() {
  Noise noise{0x1A9u};
  LowPass lp(2000);
  std::vector<float> out(std::size_t(0.4 * kRate));
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double t = double(i) / kRate;
    const double attack = std::min(1.0, t / 0.001);  // 1 ms rise: no click
    out[i] = float(attack * (std::sin(2 * kPi * 70.0 * t) * std::exp(-t / 0.06) +
                             0.8 * lp(noise.next()) * 4.0 * std::exp(-t / 0.03)));
  }
  normalise(out);
  return out;
}

std::vector<float> thunderClip() {
  Noise noise{0x7D0u};
  LowPass crackLp(1000), rumble1(150), rumble2(150), swell(0.7);
  std::vector<float> out(std::size_t(5.5 * kRate));
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double t = double(i) / kRate;
    const double x = noise.next();
    const double crack = (x - crackLp(x)) * std::exp(-t / 0.15);
    const double swells = 0.6 + 3.0 * std::fabs(swell(noise.next()));
    const double rumble = rumble2(rumble1(x)) * 12.0 * swells * std::min(1.0, t / 0.3) * std::exp(-t / 1.8);
    out[i] = float(std::min(1.0, t / 0.0005) * (crack + rumble));
  }
  normalise(out);
  return out;
}

}  // namespace tumble::audio
