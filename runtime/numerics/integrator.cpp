// Integrators for y' = f(t, y), step h.
//
// Stability: apply a method to the test equation y' = lambda*y; one step
// multiplies y by R(z), z = h*lambda. The method is stable where |R(z)| <= 1.
// Decay (lambda = -c < 0) probes the negative real axis; an undamped
// oscillator (lambda = +-i*omega) probes the imaginary axis, where |R| > 1
// means the energy grows every step.
//
//   explicit Euler   y1 = y + h f(t, y)                   R = 1 + z
//                    real: c*h < 2; imaginary: |R|^2 = 1 + (omega h)^2 > 1,
//                    energy grows for every h.
//   Heun             y~ = y + h f(t, y)
//   (explicit        y1 = y + h/2 (f(t, y) + f(t+h, y~)) R = 1 + z + z^2/2
//    trapezoid)      real: c*h < 2; imaginary: |R|^2 = 1 + (omega h)^4/4 > 1.
//   RK4              classical four stages                R = sum_{k<=4} z^k/k!
//                    real: R(-x) = 1 at 1 - x/2 + x^2/6 - x^3/24 = 0,
//                    x = 2.7853; imaginary: |R(i w)| <= 1 for w <= 2*sqrt(2).
//   implicit Euler   y1 = y + h f(t+h, y1)                R = 1/(1 - z)
//                    |R| < 1 on the whole left half-plane (A-stable) and
//                    R -> 0 as z -> -inf (L-stable: stiff modes are damped in
//                    one step). Order 1, and it also damps the resolved
//                    motion: an oscillator loses ~ (omega h)^2/2 of its
//                    amplitude per step.
//   implicit         y1 = y + h f(t+h/2, (y + y1)/2)     R = (1 + z/2)/(1 - z/2)
//   midpoint         A-stable, |R| = 1 on the imaginary axis (keeps quadratic
//                    invariants exactly: energy of linear springs), order 2,
//                    symplectic. But R -> -1 as z -> -inf: a stiff mode is not
//                    damped, it flips sign every step (jitter).
//   SDIRK2           Alexander's 2-stage singly diagonally implicit RK,
//                    gamma = 1 - 1/sqrt(2):
//                      Z1 = y + gamma h f(t + gamma h, Z1)
//                      Z2 = y + (1-gamma) h f1 + gamma h f(t+h, Z2),  y1 = Z2
//                    Order-2 condition gamma^2 - 2 gamma + 1/2 = 0; the root
//                    below 1 keeps both stage times inside the step.
//                    R = (1 + (1 - 2 gamma) z)/(1 - gamma z)^2 -> 0 as
//                    z -> -inf: A- and L-stable.
//
// Why SDIRK2 is our "best for stiff" method. Stiff scenes (springs with
// k/m = 1e6 at 60 Hz, rope and cloth, heavy-on-light stacks) have modes far
// faster than the step. Explicit methods explode (need omega h < 2 or 2.8);
// implicit midpoint / implicit trapezoid keep them as step-frequency jitter
// (R -> -1); implicit Euler damps them but is only first order and visibly
// damps the slow, resolved motion too. SDIRK2 damps the stiff modes like
// implicit Euler (L-stable, and stiffly accurate: y1 is the last stage, so no
// order reduction on stiff decay) while being second order on the resolved
// motion. Both stages have the same diagonal gamma, so they share one LU
// factorisation of I - gamma h J: about twice the cost of implicit Euler.
// Rejected: BDF2 (needs a history of steps, which contact events and
// teleports reset), Radau IIA (order 5 but a coupled 3n x 3n system per step,
// too costly for the sizes a game steps at 60 Hz).
//
// Second-order systems y = [q, v], v' = a(t, q, v):
//   semi-implicit (symplectic) Euler  v1 = v + h a(t, q, v); q1 = q + h v1
//   velocity Verlet                   v+ = v + h/2 a(t, q, v); q1 = q + h v+;
//                                     v1 = v+ + h/2 a(t+h, q1, v+)
// Both are symplectic: on an oscillator the step matrix has determinant 1 and
// trace 2 - (omega h)^2, so they are stable for omega h < 2 with a bounded
// energy error (no drift). Verlet evaluates a(q1, v+) with the half-step
// velocity: exact for position-only forces (all reference problems); with
// velocity-dependent forces (damping) it drops to first order.
#include "numerics/integrator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace tumble::numerics {
namespace {

constexpr std::array<MethodInfo, 8> kMethods = {{
    {Method::ExplicitEuler, "euler", 1, false, false, "explicit (forward) Euler"},
    {Method::SymplecticEuler, "symplectic_euler", 1, false, true,
     "semi-implicit (symplectic) Euler: velocity first, then position"},
    {Method::Heun, "heun", 2, false, false, "Heun / explicit trapezoid"},
    {Method::Rk4, "rk4", 4, false, false, "classical Runge-Kutta, 4 stages"},
    {Method::Verlet, "verlet", 2, false, true, "velocity Verlet / leapfrog"},
    {Method::ImplicitEuler, "implicit_euler", 1, true, false,
     "implicit (backward) Euler, simplified Newton"},
    {Method::ImplicitMidpoint, "implicit_midpoint", 2, true, false,
     "implicit midpoint: A-stable, symplectic, not L-stable"},
    {Method::Sdirk2, "sdirk2", 2, true, false,
     "2-stage SDIRK (Alexander): A- and L-stable, recommended for stiff"},
}};

struct Alias {
  const char* name;
  Method method;
};
constexpr std::array<Alias, 8> kAliases = {{
    {"explicit_euler", Method::ExplicitEuler},
    {"semi_implicit_euler", Method::SymplecticEuler},
    {"trapezoid", Method::Heun},
    {"leapfrog", Method::Verlet},
    {"velocity_verlet", Method::Verlet},
    {"backward_euler", Method::ImplicitEuler},
    {"midpoint", Method::ImplicitMidpoint},
    {"stiff", Method::Sdirk2},
}};

// 1 - 1/sqrt(2), see the top of the file.
const double kSdirkGamma = 1.0 - 1.0 / std::sqrt(2.0);

}  // namespace

std::span<const MethodInfo> methodTable() { return kMethods; }

const MethodInfo& methodInfo(Method method) {
  for (const MethodInfo& info : kMethods)
    if (info.method == method) return info;
  TUMBLE_ASSERT(false, "Method missing from kMethods in integrator.cpp; add its row.");
  return kMethods[0];
}

const char* methodName(Method method) { return methodInfo(method).name; }

Result<Method> parseMethod(std::string_view name) {
  for (const MethodInfo& info : kMethods)
    if (name == info.name) return info.method;
  for (const Alias& alias : kAliases)
    if (name == alias.name) return alias.method;
  std::string message = "unknown integrator '" + std::string(name) + "'; valid names: ";
  for (std::size_t i = 0; i < kMethods.size(); ++i) {
    if (i > 0) message += ", ";
    message += kMethods[i].name;
  }
  message += " (aliases:";
  for (const Alias& alias : kAliases) {
    message += ' ';
    message += alias.name;
    message += '=';
    message += methodName(alias.method);
  }
  message += ")";
  return makeError(message);
}

Status checkMethodFor(Method method, const OdeSystem& system) {
  if (methodInfo(method).needsSecondOrder && system.asSecondOrder() == nullptr)
    return makeError(std::string("integrator '") + methodName(method) +
                     "' updates positions and velocities separately and needs a "
                     "second-order system (y = [q, v]); this system is first-order. "
                     "Use euler, heun, rk4, implicit_euler, implicit_midpoint or sdirk2.");
  return Ok{};
}

Integrator::Integrator(Method method, int dimension, NewtonSettings newton)
    : m_method(method), m_dimension(dimension), m_newton(newton) {
  TUMBLE_ASSERT(dimension > 0, "Integrator needs the system's dimension (> 0).");
  for (Eigen::VectorXd* v : {&m_k1, &m_k2, &m_k3, &m_k4, &m_tmp, &m_base, &m_residual, &m_delta})
    v->resize(dimension);
  if (methodInfo(method).implicit) {
    m_jacobian.resize(dimension, dimension);
    m_iteration.resize(dimension, dimension);
  }
  if (method == Method::Verlet) {
    m_verletAccel.resize(dimension / 2);
    m_verletLastY.resize(dimension);
  }
}

StepInfo Integrator::step(const OdeSystem& system, double t, Eigen::VectorXd& y, double dt) {
  TUMBLE_ASSERT(system.dimension() == m_dimension && y.size() == m_dimension,
                "Integrator::step: system/state dimension differs from the one the "
                "Integrator was made for. Make one Integrator per system.");
  ++m_stats.steps;
  switch (m_method) {
    case Method::ExplicitEuler: return stepExplicitEuler(system, t, y, dt);
    case Method::Heun: return stepHeun(system, t, y, dt);
    case Method::Rk4: return stepRk4(system, t, y, dt);
    case Method::ImplicitEuler: return stepImplicitEuler(system, t, y, dt);
    case Method::ImplicitMidpoint: return stepImplicitMidpoint(system, t, y, dt);
    case Method::Sdirk2: return stepSdirk2(system, t, y, dt);
    case Method::SymplecticEuler:
    case Method::Verlet: {
      const SecondOrderSystem* second = system.asSecondOrder();
      TUMBLE_ASSERT(second != nullptr,
                    "symplectic_euler/verlet need a SecondOrderSystem; call "
                    "checkMethodFor() before stepping.");
      return m_method == Method::Verlet ? stepVerlet(*second, t, y, dt)
                                        : stepSymplecticEuler(*second, t, y, dt);
    }
  }
  return {};
}

void Integrator::eval(const OdeSystem& system, double t, const Eigen::VectorXd& y,
                      Eigen::VectorXd& dy) {
  ++m_stats.derivativeEvaluations;
  system.derivative(t, y, dy);
}

void Integrator::evalAcceleration(const SecondOrderSystem& system, double t,
                                  const Eigen::VectorXd& y, Eigen::Ref<Eigen::VectorXd> a) {
  ++m_stats.derivativeEvaluations;
  const int n = system.dofs();
  system.acceleration(t, y.head(n), y.tail(n), a);
}

StepInfo Integrator::stepExplicitEuler(const OdeSystem& system, double t, Eigen::VectorXd& y,
                                       double dt) {
  eval(system, t, y, m_k1);
  y += dt * m_k1;
  return {};
}

StepInfo Integrator::stepSymplecticEuler(const SecondOrderSystem& system, double t,
                                         Eigen::VectorXd& y, double dt) {
  const int n = system.dofs();
  auto a = m_k1.head(n);
  evalAcceleration(system, t, y, a);
  y.tail(n) += dt * a;
  y.head(n) += dt * y.tail(n);
  return {};
}

StepInfo Integrator::stepHeun(const OdeSystem& system, double t, Eigen::VectorXd& y, double dt) {
  eval(system, t, y, m_k1);
  m_tmp = y + dt * m_k1;
  eval(system, t + dt, m_tmp, m_k2);
  y += (0.5 * dt) * (m_k1 + m_k2);
  return {};
}

StepInfo Integrator::stepRk4(const OdeSystem& system, double t, Eigen::VectorXd& y, double dt) {
  const double half = 0.5 * dt;
  eval(system, t, y, m_k1);
  m_tmp = y + half * m_k1;
  eval(system, t + half, m_tmp, m_k2);
  m_tmp = y + half * m_k2;
  eval(system, t + half, m_tmp, m_k3);
  m_tmp = y + dt * m_k3;
  eval(system, t + dt, m_tmp, m_k4);
  y += (dt / 6.0) * (m_k1 + 2.0 * m_k2 + 2.0 * m_k3 + m_k4);
  return {};
}

StepInfo Integrator::stepVerlet(const SecondOrderSystem& system, double t, Eigen::VectorXd& y,
                                double dt) {
  const int n = system.dofs();
  // t is compared with a tolerance: callers compute t as t0 + i*dt, which
  // differs from our accumulated t + dt in the last bits.
  const bool cached = m_verletCacheValid && y == m_verletLastY &&
                      std::abs(t - m_verletLastT) <= 1e-12 * std::max(1.0, std::abs(t));
  if (!cached) evalAcceleration(system, t, y, m_verletAccel);
  y.tail(n) += (0.5 * dt) * m_verletAccel;
  y.head(n) += dt * y.tail(n);
  evalAcceleration(system, t + dt, y, m_verletAccel);
  y.tail(n) += (0.5 * dt) * m_verletAccel;
  m_verletLastY = y;
  m_verletLastT = t + dt;
  m_verletCacheValid = true;
  return {};
}

void Integrator::factorIterationMatrix(const OdeSystem& system, double t, const Eigen::VectorXd& y,
                                       double h) {
  ++m_stats.jacobianEvaluations;
  ++m_stats.factorizations;
  jacobian(system, t, y, m_jacobian);
  m_iteration = -h * m_jacobian;
  m_iteration.diagonal().array() += 1.0;
  m_lu.compute(m_iteration);
  m_factorH = h;
}

// Solves z = base + h f(tau, z) with the factorised I - h J; z holds the
// initial guess on entry and the solution on exit, fz = f(tau, z) taken from
// the stage equation, (z - base)/h, which is exact at the solution and does
// not amplify the Newton residual by the stiff Jacobian.
// First attempt: simplified Newton with the matrix factorised at the start of
// the step. If it stalls or diverges, restart from the initial guess with full
// Newton (Jacobian re-evaluated and refactorised every iteration).
StepInfo Integrator::solveStage(const OdeSystem& system, double tau, const Eigen::VectorXd& base,
                                double h, Eigen::VectorXd& z, Eigen::VectorXd& fz) {
  TUMBLE_ASSERT(h == m_factorH, "solveStage: factorise I - h J for this h first.");
  StepInfo info;
  m_k4 = z;  // the initial guess, for the restart
  for (int attempt = 0; attempt < 2; ++attempt) {
    const bool fullNewton = attempt == 1;
    if (fullNewton) z = m_k4;
    double previous = INFINITY;
    for (int k = 0; k < m_newton.maxIterations; ++k) {
      ++info.newtonIterations;
      if (fullNewton) factorIterationMatrix(system, tau, z, h);
      eval(system, tau, z, m_residual);
      m_residual = base + h * m_residual - z;  // -G(z)
      m_delta = m_lu.solve(m_residual);
      z += m_delta;
      const double size = m_delta.lpNorm<Eigen::Infinity>();
      if (!std::isfinite(size)) break;
      if (size <= m_newton.absTolerance + m_newton.relTolerance * z.lpNorm<Eigen::Infinity>()) {
        fz = (z - base) / h;
        return info;
      }
      // Growing corrections: the frozen Jacobian is too far off; give up early.
      if (!fullNewton && size > 2.0 * previous) break;
      previous = size;
    }
  }
  ++m_stats.newtonFailures;
  info.converged = false;
  fz = (z - base) / h;
  return info;
}

StepInfo Integrator::stepImplicitEuler(const OdeSystem& system, double t, Eigen::VectorXd& y,
                                       double dt) {
  factorIterationMatrix(system, t, y, dt);
  m_base = y;
  return solveStage(system, t + dt, m_base, dt, y, m_k1);
}

StepInfo Integrator::stepImplicitMidpoint(const OdeSystem& system, double t, Eigen::VectorXd& y,
                                          double dt) {
  // Z = (y + y1)/2 solves Z = y + (h/2) f(t + h/2, Z); then y1 = 2 Z - y.
  const double h = 0.5 * dt;
  factorIterationMatrix(system, t, y, h);
  m_base = y;
  m_tmp = y;
  const StepInfo info = solveStage(system, t + h, m_base, h, m_tmp, m_k1);
  y = 2.0 * m_tmp - m_base;
  return info;
}

StepInfo Integrator::stepSdirk2(const OdeSystem& system, double t, Eigen::VectorXd& y, double dt) {
  const double gh = kSdirkGamma * dt;
  factorIterationMatrix(system, t, y, gh);
  m_base = y;
  m_tmp = y;
  StepInfo info = solveStage(system, t + gh, m_base, gh, m_tmp, m_k1);  // Z1, f1
  m_base = y + ((1.0 - kSdirkGamma) * dt) * m_k1;
  // Z2 starts from Z1; the result is y1 = Z2 (stiffly accurate).
  y = m_tmp;
  const StepInfo second = solveStage(system, t + dt, m_base, gh, y, m_k2);
  info.newtonIterations += second.newtonIterations;
  info.converged = info.converged && second.converged;
  return info;
}

StepInfo step(Method method, const OdeSystem& system, double t, Eigen::VectorXd& y, double dt) {
  Integrator integrator(method, system.dimension());
  return integrator.step(system, t, y, dt);
}

}  // namespace tumble::numerics

namespace tumble::numerics {

void Integrator::saveState(ByteWriter& w) const {
  static_assert(kBitwise<IntegratorStats>);
  w.pod(m_stats);
  w.pod(std::uint8_t(m_verletCacheValid));
  w.pod(m_verletLastT);
  w.vec(std::vector<double>(m_verletAccel.data(), m_verletAccel.data() + m_verletAccel.size()));
  w.vec(std::vector<double>(m_verletLastY.data(), m_verletLastY.data() + m_verletLastY.size()));
}

bool Integrator::restoreState(ByteReader& r) {
  const auto stats = r.pod<IntegratorStats>();
  const bool valid = r.pod<std::uint8_t>() != 0;
  const auto lastT = r.pod<double>();
  const std::vector<double> accel = r.vec<double>(std::size_t(m_dimension));
  const std::vector<double> lastY = r.vec<double>(std::size_t(m_dimension));
  if (!r.ok() || accel.size() != std::size_t(m_verletAccel.size()) || lastY.size() != std::size_t(m_verletLastY.size()))
    return false;
  m_stats = stats;
  m_verletCacheValid = valid;
  m_verletLastT = lastT;
  if (!accel.empty()) m_verletAccel = Eigen::Map<const Eigen::VectorXd>(accel.data(), Eigen::Index(accel.size()));
  if (!lastY.empty()) m_verletLastY = Eigen::Map<const Eigen::VectorXd>(lastY.data(), Eigen::Index(lastY.size()));
  return true;
}

}  // namespace tumble::numerics
