#include "numerics/ode.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::numerics {

void SecondOrderSystem::derivative(double t, const Eigen::VectorXd& y, Eigen::VectorXd& dy) const {
  const int n = dofs();
  dy.head(n) = y.tail(n);
  acceleration(t, y.head(n), y.tail(n), dy.tail(n));
}

bool SecondOrderSystem::analyticJacobian(double t, const Eigen::VectorXd& y,
                                         Eigen::MatrixXd& J) const {
  const int n = dofs();
  Eigen::MatrixXd dadq(n, n);
  Eigen::MatrixXd dadv(n, n);
  if (!accelerationJacobian(t, y.head(n), y.tail(n), dadq, dadv)) return false;
  J.setZero();
  J.topRightCorner(n, n).setIdentity();
  J.bottomLeftCorner(n, n) = dadq;
  J.bottomRightCorner(n, n) = dadv;
  return true;
}

void finiteDifferenceJacobian(const OdeSystem& system, double t, const Eigen::VectorXd& y,
                              Eigen::MatrixXd& J) {
  const int n = system.dimension();
  J.resize(n, n);
  Eigen::VectorXd f0(n);
  Eigen::VectorXd f1(n);
  Eigen::VectorXd yh = y;
  system.derivative(t, y, f0);
  const double sqrtEps = std::sqrt(std::numeric_limits<double>::epsilon());
  for (int j = 0; j < n; ++j) {
    const double h = sqrtEps * std::max(std::abs(y[j]), 1.0);
    yh[j] = y[j] + h;
    // (y + h) - y is the step actually represented in floating point.
    const double hExact = yh[j] - y[j];
    system.derivative(t, yh, f1);
    J.col(j) = (f1 - f0) / hExact;
    yh[j] = y[j];
  }
}

void jacobian(const OdeSystem& system, double t, const Eigen::VectorXd& y, Eigen::MatrixXd& J) {
  const int n = system.dimension();
  J.resize(n, n);
  if (!system.analyticJacobian(t, y, J)) finiteDifferenceJacobian(system, t, y, J);
}

}  // namespace tumble::numerics
