// The Lagrange-multiplier joint solver: the constraint forces of every joint
// from one sparse linear system (after Baraff 1996). The substep driver that
// runs it inside World::step is lagrange_substeps.cpp; integrateFree, the
// joint-only integrator, free_integration.cpp.
//
// ---- Derivation (Baraff, "Linear-time dynamics using Lagrange multipliers",
//      SIGGRAPH 1996) --------------------------------------------------------
// Stack the bodies' velocities q' = (v_1, w_1, ..., v_n, w_n) (centre-of-mass
// velocity and world angular velocity, 6 per body). Newton-Euler reads
//   M q'' = Q + J^T lambda,
// M = diag(m_i 1, I_i) (I_i = R_i I_local R_i^T), W = M^-1, Q the applied
// generalized forces: gravity m g and other forces F on the centre, torques
// tau minus the gyroscopic term w x (I w). J^T lambda is the constraint force,
// one multiplier per constraint row. A joint is a set of rows C(x) = 0 with
// C' = J q'. Differentiating once more, C'' = J q'' + J' q'. Demanding
// C'' = 0 lets errors drift; Baumgarte's feedback asks instead for
//   C'' = -k_s C - k_d C'      (a critically damped spring on the error),
// and substituting q'' = W (Q + J^T lambda):
//   J W J^T lambda = -J' q' - J W Q - k_s C - k_d C'.
// J W J^T is symmetric positive definite when the rows are independent, so
// it is factorized by Cholesky (LDL^T).
//
// Rows: each joint type's are in its own file with their C, J and J' q'
// (ball_joint.cpp: the point rows every type has; hinge_joint.cpp,
// cone_twist_joint.cpp, fixed_joint.cpp), built with RowBuilder
// (internal/lagrange_solver.h) and picked by the type table
// (internal/joint_types.h).
// Inequality rows (limits) use a simple active set: a limit row is added
// when its C < 0 (violated); after the solve, rows whose lambda < 0 (they
// would pull the joint into the limit) are dropped and the system solved
// again (at most JointSettings::maxActiveSetIterations times).
//
// Soft joints: the equality rows of a joint with a stiffness are not solved
// for; their lambda = -k C - c C' is an explicit spring force, added to Q
// before the hard rows are solved (so hard rows see the springs).
//
// Hinge motors are not rows but an explicit servo torque in Q (hinge_joint.cpp).
//
// The order of the joints (elimination_order.cpp) makes the factorization
// of J W J^T linear in the number of joints for chains and trees.
#include "physics/internal/lagrange_solver.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "physics/internal/joint_types.h"
#include "physics/world.h"

namespace tumble::physics::lagrange {

JointPose poseOf(const Vec3& localAnchor, const Quat& localFrame, const BodyState* b) {
  JointPose p;
  if (!b) {  // world: the local values are world values
    p.p = wide3(localAnchor);
    p.F = localFrame.cast<double>().toRotationMatrix();
    return p;
  }
  p.r = b->R * wide3(localAnchor);
  p.p = b->x + p.r;
  p.F = b->R * localFrame.cast<double>().toRotationMatrix();
  p.w = b->w;
  p.v = b->v;
  return p;
}

BodyState stateFromWorld(const World& world, BodyId id) {
  BodyState s;
  const Body& b = world.body(id);
  s.id = id;
  s.dynamic = b.isDynamic() && b.awake;
  s.mass = b.mass_kg;
  s.invMass = s.dynamic ? double(b.invMass_per_kg) : 0;
  s.inertiaLocal = wide3(b.inertiaLocal_kgm2);
  s.x = wide3(b.position_m);
  s.q = b.orientation.cast<double>().normalized();
  s.v = wide3(b.linearVelocity_mps);
  s.w = wide3(b.angularVelocity_radps);
  s.extForce = wide3(b.force_N);
  s.extTorque = wide3(b.torque_Nm);
  return s;
}

void deriveStates(std::vector<BodyState>& states, const JointSettings& js, const V3& gravity, bool includeExternal) {
  for (BodyState& s : states) {
    s.R = s.q.toRotationMatrix();
    const M3 I = s.R * s.inertiaLocal.asDiagonal() * s.R.transpose();
    s.invI = s.dynamic ? M3(s.R * s.inertiaLocal.cwiseInverse().asDiagonal() * s.R.transpose()) : M3::Zero();
    s.Qf = s.mass * gravity;
    s.Qt = js.gyroscopic ? V3(-s.w.cross(I * s.w)) : V3::Zero();
    if (includeExternal) s.Qf += s.extForce, s.Qt += s.extTorque;
    s.Fc.setZero();
    s.Tc.setZero();
    s.Tm.setZero();
  }
}

void buildRows(const Evaluation& ev, std::vector<BodyState>& states, std::vector<Row>& rows) {
  rows.clear();
  for (std::size_t k = 0; k < ev.defs.size(); ++k) {
    const JointDef& d = *ev.defs[k];
    const JointTypeRows& type = jointTypeRows(d.type);
    const auto [ia, ib] = ev.bodies[k];
    const BodyState* A = ia >= 0 ? &states[ia] : nullptr;
    const BodyState* B = ib >= 0 ? &states[ib] : nullptr;
    RowBuilder rb{rows, ev.slots[k], ia, ib, A, B};
    const JointPose pa = poseOf(d.localAnchorA_m, d.localFrameA, A);
    const JointPose pb = poseOf(d.localAnchorB_m, d.localFrameB, B);
    const std::size_t first = rows.size();
    lagrangePointRows(rb, pa, pb);
    if (type.lagrangeEquality) type.lagrangeEquality(rb, pa, pb);
    const bool soft = d.linearStiffness_Npm > 0;
    for (std::size_t r = first; r < rows.size(); ++r) {
      rows[r].soft = soft;
      rows[r].k = rows[r].angular ? d.angularStiffness_Nmprad : d.linearStiffness_Npm;
      rows[r].d = rows[r].angular ? d.angularDamping_Nmsprad : d.linearDamping_Nspm;
    }
    if (type.lagrangeLimits) type.lagrangeLimits(rb, d, pa, pb);
  }
  for (Row& r : rows) {
    V6 qa = V6::Zero(), qb = V6::Zero();
    if (r.a >= 0) qa << states[r.a].v, states[r.a].w;
    if (r.b >= 0) qb << states[r.b].v, states[r.b].w;
    r.cdot = r.ja.dot(qa) + r.jb.dot(qb);
  }
}

void addMotorTorques(const Evaluation& ev, std::vector<BodyState>& st, const JointSettings& js) {
  for (std::size_t k = 0; k < ev.defs.size(); ++k) {
    const JointDef& d = *ev.defs[k];
    const JointTypeRows& type = jointTypeRows(d.type);
    if (!type.lagrangeMotor) continue;
    const auto [ia, ib] = ev.bodies[k];
    type.lagrangeMotor(d, ia >= 0 ? &st[ia] : nullptr, ib >= 0 ? &st[ib] : nullptr, js);
  }
}

int numberSolvedRows(JointSystem::Impl& im) {
  const std::vector<BodyState>& st = im.states;
  int m = 0;
  im.bodyRows.assign(st.size(), {});
  for (std::size_t r = 0; r < im.rows.size(); ++r) {
    Row& row = im.rows[r];
    row.index = -1;
    if (row.soft || !row.active) continue;
    const bool da = row.a >= 0 && st[row.a].dynamic, db = row.b >= 0 && st[row.b].dynamic;
    if (!da && !db) continue;
    row.index = m++;
    if (da) im.bodyRows[row.a].push_back(int(r));
    if (db) im.bodyRows[row.b].push_back(int(r));
  }
  return m;
}

namespace {

/// The diagonal of A^-1 from A's factor L D L^T (Takahashi's recurrence,
/// Z = A^-1 = D^-1 L^-1 + (I - L^T) Z, evaluated only on the pattern of L:
/// for a chordal pattern, as ours are, every Z_jk it needs is on it). From
/// the last column back: Z_ji = -sum_k L_ki Z_jk, Z_ii = 1 / D_i - sum_k
/// L_ki Z_ki, k over column i of L. Cost O(sum of squared column counts):
/// linear in the links for chains and trees, like the factorization.
void inverseDiagonal(const JointSystem::Impl::Factor& f, int m, std::vector<double>& zdiag,
                            std::vector<double>& zval) {
  const auto& L = f.ldlt.matrixL().nestedExpression();  // strictly lower, column-major, rows sorted
  const auto& D = f.ldlt.vectorD();
  const int* Lp = L.outerIndexPtr();
  const int* Li = L.innerIndexPtr();
  const double* Lx = L.valuePtr();
  zdiag.assign(std::size_t(m), 0);
  zval.assign(std::size_t(Lp[m]), 0);
  auto z = [&](int j, int k) {
    if (j == k) return zdiag[std::size_t(j)];
    const int col = std::min(j, k), row = std::max(j, k);
    const int* end = Li + Lp[col + 1];
    const int* it = std::lower_bound(Li + Lp[col], end, row);
    return it != end && *it == row ? zval[std::size_t(it - Li)] : 0.0;
  };
  for (int i = m - 1; i >= 0; --i) {
    double diag = 1 / D[i];
    for (int p = Lp[i]; p < Lp[i + 1]; ++p) {
      double sum = 0;
      for (int q = Lp[i]; q < Lp[i + 1]; ++q) sum += Lx[q] * z(Li[p], Li[q]);
      zval[std::size_t(p)] = -sum;
    }
    for (int p = Lp[i]; p < Lp[i + 1]; ++p) diag -= Lx[p] * zval[std::size_t(p)];
    zdiag[std::size_t(i)] = diag;
  }
}

}  // namespace

bool assembleAndFactorize(JointSystem::Impl& im, int m, JointSolveStats& stats, double compliance,
                          double maxWorkPerRow) {
  if (!assembleWithinCost(im, m, stats, maxWorkPerRow)) return false;
  factorizeAssembled(im, m, stats, compliance);
  return true;
}

bool assembleWithinCost(JointSystem::Impl& im, int m, JointSolveStats& stats, double maxWorkPerRow) {
  const double maxWork = maxWorkPerRow * m;
  JointSystem::Impl::Factor& f = im.factor;
  const std::vector<BodyState>& st = im.states;
  const std::vector<Row>& rows = im.rows;
  // The cost cap (JointSettings::lagrangeMaxFactorWorkPerRow). The rows on
  // one body are all coupled, so A's lower triangle has up to
  // sum r_b (r_b + 1) / 2 entries, and the factor's work is at least that:
  // checked before the triplets are even made (a body with 10 000 ball
  // joints would need 4.5e8).
  double entries = 0;
  for (const std::vector<int>& list : im.bodyRows) entries += 0.5 * double(list.size()) * double(list.size() + 1);
  if (entries > maxWork) {
    stats.factorWork = entries;
    return false;
  }
  im.triplets.clear();
  for (std::size_t b = 0; b < st.size(); ++b) {
    const BodyState& s = st[b];
    const std::vector<int>& list = im.bodyRows[b];
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Row& ri = rows[list[i]];
      const V6& Ji = ri.a == int(b) ? ri.ja : ri.jb;
      V6 WJi;
      WJi << s.invMass * Ji.head<3>(), s.invI * Ji.tail<3>();
      for (std::size_t k = 0; k <= i; ++k) {
        const Row& rk = rows[list[k]];
        const V6& Jk = rk.a == int(b) ? rk.ja : rk.jb;
        im.triplets.emplace_back(std::max(ri.index, rk.index), std::min(ri.index, rk.index), Jk.dot(WJi));
      }
    }
  }
  f.A.resize(m, m);
  f.A.setFromTriplets(im.triplets.begin(), im.triplets.end());
  // The symbolic analysis (elimination tree, column counts) depends only on
  // the pattern: redone only when the rows changed (joints, active limits).
  const int* outer = f.A.outerIndexPtr();
  const int* inner = f.A.innerIndexPtr();
  const bool samePattern = f.patternOuter.size() == std::size_t(m) + 1 &&
                           std::equal(outer, outer + m + 1, f.patternOuter.begin()) &&
                           f.patternInner.size() == std::size_t(outer[m]) &&
                           std::equal(inner, inner + outer[m], f.patternInner.begin());
  if (!samePattern) {
    f.ldlt.analyzePattern(f.A);
    f.patternOuter.assign(outer, outer + m + 1);
    f.patternInner.assign(inner, inner + outer[m]);
    ++stats.patternAnalyses;
    // The symbolic analysis sized L: column j holds c_j entries below the
    // diagonal, and the factorization (and the inverse diagonal of the
    // compliance) costs about sum (c_j + 1)^2 multiply-adds.
    const int* Lp = f.ldlt.analysedColumnStarts();
    double work = 0;
    for (int j = 0; j < m; ++j) work += double(Lp[j + 1] - Lp[j] + 1) * double(Lp[j + 1] - Lp[j] + 1);
    f.work = work;
  }
  stats.factorWork = f.work;
  return f.work <= maxWork;
}

void factorizeAssembled(JointSystem::Impl& im, int m, JointSolveStats& stats, double compliance) {
  JointSystem::Impl::Factor& f = im.factor;
  f.ldlt.factorize(f.A);
  ++stats.factorizations;
  if (f.ldlt.info() != Eigen::Success) {
    // Redundant rows (a loop of joints, two joints on one pair): a tiny
    // compliance on the diagonal makes the system definite again (the
    // diagonal is stored, so the pattern does not change).
    double trace = 0;
    for (int i = 0; i < m; ++i) trace += f.A.coeff(i, i);
    for (int i = 0; i < m; ++i) f.A.coeffRef(i, i) += 1e-9 * trace / m;
    f.ldlt.factorize(f.A);
    ++stats.factorizations;
  }
  if (compliance > 0) {
    // Compliance relative to the whole system along each row: row i's
    // diagonal grows by compliance / (A^-1)_ii, where 1 / (A^-1)_ii is the
    // inverse effective mass the row sees with every other row holding (the
    // Schur complement). For the top link of a hanging chain that is the
    // whole chain's mass, not the link's: see "Robustness" in lagrange_substeps.cpp.
    std::vector<double>& zdiag = im.inverseDiagonal;
    inverseDiagonal(f, m, zdiag, im.inverseValues);
    for (const Row& r : im.rows) {
      if (r.index < 0) continue;
      const int i = r.index;
      const double aii = f.A.coeff(i, i);
      const double own = compliance * aii;
      const double system = zdiag[i] > 0 && std::isfinite(zdiag[i]) ? std::min(compliance / zdiag[i], own) : own;
      f.A.coeffRef(i, i) = aii + (r.touched ? own : system);  // the diagonal is stored: same pattern
    }
    f.ldlt.factorize(f.A);
    ++stats.factorizations;
  }
  stats.nonZerosA = long(f.A.nonZeros()) - m;
  stats.nonZerosL = long(f.ldlt.matrixL().nestedExpression().nonZeros());
  // Fill-in: entries of L beyond those of A's strictly lower triangle.
  stats.fillIn = std::max(0L, stats.nonZerosL - stats.nonZerosA);
}

// Computes the constraint forces (states[i].Fc, Tc) for the given states.
// Returns the joints (slot indices) that broke, with their force and torque.
std::vector<JointBreakEvent> solveConstraints(JointSystem::Impl& im, const JointSettings& js, const V3& gravity,
                                              bool includeExternal, JointSolveStats& stats) {
  const Evaluation& ev = im.ev;
  std::vector<BodyState>& st = im.states;
  deriveStates(st, js, gravity, includeExternal);
  buildRows(ev, st, im.rows);
  std::vector<Row>& rows = im.rows;
  addMotorTorques(ev, st, js);
  std::vector<char> broken(ev.defs.size(), 0);  // per evaluation joint
  std::vector<JointBreakEvent> events;
  std::vector<int> jointOf(rows.size());
  {
    // rows are grouped by joint in evaluation order
    std::size_t k = 0;
    for (std::size_t r = 0; r < rows.size(); ++r) {
      while (ev.slots[k] != rows[r].joint) ++k;
      jointOf[r] = int(k);
    }
  }
  const std::vector<V3> baseQf = [&] {
    std::vector<V3> q(st.size());
    for (std::size_t i = 0; i < st.size(); ++i) q[i] = st[i].Qf;
    return q;
  }();
  const std::vector<V3> baseQt = [&] {
    std::vector<V3> q(st.size());
    for (std::size_t i = 0; i < st.size(); ++i) q[i] = st[i].Qt;
    return q;
  }();
  stats.factorizations = 0;
  for (int iter = 0; iter <= std::max(0, js.maxActiveSetIterations) + int(ev.defs.size()); ++iter) {
    // Springs (soft rows) go into Q.
    for (std::size_t i = 0; i < st.size(); ++i) st[i].Qf = baseQf[i], st[i].Qt = baseQt[i];
    for (Row& r : rows) {
      if (!r.soft || !r.active) continue;
      r.lambda = -(r.k * r.c + r.d * r.cdot);
      scatterRow(r, r.lambda, [&](int b, const V6& f) {
        st[b].Qf += f.head<3>();
        st[b].Qt += f.tail<3>();
      });
    }
    const int m = numberSolvedRows(im);
    stats.rows = m;
    if (m > 0) {
      // rhs = -J'q' - J W Q - k_s C - k_d C'.
      im.rhs.resize(m);
      for (const Row& r : rows)
        if (r.index >= 0) im.rhs[r.index] = -r.jdq - js.stiffness_per_s2 * r.c - js.damping_per_s * r.cdot;
      for (std::size_t b = 0; b < st.size(); ++b) {
        const BodyState& s = st[b];
        V6 WQ;
        WQ << s.invMass * s.Qf, s.invI * s.Qt;
        for (int r : im.bodyRows[b]) {
          const Row& row = rows[r];
          im.rhs[row.index] -= (row.a == int(b) ? row.ja : row.jb).dot(WQ);
        }
      }
      assembleAndFactorize(im, m, stats);
      im.lambda = im.factor.ldlt.solve(im.rhs);
      for (Row& r : rows)
        if (r.index >= 0) r.lambda = im.lambda[r.index];
    }
    // Active set: drop limit rows that pull.
    bool changed = false;
    if (iter < js.maxActiveSetIterations)
      for (Row& r : rows)
        if (r.limit && r.index >= 0 && r.lambda < 0) r.active = false, changed = true;
    if (changed) continue;
    // Breakable joints.
    std::vector<V3>& force = im.jointForce;
    std::vector<V3>& torque = im.jointTorque;
    force.assign(ev.defs.size(), V3::Zero());
    torque.assign(ev.defs.size(), V3::Zero());
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const Row& row = rows[r];
      if (!row.active || (row.index < 0 && !row.soft)) continue;
      if (row.angular) torque[jointOf[r]] += row.lambda * row.ja.tail<3>();
      else force[jointOf[r]] += row.lambda * row.ja.head<3>();
    }
    bool anyBroken = false;
    for (std::size_t k = 0; k < ev.defs.size(); ++k) {
      const JointDef& d = *ev.defs[k];
      if (broken[k]) continue;
      const double f = force[k].norm(), t = torque[k].norm();
      if ((d.breakForce_N > 0 && f > d.breakForce_N) || (d.breakTorque_Nm > 0 && t > d.breakTorque_Nm)) {
        broken[k] = 1;
        anyBroken = true;
        JointBreakEvent e;
        e.id.index = ev.slots[k];
        e.a = d.bodyA;
        e.b = d.bodyB;
        e.force_N = f;
        e.torque_Nm = t;
        e.userData = d.userData;
        events.push_back(e);
      }
    }
    if (anyBroken) {
      for (std::size_t r = 0; r < rows.size(); ++r)
        if (broken[jointOf[r]]) rows[r].active = false;
      continue;
    }
    break;
  }
  // Constraint forces: soft and hard rows.
  for (const Row& r : rows) {
    if (!r.active || (r.index < 0 && !r.soft)) continue;
    scatterRow(r, r.lambda, [&](int b, const V6& f) {
      if (!st[b].dynamic) return;
      st[b].Fc += f.head<3>();
      st[b].Tc += f.tail<3>();
    });
  }
  return events;
}

}  // namespace tumble::physics::lagrange

namespace tumble::physics {

using namespace lagrange;

// The joints in elimination order and their bodies, as the World has them now.
void JointSystem::prepare() {
  Impl& im = *m_impl;
  refreshLinks();
  Evaluation& ev = im.ev;
  ev.defs.clear();
  ev.slots.clear();
  ev.generations.clear();
  ev.bodies.clear();
  for (BodyState& s : im.states)
    if (s.id.index < im.slotOf.size()) im.slotOf[s.id.index] = -1;
  im.states.clear();
  auto stateOf = [&](BodyId id) -> int {
    if (id.isNull()) return -1;
    if (id.index >= im.slotOf.size()) im.slotOf.resize(id.index + 1, -1);
    int& k = im.slotOf[id.index];
    if (k < 0) {
      k = int(im.states.size());
      im.states.push_back(stateFromWorld(m_world, id));
    }
    return k;
  };
  for (std::uint32_t slot : im.order) {
    Slot& s = m_slots[slot];
    ev.defs.push_back(&s.def);
    ev.slots.push_back(slot);
    ev.generations.push_back(s.generation);
    ev.bodies.emplace_back(stateOf(s.def.bodyA), stateOf(s.def.bodyB));
  }
}

// The cost cap (JointSettings::lagrangeMaxFactorWorkPerRow) for the joints as they
// are now, before a step: every equality row and the limit rows violated now.
bool JointSystem::lagrangeFitsCostCap() {
  if (m_jointCount == 0 || !dropJointsOfDeadBodies()) return true;
  prepare();
  Impl& im = *m_impl;
  deriveStates(im.states, m_settings, V3::Zero(), false);
  buildRows(im.ev, im.states, im.rows);
  const int m = numberSolvedRows(im);
  if (m == 0) return true;
  JointSolveStats stats;
  const bool fits = assembleWithinCost(im, m, stats, m_settings.lagrangeMaxFactorWorkPerRow);
  if (!fits) m_overCostCapWorkPerRow = stats.factorWork / m;
  return fits;
}

// Post-stabilization (JointSettings::postStabilize; Cline and Pai 2003):
// velocities and positions projected back onto the joints with the same
// sparse matrix.
void JointSystem::postStabilize() {
  if (m_jointCount == 0 || !dropJointsOfDeadBodies()) return;
  prepare();
  Impl& im = *m_impl;
  deriveStates(im.states, m_settings, V3::Zero(), false);
  buildRows(im.ev, im.states, im.rows);
  // Equality rows, and the limit rows that are violated (buildRows adds no
  // others): those act as inelastic stops, J dv = -min(C', 0), dC = -C; a
  // stop whose multiplier comes out negative (it would pull) is dropped and
  // the projection solved again. Springs are soft: not projected.
  JointSolveStats stats;
  Eigen::VectorXd mu, nu;
  for (int pass = 0; pass < 3; ++pass) {
    const int m = numberSolvedRows(im);
    if (m == 0) return;
    if (!assembleAndFactorize(im, m, stats, 0, m_settings.lagrangeMaxFactorWorkPerRow)) return;  // over the cost cap: beforeWorldStep runs the impulse solver
    Eigen::VectorXd cdot(m), c(m);
    for (const Row& r : im.rows)
      if (r.index >= 0) cdot[r.index] = r.limit ? -std::min(r.cdot, 0.0) : -r.cdot, c[r.index] = -r.c;
    mu = im.factor.ldlt.solve(cdot);
    nu = im.factor.ldlt.solve(c);
    if (pass == 2) break;
    bool changed = false;
    for (Row& r : im.rows)
      if (r.limit && r.index >= 0 && (mu[r.index] < 0 || nu[r.index] < 0)) r.active = false, changed = true;
    if (!changed) break;
  }
  // dq = W J^T mu (velocities), W J^T nu (positions): the smallest changes in
  // the mass metric that make J v = 0 and, to first order, C = 0.
  std::vector<V6> dv(im.states.size(), V6::Zero()), dx(im.states.size(), V6::Zero());
  for (const Row& r : im.rows) {
    if (r.index < 0) continue;
    if (r.a >= 0) dv[r.a] += r.ja * mu[r.index], dx[r.a] += r.ja * nu[r.index];
    if (r.b >= 0) dv[r.b] += r.jb * mu[r.index], dx[r.b] += r.jb * nu[r.index];
  }
  for (std::size_t i = 0; i < im.states.size(); ++i) {
    const BodyState& s = im.states[i];
    if (!s.dynamic) continue;
    const V3 v = s.v + s.invMass * dv[i].head<3>(), w = s.w + s.invI * dv[i].tail<3>();
    const V3 x = s.x + s.invMass * dx[i].head<3>(), th = s.invI * dx[i].tail<3>();
    Qd q = s.q;
    q.coeffs() += 0.5 * (Qd(0, th.x(), th.y(), th.z()) * s.q).coeffs();
    // wake = false: only awake bodies are projected, and the projection
    // must not restart their sleep timers (it runs every step).
    if (m_settings.projectPositions) {
      m_world.setPosition(s.id, x.cast<Real>(), false);
      m_world.setOrientation(s.id, q.normalized().cast<Real>(), false);
    }
    m_world.setLinearVelocity(s.id, v.cast<Real>(), false);
    m_world.setAngularVelocity(s.id, w.cast<Real>(), false);
    // The projection is the joints' own update: the next substep solve
    // starts from it (the memo) rather than resisting it as a force.
    if (s.id.index >= im.memo.size()) im.memo.resize(s.id.index + 1);
    im.memo[s.id.index] = Impl::Memo{s.id.generation, im.serial, V3(v.cast<Real>().cast<double>()),
                                     V3(w.cast<Real>().cast<double>())};
  }
}

}  // namespace tumble::physics
