#pragma once
// Time integrators as named, interchangeable strategies.
//
// Sections
//   Method, MethodInfo, methodTable()   the catalogue: name, order, implicit?
//   parseMethod(), methodName()         names <-> enum ("rk4", "verlet", ...)
//   checkMethodFor()                    can this method step this system?
//   NewtonSettings                      tolerances of the implicit methods
//   Integrator                          one method plus its scratch memory;
//                                       step(system, t, y, dt)
//
// The formulas, their orders and stability limits are derived at the top of
// integrator.cpp. Usage:
//
//   auto method = parseMethod("rk4");            // Result<Method>
//   Integrator integrator(*method, system.dimension());
//   for (int i = 0; i < n; ++i, t += dt) integrator.step(system, t, y, dt);
#include <Eigen/Core>
#include <Eigen/LU>
#include <span>
#include <string>
#include <string_view>

#include "core/byte_stream.h"
#include "core/result.h"
#include "numerics/ode.h"

namespace tumble::numerics {

enum class Method {
  ExplicitEuler,     // "euler": order 1, explicit
  SymplecticEuler,   // "symplectic_euler": order 1, explicit, needs y = [q, v]
  Heun,              // "heun": explicit trapezoid, order 2
  Rk4,               // "rk4": classical Runge-Kutta, order 4
  Verlet,            // "verlet": velocity Verlet / leapfrog, order 2, needs y = [q, v]
  ImplicitEuler,     // "implicit_euler": order 1, L-stable
  ImplicitMidpoint,  // "implicit_midpoint": order 2, A-stable, symplectic
  Sdirk2,            // "sdirk2": order 2, L-stable; the recommended stiff method
};

struct MethodInfo {
  Method method;
  const char* name;         // canonical name used on the command line and in reports
  int order;                // global order of accuracy on smooth problems
  bool implicit;            // solves a nonlinear system (Newton) every step
  bool needsSecondOrder;    // needs OdeSystem::asSecondOrder()
  const char* description;  // one line for reports
};

/// Every method, in the order reports list them.
std::span<const MethodInfo> methodTable();
const MethodInfo& methodInfo(Method method);
const char* methodName(Method method);

/// Looks a method up by its canonical name or an alias ("explicit_euler",
/// "semi_implicit_euler", "trapezoid", "leapfrog", "velocity_verlet",
/// "backward_euler", "midpoint"). The error lists every valid name.
Result<Method> parseMethod(std::string_view name);

/// Ok, or an error saying why `method` cannot step `system` (the symplectic
/// methods need a SecondOrderSystem).
Status checkMethodFor(Method method, const OdeSystem& system);

/// Newton's method for the implicit stages Z = base + h * f(tau, Z).
///
/// Simplified Newton: the iteration matrix I - h*J is built from the Jacobian
/// at the start of the step and LU-factorised once (Eigen::PartialPivLU: the
/// matrix is not symmetric for a first-order system, so LDLT does not apply),
/// then reused for every iteration and every stage. If the iteration has not
/// converged after maxIterations, the Jacobian is re-evaluated at the current
/// iterate and Newton restarts once (full Newton for hard nonlinear steps).
/// Converged when the max-norm of the correction is at most
/// absTolerance + relTolerance * max-norm of the iterate.
struct NewtonSettings {
  double relTolerance = 1e-12;  // below the discretisation error of every sweep we run
  double absTolerance = 1e-14;  // for states that decay to ~0 (stiff decay)
  int maxIterations = 10;       // per attempt; 2 attempts per stage
};

/// What one step did (implicit methods only report Newton work).
struct StepInfo {
  int newtonIterations = 0;
  bool converged = true;  // false: Newton did not converge; y holds the last iterate
};

/// Counters over an Integrator's lifetime (the cost side of the reports).
struct IntegratorStats {
  long steps = 0;
  long derivativeEvaluations = 0;  // f(t, y) or a(t, q, v) calls
  long jacobianEvaluations = 0;
  long factorizations = 0;
  long newtonFailures = 0;
};

/// One method with preallocated scratch vectors for one system dimension, so
/// the explicit methods' step() never allocates; the implicit ones allocate
/// only inside a Jacobian evaluation (once per step, more on a Newton retry).
class Integrator {
 public:
  Integrator(Method method, int dimension, NewtonSettings newton = {});

  Method method() const { return m_method; }
  const IntegratorStats& stats() const { return m_stats; }

  /// Advances y from t to t + dt in place. The system must have the
  /// dimension given at construction and suit the method (checkMethodFor).
  StepInfo step(const OdeSystem& system, double t, Eigen::VectorXd& y, double dt);

  /// What a later step reads besides y and t, as exact bits (snapshots of a
  /// running scene): the counters and velocity Verlet's cached acceleration.
  /// restoreState refuses bytes of another dimension.
  void saveState(ByteWriter& w) const;
  bool restoreState(ByteReader& r);

 private:
  void eval(const OdeSystem& system, double t, const Eigen::VectorXd& y, Eigen::VectorXd& dy);
  void evalAcceleration(const SecondOrderSystem& system, double t, const Eigen::VectorXd& y,
                        Eigen::Ref<Eigen::VectorXd> a);
  void factorIterationMatrix(const OdeSystem& system, double t, const Eigen::VectorXd& y, double h);
  StepInfo solveStage(const OdeSystem& system, double tau, const Eigen::VectorXd& base, double h,
                      Eigen::VectorXd& z, Eigen::VectorXd& fz);

  StepInfo stepExplicitEuler(const OdeSystem& system, double t, Eigen::VectorXd& y, double dt);
  StepInfo stepSymplecticEuler(const SecondOrderSystem& system, double t, Eigen::VectorXd& y,
                               double dt);
  StepInfo stepHeun(const OdeSystem& system, double t, Eigen::VectorXd& y, double dt);
  StepInfo stepRk4(const OdeSystem& system, double t, Eigen::VectorXd& y, double dt);
  StepInfo stepVerlet(const SecondOrderSystem& system, double t, Eigen::VectorXd& y, double dt);
  StepInfo stepImplicitEuler(const OdeSystem& system, double t, Eigen::VectorXd& y, double dt);
  StepInfo stepImplicitMidpoint(const OdeSystem& system, double t, Eigen::VectorXd& y, double dt);
  StepInfo stepSdirk2(const OdeSystem& system, double t, Eigen::VectorXd& y, double dt);

  Method m_method;
  int m_dimension;
  NewtonSettings m_newton;
  IntegratorStats m_stats;

  // Scratch, sized once.
  Eigen::VectorXd m_k1, m_k2, m_k3, m_k4, m_tmp, m_base, m_residual, m_delta;
  Eigen::MatrixXd m_jacobian, m_iteration;
  Eigen::PartialPivLU<Eigen::MatrixXd> m_lu;
  // The h that m_lu was factorised for (I - h J); checked by solveStage.
  double m_factorH = 0.0;

  // Velocity Verlet reuses the acceleration at the end of one step as the
  // start of the next (one evaluation per step) when the caller passes the
  // state it got back, unchanged, at the time it ended at.
  Eigen::VectorXd m_verletAccel, m_verletLastY;
  double m_verletLastT = 0.0;
  bool m_verletCacheValid = false;
};

/// Convenience for one-off steps (allocates an Integrator each call; loops
/// should keep an Integrator instead).
StepInfo step(Method method, const OdeSystem& system, double t, Eigen::VectorXd& y, double dt);

}  // namespace tumble::numerics
