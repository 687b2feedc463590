#pragma once
// Signal features of offline renders (interleaved stereo at kSampleRate_hz),
// for the audio tests.
#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "audio/synth.h"

namespace tumble::audio::test {

/// Left + right, frames [from_s, to_s).
inline std::vector<float> monoSlice(const std::vector<float>& stereo, double from_s, double to_s) {
  const auto a = std::size_t(from_s * kSampleRate_hz), b = std::min(stereo.size() / 2, std::size_t(to_s * kSampleRate_hz));
  std::vector<float> m;
  for (std::size_t i = a; i < b; ++i) m.push_back(0.5f * (stereo[2 * i] + stereo[2 * i + 1]));
  return m;
}

inline double rms(const std::vector<float>& x) {
  double s = 0;
  for (float v : x) s += double(v) * v;
  return x.empty() ? 0 : std::sqrt(s / double(x.size()));
}

/// Power spectrum of a Hann-windowed signal; bin k is k * rate / n Hz.
inline std::vector<double> powerSpectrum(const std::vector<float>& x) {
  const std::size_t n = x.size();
  std::vector<float> w(n);
  for (std::size_t i = 0; i < n; ++i) w[i] = x[i] * float(0.5 - 0.5 * std::cos(2 * M_PI * double(i) / double(n)));
  Eigen::FFT<float> fft;
  std::vector<std::complex<float>> spec;
  fft.fwd(spec, w);
  std::vector<double> p(n / 2);
  for (std::size_t k = 0; k < p.size(); ++k) p[k] = std::norm(spec[k]);
  return p;
}

/// Frequency of the strongest line between lo and hi Hz, refined by a
/// parabola through the peak bin and its neighbours.
inline double peakFrequency(const std::vector<float>& x, double lo_hz, double hi_hz) {
  const auto p = powerSpectrum(x);
  const double binHz = double(kSampleRate_hz) / double(x.size());
  std::size_t best = std::size_t(lo_hz / binHz);
  for (std::size_t k = best; k < p.size() && k * binHz <= hi_hz; ++k)
    if (p[k] > p[best]) best = k;
  const double a = std::log(p[best - 1] + 1e-30), b = std::log(p[best] + 1e-30), c = std::log(p[best + 1] + 1e-30);
  const double offset = 0.5 * (a - c) / (a - 2 * b + c);
  return (double(best) + offset) * binHz;
}

/// Power-weighted mean frequency, Hz.
inline double spectralCentroid(const std::vector<float>& x) {
  const auto p = powerSpectrum(x);
  const double binHz = double(kSampleRate_hz) / double(x.size());
  double num = 0, den = 0;
  for (std::size_t k = 1; k < p.size(); ++k) {
    num += p[k] * double(k) * binHz;
    den += p[k];
  }
  return den > 0 ? num / den : 0;
}

/// Geometric over arithmetic mean of the power between 50 Hz and 12 kHz:
/// near 1 for white noise, near 0 for a few tones.
inline double spectralFlatness(const std::vector<float>& x) {
  const auto p = powerSpectrum(x);
  const double binHz = double(kSampleRate_hz) / double(x.size());
  double logSum = 0, sum = 0;
  int n = 0;
  for (std::size_t k = std::size_t(50 / binHz); k < p.size() && k * binHz < 12000; ++k, ++n) {
    logSum += std::log(p[k] + 1e-30);
    sum += p[k];
  }
  return n > 0 && sum > 0 ? std::exp(logSum / n) / (sum / n) : 0;
}

}  // namespace tumble::audio::test

namespace tumble::audio::test {

/// Fraction of the power between lo and hi Hz.
inline double bandPowerFraction(const std::vector<float>& x, double lo_hz, double hi_hz) {
  const auto p = powerSpectrum(x);
  const double binHz = double(kSampleRate_hz) / double(x.size());
  double in = 0, all = 0;
  for (std::size_t k = 1; k < p.size(); ++k) {
    all += p[k];
    if (k * binHz >= lo_hz && k * binHz < hi_hz) in += p[k];
  }
  return all > 0 ? in / all : 0;
}

/// Seconds from the loudest 5 ms window until the level (rms over 5 ms
/// windows) stays below the peak's minus `drop_dB`; -1 if it never does.
inline double decayTime(const std::vector<float>& x, double drop_dB) {
  const std::size_t w = kSampleRate_hz / 200;
  std::vector<double> level;
  for (std::size_t i = 0; i + w <= x.size(); i += w) {
    double s = 0;
    for (std::size_t j = i; j < i + w; ++j) s += double(x[j]) * x[j];
    level.push_back(std::sqrt(s / double(w)));
  }
  if (level.empty()) return -1;
  const std::size_t peak = std::size_t(std::max_element(level.begin(), level.end()) - level.begin());
  const double limit = level[peak] * std::pow(10.0, -drop_dB / 20.0);
  std::size_t last = peak;
  for (std::size_t i = peak; i < level.size(); ++i)
    if (level[i] >= limit) last = i;
  if (last + 1 >= level.size()) return -1;
  return double(last + 1 - peak) * double(w) / kSampleRate_hz;
}

}  // namespace tumble::audio::test
