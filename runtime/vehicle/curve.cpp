#include "vehicle/curve.h"

#include <cmath>

namespace tumble::vehicle {

Real Curve::eval(Real x) const {
  if (m_points.empty()) return 0;
  if (x <= m_points.front().first) return m_points.front().second;
  if (x >= m_points.back().first) return m_points.back().second;
  // Tables are short (a handful of points): a linear scan beats a search.
  for (std::size_t i = 1; i < m_points.size(); ++i) {
    const auto& [x1, y1] = m_points[i];
    if (x <= x1) {
      const auto& [x0, y0] = m_points[i - 1];
      return y0 + (y1 - y0) * (x - x0) / (x1 - x0);
    }
  }
  return m_points.back().second;
}

Real Curve::maxY() const {
  Real m = m_points.empty() ? 0 : m_points.front().second;
  for (const auto& p : m_points) m = std::max(m, p.second);
  return m;
}

Real Curve::argMax() const {
  Real best = m_points.empty() ? 0 : m_points.front().first, m = -1e30f;
  for (const auto& p : m_points)
    if (p.second > m) m = p.second, best = p.first;
  return best;
}

Real Curve::initialSlope() const {
  for (const auto& [x, y] : m_points)
    if (x > 0) return y / x;
  return 0;
}

Status Curve::validate(const std::string& what, Real yMin) const {
  if (m_points.size() < 2)
    return makeError(what + ": needs at least two points {x, y}, e.g. {{0, 0}, {0.1, 1.0}}");
  for (std::size_t i = 0; i < m_points.size(); ++i) {
    const auto& [x, y] = m_points[i];
    const std::string at = what + " point " + std::to_string(i + 1);
    if (!std::isfinite(x) || !std::isfinite(y)) return makeError(at + ": must be finite numbers");
    if (y < yMin) return makeError(at + ": y = " + std::to_string(y) + " is below " + std::to_string(yMin));
    if (i > 0 && !(x > m_points[i - 1].first))
      return makeError(at + ": x must be larger than the previous point's x (points sorted by x)");
  }
  return Ok{};
}

}  // namespace tumble::vehicle
