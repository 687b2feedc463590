#pragma once
// Short aliases for the Eigen types the engine uses (ARCHITECTURE.md).
// Rigid-body state is float by default; configure with -DTUMBLE_DOUBLE=ON for
// double. Generic ODE systems and the numerics lab always use double.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace tumble {

#if defined(TUMBLE_DOUBLE)
using Real = double;
#else
using Real = float;
#endif

using Vec2 = Eigen::Matrix<Real, 2, 1>;
using Vec3 = Eigen::Matrix<Real, 3, 1>;
using Vec4 = Eigen::Matrix<Real, 4, 1>;
using Mat3 = Eigen::Matrix<Real, 3, 3>;
using Quat = Eigen::Quaternion<Real>;

constexpr Real kPi = Real(3.14159265358979323846);

/// Standard gravity, m/s^2, pointing down -Y (Y is up).
constexpr Real kStandardGravity = Real(9.81);

inline bool isFinite(const Vec3& v) { return v.allFinite(); }
inline bool isFinite(const Quat& q) { return q.coeffs().allFinite(); }

/// Skew-symmetric cross-product matrix: skew(a) * b == a.cross(b).
inline Mat3 skew(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

}  // namespace tumble
