#include "numerics/elliptic.h"

#include <cmath>
#include <numbers>

#include "core/assert.h"

namespace tumble::numerics {

double arithmeticGeometricMean(double a, double b) {
  TUMBLE_ASSERT(a > 0.0 && b > 0.0, "arithmeticGeometricMean needs positive arguments.");
  // Quadratic convergence; 64 iterations is a guard, never reached.
  for (int i = 0; i < 64 && std::abs(a - b) > 1e-16 * a; ++i) {
    const double mean = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = mean;
  }
  return 0.5 * (a + b);
}

double completeEllipticK(double k) {
  TUMBLE_ASSERT(k >= 0.0 && k < 1.0, "completeEllipticK: modulus must be in [0, 1).");
  const double kPrime = std::sqrt((1.0 - k) * (1.0 + k));  // avoids cancellation in 1 - k^2
  return std::numbers::pi / (2.0 * arithmeticGeometricMean(1.0, kPrime));
}

double pendulumPeriod_s(double gOverL_per_s2, double amplitude_rad) {
  TUMBLE_ASSERT(gOverL_per_s2 > 0.0, "pendulumPeriod_s: g/L must be positive.");
  TUMBLE_ASSERT(amplitude_rad >= 0.0 && amplitude_rad < std::numbers::pi,
                "pendulumPeriod_s: amplitude must be in [0, pi) rad.");
  return 4.0 / std::sqrt(gOverL_per_s2) * completeEllipticK(std::sin(0.5 * amplitude_rad));
}

}  // namespace tumble::numerics
