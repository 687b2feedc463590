// integrateFree: the joint-only integrator, for the integrator comparison
// of Baraff's paper. No contacts and no World::step: the jointed bodies'
// full state (x, q, v, w) in double, with the constraint forces of
// lagrange_solver.cpp re-solved at every stage.
//
// Alone (integrateFree): explicit Euler, the explicit trapezoid rule (Heun),
// semi-implicit Euler or RK4 on the full state (x, q, v, w) with the
// constraint forces re-solved at every stage, no projection: the paper's
// scheme, for its stability claim. Largest stable dt (5-link chain released
// at 45 degrees, 5 s; stable = finite, anchor error < 5 cm, |E - E0| < m g L;
// printed by tests/physics/joints):
//      k_s    k_d   explicit Euler  trapezoid  semi-implicit  RK4
//        0      0       0.002         0.015       0.001       0.06
//       25     10       0.002         0.0225      0.0275      0.08
//      100     20       0.002         0.0225      0.03        0.08
//      400     40       0.002         0.0175      0.03        0.08   (defaults)
//      900     60       0.002         0.0175      0.0225      0.06
//     2500    100       0.002         0.0275      0.015       0.04
// Explicit Euler is limited by the chain's own undamped pendulum modes (its
// amplification |1 + i w h| > 1 gains energy at any dt), not by the gains;
// the trapezoid rule reaches the paper's ~0.02-0.03 s and, like the
// semi-implicit scheme, depends on (k_s, k_d): large k_d h or k_s h^2 costs
// stability. The defaults k_s = 400 /s^2, k_d = 40 /s (critically damped,
// 20 rad/s) are stable up to dt = 0.03 s with the semi-implicit scheme the
// World uses (60 Hz has a margin of 1.8).
#include <cmath>
#include <vector>

#include "physics/internal/lagrange_solver.h"
#include "physics/world.h"

namespace tumble::physics {

using namespace lagrange;

namespace {

struct Deriv {
  V3 dx = V3::Zero(), dv = V3::Zero(), dw = V3::Zero();
  Eigen::Vector4d dq = Eigen::Vector4d::Zero();
};

void advance(const std::vector<BodyState>& y, const std::vector<Deriv>& k, double h, std::vector<BodyState>& out) {
  out = y;
  for (std::size_t i = 0; i < y.size(); ++i) {
    if (!y[i].dynamic) continue;
    out[i].x += h * k[i].dx;
    out[i].v += h * k[i].dv;
    out[i].w += h * k[i].dw;
    out[i].q.coeffs() += h * k[i].dq;
    out[i].q.normalize();
  }
}

}  // namespace

void JointSystem::integrateFree(JointIntegrator method, double h) {
  m_broken.clear();
  if (!(h > 0) || !std::isfinite(h) || !dropJointsOfDeadBodies()) return;
  prepare();
  Impl& im = *m_impl;
  const V3 g = wide3(m_world.settings().gravity_mps2);
  std::vector<JointBreakEvent> events;
  // f(y): velocities and accelerations with the constraint forces solved at y.
  auto f = [&](const std::vector<BodyState>& y) {
    im.states = y;
    auto ev = solveConstraints(im, m_settings, g, false, m_stats);
    events.insert(events.end(), ev.begin(), ev.end());
    std::vector<Deriv> d(y.size());
    for (std::size_t i = 0; i < y.size(); ++i) {
      const BodyState& s = im.states[i];
      if (!s.dynamic) continue;
      d[i].dx = s.v;
      d[i].dv = s.invMass * (s.Qf + s.Fc);
      d[i].dw = s.invI * (s.Qt + s.Tc);
      const Qd wq(0, s.w.x(), s.w.y(), s.w.z());
      d[i].dq = 0.5 * (wq * s.q).coeffs();
    }
    return d;
  };
  const std::vector<BodyState> y0 = im.states;
  std::vector<BodyState> y1, tmp;
  switch (method) {
    case JointIntegrator::ExplicitEuler: advance(y0, f(y0), h, y1); break;
    case JointIntegrator::Trapezoid: {
      const std::vector<Deriv> k1 = f(y0);
      advance(y0, k1, h, tmp);
      std::vector<Deriv> k2 = f(tmp);
      for (std::size_t i = 0; i < k2.size(); ++i) {
        k2[i].dx = (k1[i].dx + k2[i].dx) / 2;
        k2[i].dv = (k1[i].dv + k2[i].dv) / 2;
        k2[i].dw = (k1[i].dw + k2[i].dw) / 2;
        k2[i].dq = (k1[i].dq + k2[i].dq) / 2;
      }
      advance(y0, k2, h, y1);
      break;
    }
    case JointIntegrator::SemiImplicitEuler: {
      std::vector<Deriv> k = f(y0);
      y1 = y0;
      for (std::size_t i = 0; i < y0.size(); ++i) {
        if (!y0[i].dynamic) continue;
        y1[i].v += h * k[i].dv;
        y1[i].w += h * k[i].dw;
        y1[i].x += h * y1[i].v;
        const Qd wq(0, y1[i].w.x(), y1[i].w.y(), y1[i].w.z());
        y1[i].q.coeffs() += 0.5 * h * (wq * y0[i].q).coeffs();
        y1[i].q.normalize();
      }
      break;
    }
    case JointIntegrator::Rk4: {
      const std::vector<Deriv> k1 = f(y0);
      advance(y0, k1, h / 2, tmp);
      const std::vector<Deriv> k2 = f(tmp);
      advance(y0, k2, h / 2, tmp);
      const std::vector<Deriv> k3 = f(tmp);
      advance(y0, k3, h, tmp);
      std::vector<Deriv> k4 = f(tmp);
      for (std::size_t i = 0; i < k4.size(); ++i) {
        k4[i].dx = (k1[i].dx + 2 * k2[i].dx + 2 * k3[i].dx + k4[i].dx) / 6;
        k4[i].dv = (k1[i].dv + 2 * k2[i].dv + 2 * k3[i].dv + k4[i].dv) / 6;
        k4[i].dw = (k1[i].dw + 2 * k2[i].dw + 2 * k3[i].dw + k4[i].dw) / 6;
        k4[i].dq = (k1[i].dq + 2 * k2[i].dq + 2 * k3[i].dq + k4[i].dq) / 6;
      }
      advance(y0, k4, h, y1);
      break;
    }
  }
  recordForces();  // the last stage's forces
  for (const BodyState& s : y1) {
    if (!s.dynamic) continue;
    m_world.setPosition(s.id, s.x.cast<Real>());
    m_world.setOrientation(s.id, s.q.cast<Real>());
    m_world.setLinearVelocity(s.id, s.v.cast<Real>());
    m_world.setAngularVelocity(s.id, s.w.cast<Real>());
  }
  finishBreaks(events);
  measureError();
}

}  // namespace tumble::physics
