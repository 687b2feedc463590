#pragma once
// Generic ordinary differential equation systems y' = f(t, y), in double.
//
// Sections
//   OdeSystem          first-order system: dimension, derivative, optional
//                      Jacobian and energy
//   SecondOrderSystem  y = [q, v] with q' = v, v' = a(t, q, v); what the
//                      symplectic methods (semi-implicit Euler, Verlet) need
//   jacobian()         the analytic Jacobian when a system has one, forward
//                      differences otherwise
//
// The numerics lab computes in double whatever the rigid-body world stores
// (ARCHITECTURE.md). Systems write into caller-owned vectors so that an
// integrator can step without allocating.
#include <Eigen/Core>
#include <optional>

namespace tumble::numerics {

class SecondOrderSystem;

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;

  /// Length of the state vector y.
  virtual int dimension() const = 0;

  /// dy = f(t, y). dy arrives sized to dimension().
  virtual void derivative(double t, const Eigen::VectorXd& y, Eigen::VectorXd& dy) const = 0;

  /// Fills J = df/dy (dimension x dimension, arrives sized) and returns true,
  /// or returns false when the system has no analytic Jacobian; jacobian()
  /// then uses finite differences.
  virtual bool analyticJacobian(double t, const Eigen::VectorXd& y, Eigen::MatrixXd& J) const {
    (void)t, (void)y, (void)J;
    return false;
  }

  /// A conserved (or expected-to-decay) energy for reports, in the system's
  /// own units; nullopt when the system has none.
  virtual std::optional<double> energy(const Eigen::VectorXd& y) const {
    (void)y;
    return std::nullopt;
  }

  /// Non-null when y splits into positions and velocities (see below).
  virtual const SecondOrderSystem* asSecondOrder() const { return nullptr; }
};

/// Second-order system M q'' = F(t, q, q') written as y = [q, v] (each half
/// has dofs() entries), q' = v, v' = a(t, q, v). Symplectic methods update q
/// and v separately, so they need this split; every other method sees the
/// plain first-order derivative below.
class SecondOrderSystem : public OdeSystem {
 public:
  using ConstRef = Eigen::Ref<const Eigen::VectorXd>;
  using Ref = Eigen::Ref<Eigen::VectorXd>;

  /// Number of coordinates q (and velocities v).
  virtual int dofs() const = 0;

  /// a = a(t, q, v). a arrives sized to dofs().
  virtual void acceleration(double t, ConstRef q, ConstRef v, Ref a) const = 0;

  /// Fills da/dq and da/dv (dofs x dofs, arrive sized) and returns true, or
  /// returns false when there is no analytic form.
  virtual bool accelerationJacobian(double t, ConstRef q, ConstRef v, Eigen::MatrixXd& dadq,
                                    Eigen::MatrixXd& dadv) const {
    (void)t, (void)q, (void)v, (void)dadq, (void)dadv;
    return false;
  }

  int dimension() const final { return 2 * dofs(); }
  void derivative(double t, const Eigen::VectorXd& y, Eigen::VectorXd& dy) const final;
  /// J = [[0, I], [da/dq, da/dv]] when accelerationJacobian() is provided.
  bool analyticJacobian(double t, const Eigen::VectorXd& y, Eigen::MatrixXd& J) const final;
  const SecondOrderSystem* asSecondOrder() const final { return this; }
};

/// J = df/dy at (t, y): the analytic Jacobian if the system has one,
/// otherwise forward differences with step h_j = sqrt(eps) * max(|y_j|, 1)
/// (error O(h) ~ 1e-8 relative, plenty for Newton's method: the Jacobian only
/// sets how fast Newton converges, not where it converges to). J is resized.
void jacobian(const OdeSystem& system, double t, const Eigen::VectorXd& y, Eigen::MatrixXd& J);

/// Forward-difference Jacobian, always (exposed so tests can compare it with
/// an analytic one). J is resized.
void finiteDifferenceJacobian(const OdeSystem& system, double t, const Eigen::VectorXd& y,
                              Eigen::MatrixXd& J);

}  // namespace tumble::numerics
