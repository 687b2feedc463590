#pragma once
// Wall clock and process memory for run reports.
#include <chrono>

namespace tumble {

/// Peak resident set size of this process so far, in MiB.
double peakRssMb();

class Stopwatch {
 public:
  Stopwatch() : m_start(std::chrono::steady_clock::now()) {}
  void reset() { m_start = std::chrono::steady_clock::now(); }
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  }

 private:
  std::chrono::steady_clock::time_point m_start;
};

}  // namespace tumble
