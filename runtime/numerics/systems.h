#pragma once
// Reference ODE systems with known answers (Eberly, Game Physics, ch. 9 and
// the usual stiff test problems). All in SI units; per-unit-mass forms.
//
//   HarmonicOscillator  q'' = -omega^2 q            exact: rotation in phase space
//   Pendulum            theta'' = -(g/L) sin theta  exact period: elliptic.h
//   LinearDecay         x' = -c x                   exact: x0 exp(-c t); stiff
//                                                   when c*dt >> 1
//   SpringChain         N equal masses, equal springs, both ends fixed to
//                       walls. a_i = (k/m)(q_{i-1} - 2 q_i + q_{i+1}),
//                       q_0 = q_{N+1} = 0. Exact solution by normal modes:
//                       phi_j(i) = sin(i j pi/(N+1)),
//                       omega_j = 2 sqrt(k/m) sin(j pi / (2 (N+1))), j = 1..N.
//                       The modes are orthogonal with |phi_j|^2 = (N+1)/2, so
//                       q(t) = sum_j phi_j (a_j cos(omega_j t) + b_j sin(omega_j t)/omega_j)
//                       with a_j = 2/(N+1) phi_j.q0, b_j = 2/(N+1) phi_j.v0.
//                       Stiffness ratio omega_N/omega_1 ~ 2(N+1)/pi; with
//                       k/m large the fast modes are far beyond 1/dt.
#include <Eigen/Core>

#include "numerics/ode.h"

namespace tumble::numerics {

class HarmonicOscillator final : public SecondOrderSystem {
 public:
  explicit HarmonicOscillator(double omega_rad_s) : m_omega(omega_rad_s) {}
  double omega_rad_s() const { return m_omega; }

  int dofs() const override { return 1; }
  void acceleration(double t, ConstRef q, ConstRef v, Ref a) const override;
  bool accelerationJacobian(double t, ConstRef q, ConstRef v, Eigen::MatrixXd& dadq,
                            Eigen::MatrixXd& dadv) const override;
  /// Energy per unit mass, J/kg: v^2/2 + omega^2 q^2/2.
  std::optional<double> energy(const Eigen::VectorXd& y) const override;

  /// Exact [q, v] at time t from y0 at t = 0.
  Eigen::VectorXd exactState(double t, const Eigen::VectorXd& y0) const;

 private:
  double m_omega;
};

class Pendulum final : public SecondOrderSystem {
 public:
  explicit Pendulum(double gOverL_per_s2) : m_gOverL(gOverL_per_s2) {}
  double gOverL_per_s2() const { return m_gOverL; }

  int dofs() const override { return 1; }
  void acceleration(double t, ConstRef q, ConstRef v, Ref a) const override;
  bool accelerationJacobian(double t, ConstRef q, ConstRef v, Eigen::MatrixXd& dadq,
                            Eigen::MatrixXd& dadv) const override;
  /// Energy per unit m L^2, 1/s^2, measured from the bottom:
  /// theta'^2/2 + (g/L)(1 - cos theta). Over-the-top motion starts at 2 g/L.
  std::optional<double> energy(const Eigen::VectorXd& y) const override;

 private:
  double m_gOverL;
};

class LinearDecay final : public OdeSystem {
 public:
  explicit LinearDecay(double rate_per_s) : m_rate(rate_per_s) {}
  double rate_per_s() const { return m_rate; }

  int dimension() const override { return 1; }
  void derivative(double t, const Eigen::VectorXd& y, Eigen::VectorXd& dy) const override;
  bool analyticJacobian(double t, const Eigen::VectorXd& y, Eigen::MatrixXd& J) const override;

 private:
  double m_rate;
};

class SpringChain final : public SecondOrderSystem {
 public:
  /// masses: N >= 1 movable masses between two walls; stiffnessPerMass = k/m.
  SpringChain(int masses, double stiffnessPerMass_per_s2);
  int masses() const { return m_n; }
  /// Highest normal-mode frequency, rad/s (sets the explicit step limit).
  double maxOmega_rad_s() const;
  /// Lowest normal-mode frequency, rad/s.
  double minOmega_rad_s() const;

  int dofs() const override { return m_n; }
  void acceleration(double t, ConstRef q, ConstRef v, Ref a) const override;
  bool accelerationJacobian(double t, ConstRef q, ConstRef v, Eigen::MatrixXd& dadq,
                            Eigen::MatrixXd& dadv) const override;
  /// Energy per unit mass, J/kg: sum v^2/2 + (k/m)/2 sum over the N+1 springs of stretch^2.
  std::optional<double> energy(const Eigen::VectorXd& y) const override;

  /// Exact [q, v] at time t from y0 at t = 0, by normal modes.
  Eigen::VectorXd exactState(double t, const Eigen::VectorXd& y0) const;

 private:
  double modeOmega(int j) const;
  int m_n;
  double m_kOverM;
};

}  // namespace tumble::numerics
