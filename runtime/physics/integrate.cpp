// Integrator strategies for the rigid-body world, and applied springs.
//
// How a method combines with contacts. Contacts stay velocity-level
// impulses (contact_solver.cpp); only the free motion between them changes.
// In each substep of length h, for every awake dynamic body:
//
//   1. free motion: the chosen method advances the translational state
//        (x0, v0) -> (x_f, v_f)
//      under gravity, the forces scripts applied (held constant over the
//      step) and the springs (evaluated at every stage the method needs);
//   2. contacts and joints see v_f as the body's velocity and change it by
//      impulses: v = v_f + dv;
//   3. position: x1 = x_f + h dv (+ h times the split-impulse pseudo-velocity).
//
// So a body that touches nothing moves exactly as the method says, and a
// contact impulse moves the body the way it does under symplectic Euler (the
// default, where x_f = x0 + h v_f and therefore x1 = x0 + h v: the same
// arithmetic as World's own loop, which is why the default skips this file).
// Non-penetration is enforced on the velocity after the free step for every
// method, so the contact solver's guarantees do not depend on the choice.
//
// Rotation is not routed through the methods: the orientation always turns
// torque-free with the angular momentum kept (world_step.cpp explains why,
// and why explicit rotation loses). Springs act at centres of mass, so
// they add no torque and their stiffness lives entirely in the translational
// state the methods see.
//
// Grouping. Bodies joined by springs (both ends moving) form one ODE system
// y = [x_1..x_n, v_1..v_n] with an analytic Jacobian (springForce below), so
// the implicit methods solve one dense (6n x 6n) Newton system per group:
// fine for the tens of bodies a spring rig has; a rope or cloth of hundreds
// of particles belongs in deformable.h (sparse CG). A body without springs
// is a 6-dimensional system of its own. A spring end on a static,
// kinematic, sleeping or frozen body, or on an anchor, is a fixed point for
// the substep (a sleeping body is not woken by a spring: keep such bodies
// awake with allow_sleep = false).
//
// What each method does with constant acceleration a (a free body): every
// method of order >= 2 reproduces x0 + h v0 + h^2 a / 2 exactly (the solution
// is a quadratic in t); explicit Euler lags by h^2 a / 2 per step, symplectic
// and implicit Euler lead by h^2 a / 2. The differences that matter show with
// springs: see the stiff-spring cases of `tumble report stability`.
#include "physics/integrate.h"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>

#include "numerics/integrator.h"
#include "physics/world.h"

namespace tumble::physics {
namespace {

constexpr std::array<BodyIntegratorInfo, 8> kBodyIntegrators = {{
    {BodyIntegrator::SymplecticEuler, "symplectic_euler", "default: fast, bounded energy error, contacts and joints"},
    {BodyIntegrator::Euler, "euler", "comparison only: gains energy on every spring"},
    {BodyIntegrator::Heun, "heun", "smooth force fields, order 2, two force evaluations"},
    {BodyIntegrator::Rk4, "rk4", "accurate free flight and soft springs, order 4, four evaluations"},
    {BodyIntegrator::Verlet, "verlet", "orbits and soft springs, order 2, symplectic"},
    {BodyIntegrator::ImplicitEuler, "implicit_euler", "stiff springs when damping them is fine"},
    {BodyIntegrator::ImplicitMidpoint, "implicit_midpoint", "energy-exact linear springs; stiff modes ring"},
    {BodyIntegrator::Sdirk2, "sdirk2", "stiff springs (k/m up to 1e6 at 60 Hz), order 2"},
}};

numerics::Method toNumerics(BodyIntegrator m) {
  switch (m) {
    case BodyIntegrator::SymplecticEuler: return numerics::Method::SymplecticEuler;
    case BodyIntegrator::Euler: return numerics::Method::ExplicitEuler;
    case BodyIntegrator::Heun: return numerics::Method::Heun;
    case BodyIntegrator::Rk4: return numerics::Method::Rk4;
    case BodyIntegrator::Verlet: return numerics::Method::Verlet;
    case BodyIntegrator::ImplicitEuler: return numerics::Method::ImplicitEuler;
    case BodyIntegrator::ImplicitMidpoint: return numerics::Method::ImplicitMidpoint;
    case BodyIntegrator::Sdirk2: return numerics::Method::Sdirk2;
  }
  return numerics::Method::SymplecticEuler;
}

Eigen::Vector3d d3(const Vec3& v) { return v.cast<double>(); }

/// One spring as a group sees it: ends are member indices or fixed points.
struct GroupSpring {
  int a = -1, b = -1;  ///< member index, -1: fixed end
  Eigen::Vector3d fixedA = Eigen::Vector3d::Zero(), fixedB = Eigen::Vector3d::Zero();
  Eigen::Vector3d fixedVA = Eigen::Vector3d::Zero(), fixedVB = Eigen::Vector3d::Zero();
  double k = 0, c = 0, rest = 0;
};

/// y = [x (3n), v (3n)] of one group of bodies; see the top of the file.
class GroupSystem final : public numerics::SecondOrderSystem {
 public:
  int n = 0;
  std::vector<double> invMass;             ///< per member, 1/kg
  std::vector<Eigen::Vector3d> constAccel;  ///< g + F/m per member, m/s^2
  std::vector<GroupSpring> springs;

  int dofs() const override { return 3 * n; }

  void acceleration(double, ConstRef q, ConstRef v, Ref a) const override {
    for (int i = 0; i < n; ++i) a.segment<3>(3 * i) = constAccel[std::size_t(i)];
    for (const GroupSpring& s : springs) {
      const SpringEval e = eval(s, q, v, false);
      if (s.a >= 0) a.segment<3>(3 * s.a) += invMass[std::size_t(s.a)] * e.force_N;
      if (s.b >= 0) a.segment<3>(3 * s.b) -= invMass[std::size_t(s.b)] * e.force_N;
    }
  }

  bool accelerationJacobian(double, ConstRef q, ConstRef v, Eigen::MatrixXd& dadq,
                            Eigen::MatrixXd& dadv) const override {
    dadq.setZero();
    dadv.setZero();
    for (const GroupSpring& s : springs) {
      const SpringEval e = eval(s, q, v, true);
      // F_a depends on x_a via -K, on x_b via +K; F_b = -F_a.
      const int ends[2] = {s.a, s.b};
      const double sign[2] = {1, -1};
      for (int r = 0; r < 2; ++r) {
        if (ends[r] < 0) continue;
        const double im = sign[r] * invMass[std::size_t(ends[r])];
        for (int col = 0; col < 2; ++col) {
          if (ends[col] < 0) continue;
          const double cs = col == 0 ? -1 : 1;
          dadq.block<3, 3>(3 * ends[r], 3 * ends[col]) += im * cs * e.K;
          dadv.block<3, 3>(3 * ends[r], 3 * ends[col]) += im * cs * e.D;
        }
      }
    }
    return true;
  }

 private:
  static SpringEval eval(const GroupSpring& s, ConstRef q, ConstRef v, bool jac) {
    const Eigen::Vector3d xa = s.a >= 0 ? Eigen::Vector3d(q.segment<3>(3 * s.a)) : s.fixedA;
    const Eigen::Vector3d xb = s.b >= 0 ? Eigen::Vector3d(q.segment<3>(3 * s.b)) : s.fixedB;
    const Eigen::Vector3d va = s.a >= 0 ? Eigen::Vector3d(v.segment<3>(3 * s.a)) : s.fixedVA;
    const Eigen::Vector3d vb = s.b >= 0 ? Eigen::Vector3d(v.segment<3>(3 * s.b)) : s.fixedVB;
    return springForce(xa, xb, va, vb, s.k, s.c, s.rest, jac);
  }
};

}  // namespace

/// Arrays reused every substep (no allocation once warm, apart from the
/// implicit methods' Jacobians inside numerics).
struct BodyIntegrationScratch {
  std::vector<std::uint32_t> parent, groupOf, members;
  std::vector<int> memberIndex;  ///< per body slot: index inside its group, -1 none
  std::vector<std::uint32_t> groupStart;
  std::vector<std::uint32_t> springStart, springIndex, cursor;  ///< springs bucketed by group root
  std::vector<Vec3> dxFree, vFree;  ///< per body slot
  std::vector<std::uint8_t> advanced;
  GroupSystem system;
  Eigen::VectorXd y;
  std::map<std::pair<int, int>, std::unique_ptr<numerics::Integrator>> integrators;  ///< by (method, dimension)
};

std::span<const BodyIntegratorInfo> bodyIntegrators() { return kBodyIntegrators; }

const char* bodyIntegratorName(BodyIntegrator method) {
  for (const auto& info : kBodyIntegrators)
    if (info.method == method) return info.name;
  return "?";
}

Result<BodyIntegrator> parseBodyIntegrator(std::string_view name) {
  for (const auto& info : kBodyIntegrators)
    if (name == info.name) return info.method;
  // numerics' aliases (trapezoid, leapfrog, stiff, ...) name the same methods.
  if (auto m = numerics::parseMethod(name))
    for (const auto& info : kBodyIntegrators)
      if (toNumerics(info.method) == *m) return info.method;
  std::string known;
  for (const auto& info : kBodyIntegrators) known += (known.empty() ? "" : ", ") + std::string(info.name);
  return makeError("integrator \"" + std::string(name) + "\" is not one the rigid-body world offers; valid: " + known);
}

Status validateSpringDef(const SpringDef& d) {
  if (d.a.isNull()) return makeError("spring field 'a' must be a body");
  if (d.b.isNull() && !d.anchor_m.allFinite()) return makeError("spring field 'anchor' must be a finite point (m)");
  if (!std::isfinite(d.stiffness_Npm) || d.stiffness_Npm <= 0)
    return makeError("spring field 'stiffness' must be a finite number > 0 (N/m), got " + std::to_string(d.stiffness_Npm));
  if (!std::isfinite(d.damping_Nspm) || d.damping_Nspm < 0)
    return makeError("spring field 'damping' must be a finite number >= 0 (N s/m)");
  if (!std::isfinite(d.restLength_m)) return makeError("spring field 'rest_length' must be finite (m)");
  if (d.a == d.b) return makeError("spring fields 'a' and 'b' must be different bodies");
  return Ok{};
}

SpringEval springForce(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb, const Eigen::Vector3d& va,
                       const Eigen::Vector3d& vb, double k, double c, double rest, bool wantJacobian) {
  SpringEval e;
  const Eigen::Vector3d d = xb - xa;
  const double L = d.norm();
  const double stretch = L - rest;
  e.energy_J = 0.5 * k * stretch * stretch;
  if (L < 1e-12) {
    // Coincident ends: no direction. The force is zero; the stiffness is
    // isotropic k so Newton still sees the spring.
    if (wantJacobian) e.K = k * Eigen::Matrix3d::Identity();
    return e;
  }
  const Eigen::Vector3d u = d / L;
  e.force_N = (k * stretch + c * (vb - va).dot(u)) * u;
  if (wantJacobian) {
    const Eigen::Matrix3d uu = u * u.transpose();
    const double transverse = std::max(0.0, 1.0 - rest / L);
    e.K = k * (uu + transverse * (Eigen::Matrix3d::Identity() - uu));
    e.D = c * uu;
  }
  return e;
}

BodyIntegration::BodyIntegration() : m_scratch(std::make_unique<BodyIntegrationScratch>()) {}
BodyIntegration::~BodyIntegration() = default;

SpringId BodyIntegration::addSpring(const SpringDef& def) {
  std::uint32_t index;
  if (!m_free.empty()) {
    index = m_free.back();
    m_free.pop_back();
  } else {
    index = std::uint32_t(m_springs.size());
    m_springs.emplace_back();
  }
  Slot& s = m_springs[index];
  s.generation += 1;  // odd while alive: 0 stays the null handle's
  s.alive = true;
  s.def = def;
  ++m_springCount;
  return SpringId{index, s.generation};
}

bool BodyIntegration::isValid(SpringId id) const {
  return !id.isNull() && id.index < m_springs.size() && m_springs[id.index].alive &&
         m_springs[id.index].generation == id.generation;
}

bool BodyIntegration::removeSpring(SpringId id) {
  if (!isValid(id)) return false;
  Slot& s = m_springs[id.index];
  s.alive = false;
  ++s.generation;
  m_free.push_back(id.index);
  --m_springCount;
  return true;
}

const SpringDef& BodyIntegration::spring(SpringId id) const {
  TUMBLE_ASSERT(isValid(id), "stale or null SpringId; check BodyIntegration::isValid first");
  return m_springs[id.index].def;
}

Eigen::Vector3d BodyIntegration::advance(BodyIntegrator method, const World& world, std::span<const Body> bodies,
                                         const Vec3& g, Real h, std::span<Vec3> linear) {
  BodyIntegrationScratch& st = *m_scratch;
  const std::size_t n = bodies.size();
  auto moving = [&](std::uint32_t i) { return bodies[i].alive && bodies[i].isDynamic() && bodies[i].awake; };
  // Drop springs whose bodies are gone.
  for (std::uint32_t i = 0; i < m_springs.size(); ++i) {
    Slot& s = m_springs[i];
    if (s.alive && (!world.isValid(s.def.a) || (!s.def.b.isNull() && !world.isValid(s.def.b))))
      removeSpring(SpringId{i, s.generation});
  }
  // Groups: union-find over springs whose ends both move.
  st.parent.resize(n);
  std::iota(st.parent.begin(), st.parent.end(), 0u);
  auto find = [&](std::uint32_t x) {
    while (st.parent[x] != x) x = st.parent[x] = st.parent[st.parent[x]];
    return x;
  };
  for (const Slot& s : m_springs)
    if (s.alive && !s.def.b.isNull() && moving(s.def.a.index) && moving(s.def.b.index))
      st.parent[find(s.def.a.index)] = find(s.def.b.index);
  // Members sorted by group root (counting sort), so each group is a range.
  st.groupStart.assign(n + 1, 0);
  for (std::uint32_t i = 0; i < n; ++i)
    if (moving(i)) ++st.groupStart[find(i) + 1];
  for (std::size_t i = 0; i < n; ++i) st.groupStart[i + 1] += st.groupStart[i];
  st.members.resize(st.groupStart[n]);
  st.memberIndex.assign(n, -1);
  {
    std::vector<std::uint32_t>& cursor = st.groupOf;
    cursor.assign(st.groupStart.begin(), st.groupStart.end() - 1);
    for (std::uint32_t i = 0; i < n; ++i)
      if (moving(i)) {
        const std::uint32_t root = find(i);
        st.memberIndex[i] = int(cursor[root] - st.groupStart[root]);
        st.members[cursor[root]++] = i;
      }
  }
  st.dxFree.resize(n);
  st.vFree.resize(n);
  st.advanced.assign(n, 0);

  // Springs bucketed by the group of their moving end(s) (counting sort).
  auto springRoot = [&](const Slot& s) -> std::int64_t {
    if (!s.alive) return -1;
    if (moving(s.def.a.index)) return find(s.def.a.index);
    if (!s.def.b.isNull() && moving(s.def.b.index)) return find(s.def.b.index);
    return -1;  // neither end moves: nothing to integrate
  };
  st.springStart.assign(n + 1, 0);
  for (const Slot& s : m_springs)
    if (const std::int64_t r = springRoot(s); r >= 0) ++st.springStart[std::size_t(r) + 1];
  for (std::size_t i = 0; i < n; ++i) st.springStart[i + 1] += st.springStart[i];
  st.springIndex.resize(st.springStart[n]);
  st.cursor.assign(st.springStart.begin(), st.springStart.end() - 1);
  for (std::uint32_t k = 0; k < m_springs.size(); ++k)
    if (const std::int64_t r = springRoot(m_springs[k]); r >= 0) st.springIndex[st.cursor[std::size_t(r)]++] = k;

  Eigen::Vector3d externalImpulse = Eigen::Vector3d::Zero();
  const numerics::Method nm = toNumerics(method);
  for (std::uint32_t root = 0; root < n; ++root) {
    const std::uint32_t begin = st.groupStart[root], end = st.groupStart[root + 1];
    if (begin == end) continue;
    GroupSystem& sys = st.system;
    sys.n = int(end - begin);
    sys.invMass.resize(std::size_t(sys.n));
    sys.constAccel.resize(std::size_t(sys.n));
    sys.springs.clear();
    st.y.resize(6 * sys.n);
    for (int m = 0; m < sys.n; ++m) {
      const Body& b = bodies[st.members[begin + std::uint32_t(m)]];
      sys.invMass[std::size_t(m)] = b.invMass_per_kg;
      sys.constAccel[std::size_t(m)] = d3(g + b.invMass_per_kg * b.force_N);
      st.y.segment<3>(3 * m) = d3(b.position_m);
      st.y.segment<3>(3 * sys.n + 3 * m) = d3(linear[st.members[begin + std::uint32_t(m)]]);
    }
    // The group's springs: those with an end in it (bucketed below, so the
    // work is linear in springs + bodies).
    for (std::uint32_t k = st.springStart[root]; k < st.springStart[root + 1]; ++k) {
      const Slot& s = m_springs[st.springIndex[k]];
      const std::uint32_t ia = s.def.a.index;
      const bool bodyB = !s.def.b.isNull();
      const std::uint32_t ib = bodyB ? s.def.b.index : 0;
      const bool inA = moving(ia) && find(ia) == root;
      const bool inB = bodyB && moving(ib) && find(ib) == root;
      if (!inA && !inB) continue;
      GroupSpring gs;
      gs.k = s.def.stiffness_Npm;
      gs.c = s.def.damping_Nspm;
      gs.rest = s.def.restLength_m;
      gs.a = inA ? st.memberIndex[ia] : -1;
      gs.b = inB ? st.memberIndex[ib] : -1;
      if (!inA) gs.fixedA = d3(bodies[ia].position_m), gs.fixedVA = d3(bodies[ia].linearVelocity_mps);
      if (!inB) {
        gs.fixedB = bodyB ? d3(bodies[ib].position_m) : d3(s.def.anchor_m);
        if (bodyB && bodies[ib].moves()) gs.fixedVB = d3(bodies[ib].linearVelocity_mps);
      }
      if (!inA || !inB) {
        // External: the force on the moving end at the start of the substep.
        const Eigen::Vector3d xa = inA ? Eigen::Vector3d(st.y.segment<3>(3 * gs.a)) : gs.fixedA;
        const Eigen::Vector3d xb = inB ? Eigen::Vector3d(st.y.segment<3>(3 * gs.b)) : gs.fixedB;
        const Eigen::Vector3d va = inA ? Eigen::Vector3d(st.y.segment<3>(3 * sys.n + 3 * gs.a)) : gs.fixedVA;
        const Eigen::Vector3d vb = inB ? Eigen::Vector3d(st.y.segment<3>(3 * sys.n + 3 * gs.b)) : gs.fixedVB;
        const Eigen::Vector3d f = springForce(xa, xb, va, vb, gs.k, gs.c, gs.rest, false).force_N;
        externalImpulse += double(h) * (inA ? f : Eigen::Vector3d(-f));
      }
      sys.springs.push_back(gs);
    }
    auto& integrator = st.integrators[{int(nm), 6 * sys.n}];
    if (!integrator) integrator = std::make_unique<numerics::Integrator>(nm, 6 * sys.n);
    const numerics::StepInfo info = integrator->step(sys, 0.0, st.y, double(h));
    if (!info.converged) ++m_newtonFailures;
    for (int m = 0; m < sys.n; ++m) {
      const std::uint32_t i = st.members[begin + std::uint32_t(m)];
      const Vec3 x1 = st.y.segment<3>(3 * m).cast<Real>();
      const Vec3 v1 = st.y.segment<3>(3 * sys.n + 3 * m).cast<Real>();
      st.dxFree[i] = x1 - bodies[i].position_m;
      st.vFree[i] = v1;
      st.advanced[i] = 1;
      linear[i] = v1;
    }
  }
  return externalImpulse;
}

Vec3 BodyIntegration::displacement(std::uint32_t index, const Vec3& vNow, Real h) const {
  const BodyIntegrationScratch& st = *m_scratch;
  if (index >= st.advanced.size() || !st.advanced[index]) return h * vNow;
  return st.dxFree[index] + h * (vNow - st.vFree[index]);
}

double BodyIntegration::springEnergy(const World& world) const {
  double e = 0;
  for (const Slot& s : m_springs) {
    if (!s.alive || !world.isValid(s.def.a)) continue;
    if (!s.def.b.isNull() && !world.isValid(s.def.b)) continue;
    const Eigen::Vector3d xa = d3(world.body(s.def.a).position_m);
    const Eigen::Vector3d xb = s.def.b.isNull() ? d3(s.def.anchor_m) : d3(world.body(s.def.b).position_m);
    const double stretch = (xb - xa).norm() - s.def.restLength_m;
    e += 0.5 * s.def.stiffness_Npm * stretch * stretch;
  }
  return e;
}

}  // namespace tumble::physics
