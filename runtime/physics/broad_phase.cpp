#include "physics/internal/broad_phase.h"

namespace tumble::physics {

void BroadPhase::chooseAxis(const std::vector<Aabb>& boxes) {
  // Axis with the largest variance of box centres: fewest false overlaps.
  Eigen::Matrix<double, 3, 1> sum = Eigen::Matrix<double, 3, 1>::Zero(), sum2 = sum;
  for (std::uint32_t i : m_order) {
    Eigen::Matrix<double, 3, 1> c = ((boxes[i].lo + boxes[i].hi) / 2).cast<double>();
    sum += c;
    sum2 += c.cwiseProduct(c);
  }
  double n = double(m_order.size());
  Eigen::Matrix<double, 3, 1> var = sum2 / n - (sum / n).cwiseProduct(sum / n);
  int axis = 0;
  var.maxCoeff(&axis);
  m_axis = axis;
}

}  // namespace tumble::physics
