#pragma once
// Complete elliptic integral of the first kind and the exact period of a
// large-amplitude pendulum.
//
// Pendulum theta'' = -(g/L) sin(theta), released at rest from theta0.
// Energy: theta'^2/2 = (g/L)(cos theta - cos theta0). Substituting
// sin(theta/2) = k sin(phi), k = sin(theta0/2), the quarter period becomes
//   T/4 = sqrt(L/g) * integral_0^{pi/2} dphi / sqrt(1 - k^2 sin^2 phi)
//       = sqrt(L/g) * K(k),
// so T = 4 sqrt(L/g) K(k); T -> 2 pi sqrt(L/g) as theta0 -> 0 (K(0) = pi/2).
//
// K by the arithmetic-geometric mean (Gauss): K(k) = pi / (2 AGM(1, k')),
// k' = sqrt(1 - k^2). AGM converges quadratically: ~5 iterations for double
// precision unless k is within ~1e-6 of 1, never more than ~10.
namespace tumble::numerics {

/// AGM(a, b) for a, b > 0.
double arithmeticGeometricMean(double a, double b);

/// K(k) for the modulus 0 <= k < 1 (note: modulus k, not the parameter m = k^2).
double completeEllipticK(double k);

/// Exact period (s) of a pendulum with g/L in 1/s^2 released at rest from
/// amplitude 0 <= theta0 < pi (rad).
double pendulumPeriod_s(double gOverL_per_s2, double amplitude_rad);

}  // namespace tumble::numerics
