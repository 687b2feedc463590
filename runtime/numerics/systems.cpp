#include "numerics/systems.h"

#include <cmath>
#include <numbers>

#include "core/assert.h"

namespace tumble::numerics {

// --- HarmonicOscillator ---------------------------------------------------

void HarmonicOscillator::acceleration(double, ConstRef q, ConstRef, Ref a) const {
  a[0] = -m_omega * m_omega * q[0];
}

bool HarmonicOscillator::accelerationJacobian(double, ConstRef, ConstRef, Eigen::MatrixXd& dadq,
                                              Eigen::MatrixXd& dadv) const {
  dadq(0, 0) = -m_omega * m_omega;
  dadv(0, 0) = 0.0;
  return true;
}

std::optional<double> HarmonicOscillator::energy(const Eigen::VectorXd& y) const {
  return 0.5 * y[1] * y[1] + 0.5 * m_omega * m_omega * y[0] * y[0];
}

Eigen::VectorXd HarmonicOscillator::exactState(double t, const Eigen::VectorXd& y0) const {
  const double c = std::cos(m_omega * t);
  const double s = std::sin(m_omega * t);
  Eigen::VectorXd y(2);
  y[0] = y0[0] * c + y0[1] / m_omega * s;
  y[1] = -y0[0] * m_omega * s + y0[1] * c;
  return y;
}

// --- Pendulum ---------------------------------------------------------------

void Pendulum::acceleration(double, ConstRef q, ConstRef, Ref a) const {
  a[0] = -m_gOverL * std::sin(q[0]);
}

bool Pendulum::accelerationJacobian(double, ConstRef q, ConstRef, Eigen::MatrixXd& dadq,
                                    Eigen::MatrixXd& dadv) const {
  dadq(0, 0) = -m_gOverL * std::cos(q[0]);
  dadv(0, 0) = 0.0;
  return true;
}

std::optional<double> Pendulum::energy(const Eigen::VectorXd& y) const {
  return 0.5 * y[1] * y[1] + m_gOverL * (1.0 - std::cos(y[0]));
}

// --- LinearDecay ------------------------------------------------------------

void LinearDecay::derivative(double, const Eigen::VectorXd& y, Eigen::VectorXd& dy) const {
  dy[0] = -m_rate * y[0];
}

bool LinearDecay::analyticJacobian(double, const Eigen::VectorXd&, Eigen::MatrixXd& J) const {
  J(0, 0) = -m_rate;
  return true;
}

// --- SpringChain ------------------------------------------------------------

SpringChain::SpringChain(int masses, double stiffnessPerMass_per_s2)
    : m_n(masses), m_kOverM(stiffnessPerMass_per_s2) {
  TUMBLE_ASSERT(masses >= 1 && stiffnessPerMass_per_s2 > 0.0,
                "SpringChain needs at least one mass and k/m > 0.");
}

double SpringChain::modeOmega(int j) const {
  return 2.0 * std::sqrt(m_kOverM) * std::sin(j * std::numbers::pi / (2.0 * (m_n + 1)));
}

double SpringChain::maxOmega_rad_s() const { return modeOmega(m_n); }
double SpringChain::minOmega_rad_s() const { return modeOmega(1); }

void SpringChain::acceleration(double, ConstRef q, ConstRef, Ref a) const {
  for (int i = 0; i < m_n; ++i) {
    const double left = i > 0 ? q[i - 1] : 0.0;
    const double right = i + 1 < m_n ? q[i + 1] : 0.0;
    a[i] = m_kOverM * (left - 2.0 * q[i] + right);
  }
}

bool SpringChain::accelerationJacobian(double, ConstRef, ConstRef, Eigen::MatrixXd& dadq,
                                       Eigen::MatrixXd& dadv) const {
  dadq.setZero();
  for (int i = 0; i < m_n; ++i) {
    dadq(i, i) = -2.0 * m_kOverM;
    if (i > 0) dadq(i, i - 1) = m_kOverM;
    if (i + 1 < m_n) dadq(i, i + 1) = m_kOverM;
  }
  dadv.setZero();
  return true;
}

std::optional<double> SpringChain::energy(const Eigen::VectorXd& y) const {
  double kinetic = 0.5 * y.tail(m_n).squaredNorm();
  double potential = 0.0;
  for (int i = 0; i <= m_n; ++i) {
    const double left = i > 0 ? y[i - 1] : 0.0;
    const double right = i < m_n ? y[i] : 0.0;
    potential += 0.5 * m_kOverM * (right - left) * (right - left);
  }
  return kinetic + potential;
}

Eigen::VectorXd SpringChain::exactState(double t, const Eigen::VectorXd& y0) const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * m_n);
  Eigen::VectorXd phi(m_n);
  for (int j = 1; j <= m_n; ++j) {
    for (int i = 1; i <= m_n; ++i) phi[i - 1] = std::sin(i * j * std::numbers::pi / (m_n + 1));
    const double a = 2.0 / (m_n + 1) * phi.dot(y0.head(m_n));
    const double b = 2.0 / (m_n + 1) * phi.dot(y0.tail(m_n));
    const double w = modeOmega(j);
    const double c = std::cos(w * t);
    const double s = std::sin(w * t);
    y.head(m_n) += phi * (a * c + b * s / w);
    y.tail(m_n) += phi * (-a * w * s + b * c);
  }
  return y;
}

}  // namespace tumble::numerics
