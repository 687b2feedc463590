#pragma once
// Curve: a piecewise-linear table y(x) (torque against rpm, tyre friction
// against slip). Points sorted by x; outside the table the end values hold.
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"
#include "core/result.h"

namespace tumble::vehicle {

class Curve {
 public:
  Curve() = default;
  explicit Curve(std::vector<std::pair<Real, Real>> points) : m_points(std::move(points)) {}

  /// y at x, linear between points, the end value outside them; 0 when empty.
  Real eval(Real x) const;
  /// Largest y and the first x where it is reached.
  Real maxY() const;
  Real argMax() const;
  /// y/x near 0 (the slope from the origin to the first point beyond it).
  Real initialSlope() const;
  const std::vector<std::pair<Real, Real>>& points() const { return m_points; }
  bool empty() const { return m_points.empty(); }

  /// At least two points, finite, x strictly increasing, y >= yMin. The
  /// message names `what` (the field) and the point.
  Status validate(const std::string& what, Real yMin) const;

 private:
  std::vector<std::pair<Real, Real>> m_points;
};

}  // namespace tumble::vehicle
