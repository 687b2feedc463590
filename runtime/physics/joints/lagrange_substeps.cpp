// The Lagrange-multiplier joint solver inside World::step: its substep
// driver, called through the World's ConstraintSolver hook
// (LagrangeSubsteps). The system it solves is derived in lagrange_solver.cpp.
//
// ---- Time stepping ------------------------------------------------------------
// With the World (JointSystem::step, or beforeWorldStep + World::step): the
// multipliers are solved in every World substep, through the World's
// ConstraintSolver hook (LagrangeSubsteps), at the substep's state:
// poses as integrated so far, after the World's free step (gravity, applied
// forces, springs, gyroscopic term, by whichever integrator it runs) and the
// contacts' warm start. Let q'_J be the velocity the joints left at their
// last solve (a per-body memo) and v_k the velocity handed over now.
// Everything that changed v since, v_k - q'_J, is the known force: h W Q.
// With C' = J q'_J, the paper's equation times h is
//   J W J^T (h lambda) = target - J v_k,
//   target = (C' - h (J'q'_J + k_s C)) / (1 + h k_d + h^2 k_s),
// and v = v_k + W J^T (h lambda). The target is Baumgarte's C'' = -k_s C -
// k_d C' over the substep, with C and C' taken at the end of the substep
// (backward Euler on the error dynamics). Taken at its start, (1 - h k_d) C'
// - h (J'q' + k_s C), a 10-link chain released horizontally gained 6.6 % of
// its m g L in 10 s and blew up with 4 substeps; implicit, it never gains
// and holds with 1 substep. Limit rows carry max(C', 0): they stop the
// approach inelastically. One factorization per substep (8 per step); the
// pattern is analysed once and reused while the rows stay the same. The
// projections between and after the contact sweeps (see "Robustness")
// reuse that factorization: one back-substitution each.
// What changed, and why. Before, lambda was solved once per step and held
// as a force through the 8 substeps: a free chain whose links do not touch
// blew up (base:chain, WILL_FAIL), and the contacts were not in Q (10.3 cm
// on ragdoll_pile). Now the contacts' impulses of the substep before (their
// warm start, in v_k) are known forces, W comes from the substep's poses,
// and: chain 3.7 mm, 100 links 2.2 cm, ragdoll_pile 2.6 cm, asleep.
// Measured and rejected (ragdoll_pile, stairs, hit, 10 piled dolls):
//   - the joints solved once per substep only, before the contact sweeps
//     (the version before "Robustness" below): see there;
//   - the joints re-projected between the contact sweeps with W taken as
//     the contact rows take it (step start): a
//     chain link spun to 130 rad/s by a grab got joint impulses that do work;
//   - q' after the contacts instead of q'_J (so that the contacts' impulse
//     is a velocity, not a force): the pile and the hit blew up;
//   - the post-stabilization projection at every step: the contacts then
//     push back into the projected parts (a head jittering on the stairs);
//     it now runs only when a joint or a jointed body is new to the solver
//     (a link added to a swinging chain: 13.7 cm without, 8 mm with);
//   - larger gains (k_s, k_d): smaller errors on chains (100 links 2.2 cm
//     -> 1.4 cm at (1600, 80), 0.8 cm at (14400, 240); a grabbed chain 8.8
//     -> 2.2 cm), but (1600, 80) blew up 6 piled dolls and a 20 m/s
//     ragdoll_hit, (3600, 120) that hit too, and (14400, 240) opened the
//     stairs doll by 7.3 cm. The defaults (400, 40), those of the stability
//     table, blew up none of these scenes.
//
// ---- Robustness (piles of rag-dolls) ------------------------------------------------
// Symptom: 10 dolls piled (ragdoll_pile --set count=10) blew up (NaN, anchor
// error 1e8 m) or ended at 16.6 cm depending only on the rounding of the
// World's gyroscopic step (LU or closed-form 3x3 inverse); 12 dolls, dt 1/30
// or 4 substeps blew up as well. Traced body by body, two causes:
//  1. The hinge and fixed joints' angular rows were "dot" rows, C = u.w
//     with J = u x w. |J| = sin of the angle between u and w: where the
//     joint is twisted so that u.w nears +-1 the row loses rank. In the pile
//     elbows were bent 60-90 degrees off their axis (|J| down to 0.045); a
//     row that cannot pull the joint back asks, through Baumgarte, for
//     velocities ~ 1/|J|: a forearm spun to 46 rad/s at rest, then 275 rad/s,
//     then NaN (t = 6.05 s). Fix: "axis" rows, J = an axis fixed in A (never
//     zero), C = the same angle error (sin, or the relative rotation vector
//     for the fixed joint). The cone limit keeps its dot row (u.w there is
//     cos(swingLimit), far from +-1).
//  2. The contacts, solved after the joints in each substep, had the last
//     word on the velocities the positions move with, and the joints saw
//     their impulses one substep late. A contact treats a part as free: a
//     forearm's axial inertia is 0.95 g m^2, so friction at its surface spun
//     it by 200-1000 rad/s in one substep (up to 1 rad of twist before the
//     joints could answer). The joints then cancelled that as a known force,
//     the contacts pushed harder: hard rows against hard contacts raise each
//     other without limit, and the J'q' term, quadratic in w, turned the
//     growth super-exponential (157, 561, 1.9e3, 4e4, 6e6 rad/s). Hinges
//     ended 50-120 degrees off axis even where nothing blew up. Fix, three
//     parts, each measured:
//     - joints and contacts take turns between the contact sweeps (block
//       Gauss-Seidel, substepProject; before, only when a joint's own two
//       bodies collided), and the joints have the last word before the
//       positions are integrated (ConstraintSolver::beforeIntegrate): 10
//       dolls' hinges stay within 0.5 degree at rest (were 50-120);
//     - the relax sweeps drop the Baumgarte feedback (limits: no
//       approach), like the contacts' relax: the Baumgarte velocity that
//       moved the positions does not stay in the velocity (coupled with the
//       Baumgarte target in the relax sweeps too: the stairs doll stuck on
//       a step, its 'tumbled down' expectation failed). They keep the
//       curvature term -h/2 J'q' (see "Relax target" in substepProject);
//       with J v = 0 there a swinging pendulum lost energy;
//     - a compliance on the rows' diagonal (JointSettings::compliance,
//       1 %): where contacts and joints cannot both hold, the impulses stay
//       bounded (without it: 12 dolls 10 cm, with 6.8 cm; ragdoll_stairs
//       not at rest, 0.19 m/s). Scaled how, measured (tumble_bench_joints,
//       hanging chains of 10 / 100 / 1000 links; 12 um / 55 um / 21 um
//       rigid):
//       * 1 % of each row's own J W J^T diagonal everywhere (the first
//         version): 43 um / 7.7 mm / 13 cm. The own diagonal is the links'
//         mass, but the top joint of a chain carries the whole chain: the
//         error a compliance eps lets through is eps * lambda per substep,
//         and lambda grows with the load;
//       * only in substeps where contacts touched a jointed body, rigid
//         otherwise: chains back to rigid, but then the dolls of a pile
//         fall rigid and land with the compliance switching on mid-impact:
//         elbows up to 87-155 degrees off their axis during the impacts
//         (the 10-doll and the perturbation tests failed), and the stairs
//         doll missed "at rest" (the earlier measurement);
//       * relative to the whole system along the row: eps_i = 1 % of
//         1 / (A^-1)_ii, the inverse effective mass row i sees with all the
//         other rows holding (for a chain's top joint the whole chain).
//         eps * lambda no longer grows with the load. (A^-1)_ii comes from
//         the factor by Takahashi's recurrence on L's pattern
//         (inverseDiagonal; linear for trees like the factorization), then
//         A + eps is factorized again: one more numeric factorization per
//         substep (1000 links: solve 11.1 ms per step, 8.6 ms before, 6.9
//         rigid). Alone, this is too stiff for piles (10 dolls: elbows 42
//         degrees off axis during the impacts, test bound 30);
//       * kept: both. Rows of an assembly (bodies connected by joints) that
//         a contact moved in the last second (kContactMemory_s; detected
//         as a velocity that is not what the joints wrote before the
//         contact sweep) keep 1 % of their own diagonal, switched on at the
//         first contact sweep that touches them (not the next substep);
//         all other rows get 1 % of the system's. Chains 12 um / 49 um /
//         1.1 mm; 10 dolls 4.3 cm, elbows 17 degrees at most, 0.1 at the
//         end; ragdoll_stairs 4.7 cm and at rest at dt 1/60 (with one
//         step of memory instead of 1 s: 10.5 cm, not at rest: the doll
//         switched at every bounce). A chain whose links collide with each
//         other counts as touched and sags as before (7.7 mm at 100
//         links): disable collision between jointed neighbours.
//     The gyroscopic step was not the cause (it only picked which run blew
//     up): the closed-form inverse stays. Clamping the J'q' term (its exact
//     change over a substep, bounded in w) removed NaN but doubled the errors
//     (13-26 cm); rejected. Coupling without the last word made the pile
//     finite but left the hinges twisted and the stairs doll stuck.
//   Measured (tumble run base:ragdoll_pile --set physics.joint_solver=
//   lagrange --seconds 8, joint_error_max_m, closed-form / LU gyroscopic
//   step): count 3..12: 1.2/1.2, 2.5/2.5, 3.2/3.2, 4.5/3.7, 5.7/5.3,
//   7.3/5.3, 5.0/3.4, 6.4/4.9, 7.1/4.4, 6.8/5.4 cm; 10 dolls at dt 1/30
//   15.6/10.8 cm, dt 1/120 6.2/5.3, 4 substeps 5.0/6.2, 16 substeps
//   6.8/9.0; no NaN anywhere (before: 10, 12, dt 1/30 blew up).
//   With the compliance kept above (closed-form gyroscopic step, same
//   command): count 3..12: 1.2, 2.5, 3.2, 4.8, 4.4, 6.2, 4.7, 7.8, 4.5,
//   5.3 cm; 10 dolls at dt 1/30 9.2 cm, dt 1/120 7.3, 4 substeps 6.0, 16
//   substeps 9.2; no NaN (main before this change, same machine: 1.2, 2.5,
//   3.2, 4.5, 5.7, 7.3, 5.0, 6.4, 7.1, 6.8; 9.2, 16.4, 5.0, 6.8).
// Known limit: in piles of 7 or more dolls a part can still move at 0.1-0.5
// m/s after 8 s (16 s too): a head hanging over the pile's edge swings on its
// frictionless neck as a conical pendulum along the swing limit (no contact;
// the limit row stops approach but nothing damps the motion along it; the
// impulse solver's soft rows damp it). Joint friction would be the fix.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "physics/internal/contact_solver.h"
#include "physics/internal/lagrange_solver.h"
#include "physics/world.h"

namespace tumble::physics {

using namespace lagrange;

void LagrangeSubsteps::prepare(const World&, Real dt_s, int substeps) {
  m_joints.substepPrepare(double(dt_s) / std::max(1, substeps));
}
void LagrangeSubsteps::warmStart(SolverVelocity* vel, const Body* bodies) { m_joints.substepSolve(vel, bodies); }
Real LagrangeSubsteps::solve(SolverVelocity* vel, const Body*, bool useBias) {
  return Real(m_joints.substepProject(vel, useBias));
}
void LagrangeSubsteps::beforeIntegrate(SolverVelocity* vel, const Body*) { m_joints.substepProject(vel, true); }
void LagrangeSubsteps::projectPushout(SolverVelocity* pseudo, const Body*) { m_joints.substepProjectPushout(pseudo); }
void LagrangeSubsteps::finish(const World&) { m_joints.substepFinish(); }

void JointSystem::substepPrepare(double h) {
  const auto t0 = std::chrono::steady_clock::now();
  Impl& im = *m_impl;
  im.inStep = false;
  m_stats = JointSolveStats{};
  if (m_jointCount == 0 || !dropJointsOfDeadBodies()) return;
  prepare();  // joints (in elimination order) and their bodies, as of now
  if (im.ev.defs.empty() || !(h > 0)) return;
  im.h = h;
  const BodyIntegrator integrator = m_world.settings().integrator;
  im.endVelocityMovesPositions =
      integrator == BodyIntegrator::SymplecticEuler || integrator == BodyIntegrator::ImplicitEuler;
  ++im.serial;
  im.inStep = true;
  im.resultsPending = true;
  im.pendingBreaks.clear();
  im.vk.resize(im.states.size());
  im.wk.resize(im.states.size());
  if (im.memo.size() < im.slotOf.size()) im.memo.resize(im.slotOf.size());
  m_stats.solveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// How long an assembly keeps the compliance of contact after a contact
/// last moved one of its bodies (s). One step (the first version) let a
/// rag-doll tumbling down stairs switch at every bounce: 10.5 cm of joint
/// error and the doll not at rest; 1 s: 4.7 cm, at rest (ragdoll_stairs).
constexpr double kContactMemory_s = 1.0;

/// Marks the rows of every jointed assembly (bodies connected by joints)
/// one of whose bodies a contact moved in the last kContactMemory_s (see
/// JointSettings::compliance). Returns whether a solved row became touched.
static bool markTouchedRows(JointSystem::Impl& im) {
  const std::vector<BodyState>& st = im.states;
  std::vector<int>& root = im.assembly;
  root.resize(st.size());
  for (std::size_t i = 0; i < st.size(); ++i) root[i] = int(i);
  auto find = [&](int i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  for (const std::pair<int, int>& ab : im.ev.bodies)
    if (ab.first >= 0 && ab.second >= 0 && st[ab.first].dynamic && st[ab.second].dynamic)
      root[find(ab.first)] = find(ab.second);
  std::vector<char>& touched = im.assemblyTouched;
  touched.assign(st.size(), 0);
  for (std::size_t i = 0; i < st.size(); ++i) {
    if (!st[i].dynamic) continue;
    const JointSystem::Impl::Memo& memo = im.memo[st[i].id.index];
    if (memo.generation == st[i].id.generation && im.time_s - memo.contactTime_s <= kContactMemory_s)
      touched[find(int(i))] = 1;
  }
  bool newly = false;
  for (Row& r : im.rows) {
    const bool t = (r.a >= 0 && st[r.a].dynamic && touched[find(r.a)]) ||
                   (r.b >= 0 && st[r.b].dynamic && touched[find(r.b)]);
    if (t && !r.touched && r.index >= 0) newly = true;
    r.touched = t;
  }
  return newly;
}

/// Whether row r keeps the curvature of its swing: its natural C' stays out
/// of the feedback (substepSolve) and the relax targets -h/2 J'q' instead of
/// 0 (substepProject, "Relax target", which says where and why).
static bool keepsCurvature(const JointSystem::Impl& im, const Row& r) {
  return !r.limit && im.endVelocityMovesPositions && !r.touched;
}

/// The turn of a body within the substep, in each row's curvature. A body
/// whose principal moments differ is turned by the World as a free rigid
/// body (world_step.cpp, "Rotation"): its w changes within the substep by
/// the gyroscopic acceleration alpha = -I^-1 (w x I w), and the orientation
/// the positions end with carries h^2/2 J_w alpha of it. The World hands
/// that change of w over at the next substep's start, where q'_J makes it a
/// known force; the position it moved is already there. So the second
/// derivative of C along the World's motion is kappa = J'q' + J_w alpha,
/// not J'q' alone (lagrange_solver.cpp, which solves forces, has alpha in
/// Q). The target takes -h/2 kappa as the chord the positions move along
/// (and the relax keeps it), while the C' a row arrives with, measured with
/// q'_J (the turn not yet in it), is naturally h/2 (J'q' - J_w alpha):
/// substepSolve and substepProject, "Relax target".
/// Without it a level top sank by h^2/2 (I3/I1 - 1) w3 wp d a substep: in
/// the accuracy suite (8 substeps, 4.5 s) the joint of a disc spinning at
/// 50 rad/s opened 41 mm and of a square box 74 mm (0.53 and 1.03 mm in the
/// first step at 200 rad/s, as that predicts); with it 1.3 and 1.8 mm.
static void addFreeTurnCurvature(const std::vector<BodyState>& st, const Body* bodies, bool gyroscopic,
                                 std::vector<V3>& alpha, std::vector<Row>& rows) {
  for (Row& r : rows) r.jturn = 0;
  if (!gyroscopic) return;
  alpha.assign(st.size(), V3::Zero());
  bool any = false;
  for (std::size_t i = 0; i < st.size(); ++i) {
    const BodyState& s = st[i];
    const Vec3& I = bodies[s.id.index].inertiaLocal_kgm2;
    // The World's test (world_step.cpp, integratePositions): equal moments
    // turn to first order, with w unchanged.
    if (!s.dynamic || (I.x() == I.y() && I.y() == I.z())) continue;
    const M3 Iw = s.R * s.inertiaLocal.asDiagonal() * s.R.transpose();
    alpha[i] = -(s.invI * s.w.cross(Iw * s.w));
    any = true;
  }
  if (!any) return;
  for (Row& r : rows) {
    if (r.a >= 0) r.jturn += r.ja.tail<3>().dot(alpha[r.a]);
    if (r.b >= 0) r.jturn += r.jb.tail<3>().dot(alpha[r.b]);
  }
}

/// J q' of one row for the velocities v, w (per state; -1 = the world, at rest).
static double rowVelocity(const Row& r, const std::vector<V3>& v, const std::vector<V3>& w) {
  double c = 0;
  if (r.a >= 0) c += r.ja.head<3>().dot(v[r.a]) + r.ja.tail<3>().dot(w[r.a]);
  if (r.b >= 0) c += r.jb.head<3>().dot(v[r.b]) + r.jb.tail<3>().dot(w[r.b]);
  return c;
}

/// Hands state i's velocity (im.vk, im.wk) back to the World and keeps it as
/// the joints' own (the memo: q' of the next solve, see "Time stepping").
/// Always inlined: as a call per state it cost 0.6 % more instructions in a
/// Lagrange rag-doll step (callgrind, ragdolls_100).
[[gnu::always_inline]] inline void handBack(JointSystem::Impl& im, SolverVelocity* vel, std::size_t i) {
  const BodyState& s = im.states[i];
  vel[s.id.index].linear = wide(Vec3(im.vk[i].cast<Real>()));
  vel[s.id.index].angular = wide(Vec3(im.wk[i].cast<Real>()));
  JointSystem::Impl::Memo& mem = im.memo[s.id.index];
  mem = JointSystem::Impl::Memo{
      s.id.generation, im.serial, im.vk[i], im.wk[i],
      mem.generation == s.id.generation ? mem.contactTime_s : -std::numeric_limits<double>::infinity()};
}

void JointSystem::substepSolve(SolverVelocity* vel, const Body* bodies) {
  Impl& im = *m_impl;
  if (!im.inStep) return;
  const auto t0 = std::chrono::steady_clock::now();
  const double h = im.h;
  im.time_s += h;
  if (im.overCostCap) return;  // found over the cost cap in an earlier substep of this step
  const V3 g = wide3(m_world.settings().gravity_mps2);
  std::vector<BodyState>& st = im.states;
  // The state of the substep: poses as integrated so far; q' = the velocity
  // the joints left at their last update (the memo), so that everything that
  // changed the velocities since (the free step's gravity, forces and
  // gyroscopic term, the contacts' impulses, scripts) is the known force Q,
  // not a velocity the joints have to live with. See "Time stepping".
  for (std::size_t i = 0; i < st.size(); ++i) {
    BodyState& s = st[i];
    const Body& b = bodies[s.id.index];
    s.x = wide3(b.position_m);
    s.q = b.orientation.cast<double>().normalized();
    const bool moves = b.moves();
    im.vk[i] = moves ? V3(narrow(vel[s.id.index].linear).cast<double>()) : V3::Zero();
    im.wk[i] = moves ? V3(narrow(vel[s.id.index].angular).cast<double>()) : V3::Zero();
    s.v = im.vk[i];
    s.w = im.wk[i];
    if (!s.dynamic) continue;
    const Impl::Memo& memo = im.memo[s.id.index];
    if (memo.generation == s.id.generation && memo.serial + 1 >= im.serial) {
      s.v = memo.v;
      s.w = memo.w;
    } else {
      // Not seen last step (new, just woken): the velocity before this
      // substep's free step, gravity and the applied force and torque taken out.
      s.v = im.vk[i] - h * (g + s.invMass * wide3(b.force_N));
      s.w = im.wk[i] - h * (b.invInertiaWorld.cast<double>() * wide3(b.torque_Nm));
    }
  }
  deriveStates(st, m_settings, V3::Zero(), false);  // R, W at the substep's poses
  buildRows(im.ev, st, im.rows);  // C, J, J'q', C' = J q'
  addFreeTurnCurvature(st, bodies, m_world.settings().gyroscopic, im.freeTurn, im.rows);
  addMotorTorques(im.ev, st, m_settings);
  // The parts of Q the World does not apply: springs (soft rows, lambda =
  // -k C - c C') and hinge motors, as impulses over the substep.
  auto kick = [&](int b, const V6& p) {
    if (!st[b].dynamic) return;
    im.vk[b] += st[b].invMass * p.head<3>();
    im.wk[b] += st[b].invI * p.tail<3>();
  };
  for (Row& r : im.rows)
    if (r.soft) {
      r.lambda = -(r.k * r.c + r.d * r.cdot);
      scatterRow(r, h * r.lambda, kick);
    }
  for (std::size_t i = 0; i < st.size(); ++i)
    if (st[i].dynamic) im.wk[i] += h * (st[i].invI * st[i].Tm);
  // Hard rows. Baumgarte's C'' = -k_s C - k_d C' over the substep, with C
  // and C' at its end (implicit), asks for the row's target
  //   J v_end = (C' - h (J'q' + k_s C)) / (1 + h k_d + h^2 k_s),
  // and J W J^T (h lambda) = target - J v_k is the paper's equation times h
  // (J v_k - C' = h J W Q). A limit row stops the approach inelastically
  // (C' < 0 is not carried on) and pushes out with k_s.
  // Where the relax keeps the curvature term (see "Relax target" in
  // substepProject), a row's C' at the substep's start is not all error:
  // the chord that carried the joint round its constraint surface arrives
  // with C' = +h/2 J'q'. Only the rest is fed back; damping all of it took
  // swing energy out (a 170 degree pendulum's period 0.66 % short; with
  // the natural part kept out of the feedback, as with no feedback at all,
  // 0.01 %):
  //   J v_end = n - h J'q' + (C' - n - h k_s C) / (1 + h k_d + h^2 k_s),
  // n = h/2 J'q'. For a body the World turns as a free body, J'q' becomes
  // kappa = J'q' + J_w alpha in the chord and n = h/2 (J'q' - J_w alpha)
  // (addFreeTurnCurvature says why):
  //   J v_end = -h/2 kappa + (C' - n - h k_s C) / (1 + h k_d + h^2 k_s).
  // Elsewhere (limits, touched rows, averaging integrators) the formula
  // above.
  const double ks = m_settings.stiffness_per_s2, kd = m_settings.damping_per_s;
  const double feedback = 1 + h * kd + h * h * ks;
  markTouchedRows(im);
  for (Row& r : im.rows) {
    if (keepsCurvature(im, r)) {
      const double natural = 0.5 * h * (r.jdq - r.jturn);
      r.target = -0.5 * h * (r.jdq + r.jturn) + (r.cdot - natural - h * ks * r.c) / feedback;
    } else {
      const double carried = r.limit ? std::max(r.cdot, 0.0) : r.cdot;
      r.target = (carried - h * (r.jdq + ks * r.c)) / feedback;
    }
    if (!r.soft) r.lambda = 0;
  }
  const int maxIter = std::max(0, m_settings.maxActiveSetIterations);
  for (int iter = 0;; ++iter) {
    const int m = numberSolvedRows(im);
    m_stats.rows = m;
    if (m == 0) break;
    if (!assembleAndFactorize(im, m, m_stats, std::max(0.0, m_settings.compliance),
                              m_settings.lagrangeMaxFactorWorkPerRow)) {
      // Over the cost cap (a body carrying hundreds of joints, a lattice
      // of loops): nothing is solved in this step, and beforeWorldStep
      // hands the joints to the impulse solver from the next step on.
      im.overCostCap = true;
      for (Row& r : im.rows) r.index = -1;
      break;
    }
    im.rhs.resize(m);
    for (const Row& r : im.rows)
      if (r.index >= 0) im.rhs[r.index] = r.target - rowVelocity(r, im.vk, im.wk);
    im.lambda = im.factor.ldlt.solve(im.rhs);  // impulses h lambda (N s, N m s)
    // Active set: a limit row that would pull leaves and the rest is solved again.
    bool changed = false;
    if (iter < maxIter)
      for (Row& r : im.rows)
        if (r.limit && r.index >= 0 && im.lambda[r.index] < 0) r.active = false, changed = true;
    if (!changed) break;
  }
  for (Row& r : im.rows)
    if (r.index >= 0) {
      r.lambda = im.lambda[r.index] / h;
      scatterRow(r, im.lambda[r.index], kick);
    }
  for (std::size_t i = 0; i < st.size(); ++i)
    if (st[i].dynamic) handBack(im, vel, i);
  m_stats.solveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double JointSystem::substepProject(SolverVelocity* vel, bool useBias) {
  Impl& im = *m_impl;
  if (!im.inStep || m_stats.rows == 0 || im.overCostCap) return 0;
  const auto t0 = std::chrono::steady_clock::now();
  const double h = im.h;
  std::vector<BodyState>& st = im.states;
  // Before every contact sweep and after the last one (beforeIntegrate):
  // the contacts changed the velocities since the joints' solve; with their
  // impulses in Q, the multipliers change by J W J^T dmu = target - J v (the
  // same factorization), and contacts and joints take turns (block
  // Gauss-Seidel), the joints last before the positions move. See
  // "Robustness" at the top of the file.
  // A body whose velocity is not what the joints wrote last was moved by a
  // contact sweep since.
  bool touchedNow = false;
  for (std::size_t i = 0; i < st.size(); ++i)
    if (st[i].dynamic) {
      const V3 v = narrow(vel[st[i].id.index].linear).cast<double>();
      const V3 w = narrow(vel[st[i].id.index].angular).cast<double>();
      if (v != V3(im.vk[i].cast<Real>().cast<double>()) || w != V3(im.wk[i].cast<Real>().cast<double>())) {
        Impl::Memo& memo = im.memo[st[i].id.index];
        if (memo.contactTime_s != im.time_s) touchedNow = true;
        memo.contactTime_s = im.time_s;
      }
      im.vk[i] = v;
      im.wk[i] = w;
    }
  const int m = m_stats.rows;
  // An assembly a contact touched for the first time (a doll landing) gets
  // its compliance at once, not in the next substep: the impact is where
  // joints and contacts fight hardest.
  if (touchedNow && m_settings.compliance > 0 && markTouchedRows(im))
    assembleAndFactorize(im, m, m_stats, m_settings.compliance);  // the pattern substepSolve found within the cap
  im.rhs.resize(m);
  for (const Row& r : im.rows)
    if (r.index >= 0) {
      // Relax phase: no position feedback, as for the contacts (the rows'
      // Baumgarte velocity moved the positions already and must not stay in
      // the velocity); a limit row still stops an approach.
      // Relax target: not J v = 0 but the curvature the velocity must keep.
      // The relax runs after the substep's position update, with the rows
      // (J, J'q') of the substep's start. A velocity that carries a point
      // round the joint's constraint surface from one substep to the next
      // (the chord of a swinging bob) has J v = -h/2 J'q' at the chord's
      // start: C(x + h v) = C + h J v + h^2/2 J'v = 0. Projecting it onto
      // J v = 0 (before) took that part out at every substep, h^2/8 m
      // (J'q')^2 of kinetic energy: a loss of order h per unit time,
      // growing as the speed to the fourth power. Measured with a ball-joint
      // pendulum (1.1 m, 8 substeps, 12 s): 90 degrees lost 17 % of m g L,
      // 150 degrees 55 %, and halving h halved the loss. With -h/2 J'q'
      // here and the natural C' kept out of the feedback (substepSolve) the
      // largest |E - E0| is 0.5 % of m g L at any amplitude from 5 to 170
      // degrees (the impulse solver: 0.6 %), 3.5 % with one substep (was
      // 62 %), and the joint opens 0.12 mm at most (was 1 mm). Tests:
      // JointSystem.PendulumKeepsItsEnergyAtEveryAmplitude; the accuracy
      // suite's pendulum periods (170 degrees: 0.1 % long, was 38 % short).
      // Only where the derivation holds:
      //   - the World moves positions with the end velocity (symplectic or
      //     backward Euler; the default). Heun and the other averaging
      //     integrators move them with a mean velocity; with the term a
      //     Heun pendulum still lost 2.5-7.6 % (8-31 % without), so those
      //     keep J v = 0;
      //   - rows of assemblies no contact moved in the last second
      //     (JointSettings::compliance): a contact can spin a limb by
      //     hundreds of rad/s within a substep, and J'q' (quadratic in w,
      //     taken at the substep's start) is then no estimate of the
      //     curvature. With the term there too, 10 piled dolls had a hinge
      //     84 degrees off its axis (12 without) and their joints opened
      //     10.6 cm (4.9 without).
      const double target = useBias          ? r.target
                            : r.limit          ? std::max(r.target, 0.0)
                            : keepsCurvature(im, r) ? -0.5 * h * (r.jdq + r.jturn)
                                                    : 0.0;
      im.rhs[r.index] = target - rowVelocity(r, im.vk, im.wk);
    }
  const Eigen::VectorXd& dmu = im.lambda = im.factor.ldlt.solve(im.rhs);
  double changed2 = 0, total2 = 0;
  std::vector<V3>& dv = im.dv;
  std::vector<V3>& dw = im.dw;
  std::vector<double>& d = im.rowImpulse;
  dv.assign(st.size(), V3::Zero());
  dw.assign(st.size(), V3::Zero());
  d.assign(im.rows.size(), 0);
  auto kick = [&](int b, const V6& p) {
    if (!st[b].dynamic) return;
    dv[b] += st[b].invMass * p.head<3>();
    dw[b] += st[b].invI * p.tail<3>();
  };
  for (std::size_t k = 0; k < im.rows.size(); ++k) {
    const Row& r = im.rows[k];
    if (r.index < 0) continue;
    // A limit row may only push: its total impulse stays >= 0.
    d[k] = r.limit ? std::max(dmu[r.index], -h * r.lambda) : dmu[r.index];
    scatterRow(r, d[k], kick);
  }
  double size2 = 0;
  for (std::size_t i = 0; i < st.size(); ++i)
    if (st[i].dynamic) size2 += dv[i].squaredNorm() + dw[i].squaredNorm();
  if (!std::isfinite(size2)) {  // a degenerate system: leave this turn to the contacts
    m_stats.solveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return 0;
  }
  for (std::size_t k = 0; k < im.rows.size(); ++k) {
    Row& r = im.rows[k];
    if (r.index < 0) continue;
    r.lambda += d[k] / h;
    changed2 += d[k] * d[k];
    total2 += h * h * r.lambda * r.lambda;
  }
  for (std::size_t i = 0; i < st.size(); ++i) {
    if (!st[i].dynamic) continue;
    im.vk[i] += dv[i];
    im.wk[i] += dw[i];
    handBack(im, vel, i);
  }
  m_stats.solveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return total2 > 0 ? changed2 / total2 : 0;
}

// ---- Push-out (the contacts' split impulses, contact_solver.cpp) -------------
// The contacts remove overlap with pseudo-velocities that move the
// positions in this substep and are then dropped; the joints never saw
// them, so a limb pushed out of the ground moved without the body it hangs
// on, and the joint opened by the push. That grew with the substeps (each
// removes WorldSettings::baumgarte of the overlap, so more substeps push
// out faster than the joints' feedback closes): a rag-doll dropped flat
// onto the ground (0.3 m, tests/physics/joints/ragdoll_test.cpp) opened a
// joint by 2.6, 4.9, 8.2 and 14.3 mm at 4, 8, 16 and 32 substeps, and by
// 0.6, 0.3, 0.17 and 0.08 mm with no push-out at all. So the push-out
// velocities are projected onto the joints like any velocity, with the
// substep's factorization: J W J^T mu = -J pv for the equality rows (limit
// rows keep what the push gives them), pv += W J^T mu. The overlap is then
// removed by moving the jointed parts together: the same doll 0.65, 0.35,
// 0.25 and 0.24 mm; `tumble run base:ragdoll_pile --set
// physics.joint_solver=lagrange --set physics.substeps=N`: 8.1, 11.9, 20,
// 52 mm before, 3.7, 2.0, 1.4, 3.7 mm now. Test: Ragdoll.LandingUnderThe
// LagrangeSolverOpensNoJointWiderWithMoreSubsteps.
void JointSystem::substepProjectPushout(SolverVelocity* pseudo) {
  Impl& im = *m_impl;
  if (!im.inStep || m_stats.rows == 0 || im.overCostCap) return;
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<BodyState>& st = im.states;
  const int m = m_stats.rows;
  std::vector<V3>& pv = im.dv;
  std::vector<V3>& pw = im.dw;
  pv.assign(st.size(), V3::Zero());
  pw.assign(st.size(), V3::Zero());
  bool any = false;
  for (std::size_t i = 0; i < st.size(); ++i)
    if (st[i].dynamic) {
      pv[i] = narrow(pseudo[st[i].id.index].linear).cast<double>();
      pw[i] = narrow(pseudo[st[i].id.index].angular).cast<double>();
      any = any || pv[i] != V3::Zero() || pw[i] != V3::Zero();
    }
  if (!any) return;
  im.rhs.setZero(m);
  for (const Row& r : im.rows)
    if (r.index >= 0 && !r.limit) im.rhs[r.index] = -rowVelocity(r, pv, pw);
  const Eigen::VectorXd mu = im.factor.ldlt.solve(im.rhs);
  std::vector<V6>& d = im.pushout;
  d.assign(st.size(), V6::Zero());
  for (const Row& r : im.rows) {
    if (r.index < 0) continue;
    if (r.a >= 0) d[r.a] += r.ja * mu[r.index];
    if (r.b >= 0) d[r.b] += r.jb * mu[r.index];
  }
  for (std::size_t i = 0; i < st.size(); ++i) {
    if (!st[i].dynamic) continue;
    const V3 v = pv[i] + st[i].invMass * d[i].head<3>(), w = pw[i] + st[i].invI * d[i].tail<3>();
    if (!v.allFinite() || !w.allFinite()) continue;  // a degenerate system: the contacts' push stands
    pseudo[st[i].id.index].linear = wide(Vec3(v.cast<Real>()));
    pseudo[st[i].id.index].angular = wide(Vec3(w.cast<Real>()));
  }
  m_stats.solveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void JointSystem::substepFinish() {
  Impl& im = *m_impl;
  if (!im.inStep) return;
  im.inStep = false;
  const auto t0 = std::chrono::steady_clock::now();
  const Evaluation& ev = im.ev;
  // The constraint force of the last substep, per joint (on body A).
  im.jointForce.assign(ev.defs.size(), V3::Zero());
  im.jointTorque.assign(ev.defs.size(), V3::Zero());
  std::size_t k = 0;
  for (const Row& r : im.rows) {
    while (k < ev.slots.size() && ev.slots[k] != r.joint) ++k;  // rows are grouped by joint in evaluation order
    if (k == ev.slots.size()) break;
    if (!r.active || (r.index < 0 && !r.soft)) continue;
    if (r.angular) im.jointTorque[k] += r.lambda * r.ja.tail<3>();
    else im.jointForce[k] += r.lambda * r.ja.head<3>();
  }
  for (std::size_t j = 0; j < ev.defs.size(); ++j) {
    const JointDef& d = *ev.defs[j];
    const double f = im.jointForce[j].norm(), t = im.jointTorque[j].norm();
    if ((d.breakForce_N > 0 && f > d.breakForce_N) || (d.breakTorque_Nm > 0 && t > d.breakTorque_Nm))
      im.pendingBreaks.push_back(
          JointBreakEvent{JointId{ev.slots[j], ev.generations[j]}, d.bodyA, d.bodyB, f, t, d.userData});
  }
  m_stats.solveMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace tumble::physics
