#include "audio/synth.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <utility>

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
        const double click = noise.next();  // drawn first: the operands of + are unsequenced
        return band(click * env) + 0.05 * noise.next();
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

namespace {

/// A struck resonator: a mode at f_hz with amplitude a and decay time tau_s
/// (the amplitude falls by e every tau_s).
struct Mode {
  double f_hz, a, tau_s;
};

double modes(const std::initializer_list<Mode>& ms, double t) {
  double s = 0;
  for (const Mode& m : ms) s += m.a * std::sin(2 * kPi * m.f_hz * t) * std::exp(-t / m.tau_s);
  return s;
}

/// One material's hit, peak 1, `length` samples. The character of each:
/// metal rings (inharmonic modes 0.5..5.6 kHz decaying over 0.1..0.45 s),
/// wood knocks (modes 190..1350 Hz, gone in 35 ms), rubber bumps (85 Hz and
/// noise below 300 Hz, 40 ms), rock clicks (noise above 1.5 kHz and modes
/// at 1.8..4.7 kHz, 6..12 ms), gravel crunches (a dozen 3 ms clicks near
/// 2.5 kHz over 0.12 s on a low knock), soil thumps (60 Hz and noise below
/// 400 Hz, 50 ms), mud splats (noise below 250 Hz over 90 ms, a 600 Hz slap).
std::vector<double> materialHit(ImpactMaterial m, std::size_t length) {
  Noise noise{0x1A9u + std::uint64_t(m)};
  std::vector<double> out(length);
  LowPass lp1(2000), lp2(300), lp3(300), hp(1500), lp4(400), lp5(250), lp6(250);
  BandPass band(2500, 1.5), slap(600, 1.2), knock(1000, 1.5);
  // Gravel: click times (s) and gains, drawn once.
  std::vector<std::pair<double, double>> clicks;
  if (m == ImpactMaterial::Gravel)
    for (int i = 0; i < 12; ++i) clicks.push_back({0.12 * noise.unit() * noise.unit(), 0.3 + 0.7 * noise.unit()});
  for (std::size_t i = 0; i < length; ++i) {
    const double t = double(i) / kRate, x = noise.next();
    double s = 0;
    switch (m) {
      case ImpactMaterial::Thud:
        s = std::sin(2 * kPi * 70.0 * t) * std::exp(-t / 0.06) + 3.2 * lp1(x) * std::exp(-t / 0.03);
        break;
      case ImpactMaterial::Metal:
        s = modes({{523, 1, 0.45}, {1247, 0.8, 0.35}, {2351, 0.6, 0.25}, {3797, 0.45, 0.18}, {5560, 0.3, 0.12}}, t) +
            0.5 * x * std::exp(-t / 0.002);
        break;
      case ImpactMaterial::Wood:
        s = modes({{190, 1, 0.035}, {420, 0.7, 0.025}, {780, 0.5, 0.018}, {1350, 0.3, 0.012}}, t) +
            1.5 * knock(x) * std::exp(-t / 0.006);
        break;
      case ImpactMaterial::Rubber:
        s = std::sin(2 * kPi * 85.0 * t) * std::exp(-t / 0.04) + 6.0 * lp3(lp2(x)) * std::exp(-t / 0.025);
        break;
      case ImpactMaterial::Rock:
        s = 1.2 * (x - hp(x)) * std::exp(-t / 0.006) +
            modes({{1800, 0.6, 0.012}, {3100, 0.5, 0.01}, {4700, 0.4, 0.008}}, t);
        break;
      case ImpactMaterial::Gravel: {
        double c = 0;
        for (auto [at_s, g] : clicks)
          if (t >= at_s) c += g * std::exp(-(t - at_s) / 0.003);
        s = 3.0 * band(x * c) + 0.3 * std::sin(2 * kPi * 90.0 * t) * std::exp(-t / 0.03);
        break;
      }
      case ImpactMaterial::Soil:
        s = std::sin(2 * kPi * 60.0 * t) * std::exp(-t / 0.05) + 4.0 * lp4(x) * std::exp(-t / 0.04);
        break;
      case ImpactMaterial::Mud:
        s = 8.0 * lp6(lp5(x)) * std::exp(-t / 0.09) + 0.8 * slap(x) * std::exp(-t / 0.02);
        break;
    }
    out[i] = std::min(1.0, t / 0.001) * s;  // 1 ms rise: no click
  }
  double peak = 0;
  for (double v : out) peak = std::max(peak, std::fabs(v));
  if (peak > 0)
    for (double& v : out) v /= peak;
  return out;
}

/// Seconds a material's hit lasts in its buffer (long enough for its slowest mode to fall 60 dB or more).
double hitSeconds(ImpactMaterial m) { return m == ImpactMaterial::Metal ? 3.2 : 0.45; }

}  // namespace

const char* impactMaterialName(ImpactMaterial m) {
  static const char* const names[kImpactMaterialCount] = {"thud", "metal", "wood", "rubber", "rock", "gravel", "soil", "mud"};
  const int i = int(m);
  return i >= 0 && i < kImpactMaterialCount ? names[i] : "?";
}

std::optional<ImpactMaterial> parseImpactMaterial(std::string_view name) {
  for (int i = 0; i < kImpactMaterialCount; ++i)
    if (name == impactMaterialName(ImpactMaterial(i))) return ImpactMaterial(i);
  return std::nullopt;
}

std::vector<float> impactClip(ImpactMaterial a, ImpactMaterial b) {
  const std::size_t length = std::size_t(std::max(hitSeconds(a), hitSeconds(b)) * kRate);
  const std::vector<double> ha = materialHit(a, length);
  const std::vector<double> hb = a == b ? std::vector<double>(length, 0.0) : materialHit(b, length);
  std::vector<float> out(length);
  for (std::size_t i = 0; i < length; ++i) out[i] = float(ha[i] + hb[i]);
  normalise(out);
  return out;
}

std::vector<float> rainLoop() {
  Noise noise{0x4A1u};
  LowPass lowCut(500), highCut1(5000), highCut2(5000);
  // Drops: a ping each, at a random pitch 1.5..6 kHz, 3 ms long.
  double dropPhase = 0, dropStep = 0, dropEnv = 0;
  return seamlessLoop(std::size_t(2 * kRate), [&] {
    if (noise.unit() < 300.0 / kRate) {
      dropStep = 2 * kPi * (1500.0 + 4500.0 * noise.unit()) / kRate;
      dropEnv = 0.3 + 0.7 * noise.unit();
    }
    dropEnv *= std::exp(-1.0 / (0.003 * kRate));
    dropPhase += dropStep;
    const double x = noise.next();
    return highCut2(highCut1(x - lowCut(x))) + 0.5 * dropEnv * std::sin(dropPhase);
  });
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
