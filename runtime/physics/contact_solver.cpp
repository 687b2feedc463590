// Contact solver: sequential impulses at velocity level with soft
// constraints and substepping ("soft step", Catto, Box2D v3, 2024).
//
// For each contact point with normal n and offsets rA, rB from the centres of
// mass, the relative normal velocity is
//     vn = n . (vB + wB x rB - vA - wA x rA)
// and an impulse P = lambda n changes it by lambda / m_eff, with
//     1/m_eff = 1/mA + 1/mB + n . ((IA^-1 (rA x n)) x rA + (IB^-1 (rB x n)) x rB).
// Accumulated impulses are clamped (lambda >= 0: contacts push, never pull),
// which with Gauss-Seidel iteration converges to the complementarity
// solution; warm starting with last step's impulses makes stacks converge.
//
// Overlap is removed by a soft constraint: a spring-damper of stiffness
// `contactHertz` and damping ratio `contactDampingRatio` expressed as
// (biasRate, massScale, impulseScale) so that it is unconditionally stable for
// any step. Each substep solves with that bias, integrates positions, then
// "relaxes" without bias so the push-out velocity does not turn into bounce
// (this is what split impulses achieve, without a second velocity set).
// Two push-out models are implemented (WorldSettings::softContacts):
//  - split impulses (default): the velocity solve never pushes overlapping
//    bodies apart; a separate pass computes pseudo-velocities that remove
//    beta * depth / h of the overlap (at most maxPushout), positions move by
//    them, and they are then discarded (Catto 2006; Bullet's split impulse).
//    Correction cannot add kinetic energy, so a clump of deeply overlapping
//    bodies separates without being launched;
//  - soft: Box2D v3's mass-normalised spring-damper in the solve pass, with a
//    bias-free relax pass after the position update. Its steady-state overlap
//    is F / (m_eff w^2): a light body under a heavy one sinks deeply.
// Measured on 2026-11-22 (10 s of a 20-box stack, 5 s of a 1 kg box under a
// 1000 kg box, 6 s of 50 boxes spawned overlapping; dt = 1/60):
//   model  substeps x iters   stack drift   stack sink   1:1000 sink   overlap max speed
//   soft        4 x 1            6 mm         208 mm      collapses
//   soft        8 x 8            5 mm         208 mm      558 mm
//   rigid Baumgarte bias in the velocity solve (+relax), 8 x 4:
//                                3 mm           2 mm        9 mm        20 m/s (launched)
//   split impulses, 8 x 4:       3 mm           2 mm       12 mm         6.3 m/s (the fall)
//   split impulses, 4 x 4:      24 mm           8 mm       24 mm
//   split impulses, 8 x 8:       7 mm           1 mm        7 mm
// so the default is split impulses with 8 substeps of 4 iterations.
// Early exit (WorldSettings::solverTolerance): a substep stops iterating once
// a sweep changes the impulses by at most tol (RMS, relative to the normal
// impulses). Measured after the compact-solver rewrite (2026-11-23; 20-box
// stack top drift over 10 s, 1 kg under 1000 kg sink over 5 s, pyramid_20
// largest drift over 10 s and CPU time per step, single thread):
//   substeps x iters   tol     stack drift  1:1000 sink  pyramid drift  pyramid ms
//        8 x 4          0         3.2 mm      12.6 mm       0.53 mm        3.13
//        8 x 4          1e-3      3.1 mm      12.6 mm       0.89 mm        1.62
//        8 x 4          1e-2    155   mm      11.9 mm       0.39 mm        1.58
//        8 x 2          1e-3      6.6 mm      19.7 mm       0.48 mm        1.69
//        4 x 4          1e-3     71   mm      25.8 mm       3.45 mm        0.98
//        4 x 4          0        24   mm      25.8 mm       1.17 mm        1.67
// A resting pyramid converges to round-off in the first sweep of a substep
// (the residual then stays flat at ~4e-5 N s, a float limit cycle), so with
// tol = 1e-3 it costs one sweep per substep instead of four; 1e-2 stops tall
// stacks before they converge (they creep). 4 substeps fail the stack test
// (< 1 cm), 8 x 2 passes with half the margin and is no faster once the
// early exit is on, so the defaults stay 8 x (4 + 1) with tol = 1e-3.
// Then the scenarios disagreed (2026-11-22, tumble run with --set): the
// stack scenario with sleep off and the 1:1000 "at rest in the last second"
// check (< 5 cm/s) sit near their limits and move chaotically with the
// settings:
//   substeps x (iters + relax)   tol    stack, no sleep   1:1000 last-second speed
//        8 x (4 + 1)            1e-3     19.2 mm  fail      7.7 cm/s  fail
//        8 x (4 + 1)            1e-4      6.8 mm            7.7 cm/s  fail
//        8 x (8 + 1)            1e-4     10.8 mm  fail       pass
//        8 x (6 + 1)            1e-4     11.7 mm  fail      6.3 cm/s  fail
//       12 x (4 + 1)            1e-4     30.8 mm  fail       pass
//        8 x (4 + 2)            1e-4      7.5 mm             pass
// so the defaults are 8 x (4 + 2) with tol = 1e-4. tumble_compare with them
// (same run, Bullet at the same 40-pass budget): pyramid_20 0.76x Bullet's
// step time, boxes_3000 0.67x (penetration 0.40 vs 0.65 m), highspeed_1000
// 0.68x with no escapes.
//
// Normal blocks (2026-11-26). A 100 kg box on a column of ten 1 kg boxes
// swayed until the column fell (sleep off, 13 m of drift in 60 s), and an
// 8-box column alternating 1 kg and 100 kg drifted 30 mm: the rows of one
// face contact (3 or 4 points, one body pair) were solved one after the
// other, once per sweep; each row undoes part of the others, and what the
// rows leave between them is a torque on the light box (its inertia is 1/100
// of the heavy box's) that rocks it. Sweeping a manifold's rows until they
// agree (at most 8 sweeps, 1e-4 relative) made these stacks stand but cost
// 1.7x on boxes_3000_stacked, where every box has two face manifolds and
// square faces converge slowly under Gauss-Seidel whatever the masses (K of
// two equal cubes is (1/mA + 1/mB) times a matrix of geometry alone).
// Instead each face manifold's normal rows are solved as one block, exactly:
//   K = J M^-1 J^T (N x N, N points). Each row is n . (vB - vA) plus
//   (rB x n) . wB - (rA x n) . wA, and r x n is affine in the point's
//   coordinates in the contact plane, so K = P G P^T with P = [1, u, v]
//   (N x 3; the points' coordinates from their centroid along the principal
//   axes of their spread) and G (3 x 3) the pair's response to a force and
//   two moments. For four coplanar points K has rank 3 and no inverse (this
//   is why Box2D v2's two-point block solver does not carry over), but
//   K^+ = P^+T G^-1 P^+ is its pseudo-inverse, built once per step in
//   prepareNormalBlock (double).
//   Solve: r = vn + bias (the speculative bias sep / h of separated points),
//   lambda' = lambda - K^+ r. Accepted when it is a solution of the
//   complementarity problem with every point pushing: no pull (lambda' >= 0)
//   and r in K's range (r's part along K's null vector, the twist t with
//   P^T t = 0, is round-off: under 1e-3 of |r|; a larger part means a point
//   must let go). If some lambda' < 0, the distribution is moved along the
//   twist, which changes no velocity, to the nearest one without pull.
//   Otherwise (a box tipping onto an edge, curved or uneven points) the
//   rows are swept one by one as before.
// The block is applied to manifolds of 3 and 4 points (faces). Two-point
// manifolds (edges, capsules lying on something) are rank 2 and K is
// invertible, so the block would be Box2D's two-point solver; measured
// with it, the Lagrange rag-doll pile (Ragdoll.TenPiledUnderTheLagrangeSolver
// StayTogether, 10 dolls, 8 s) opened its joints by 13.5 cm against its
// 10 cm bound (4.3 cm before), and at dt 1/30 twisted hinges 109 degrees
// off their axis (49 before): so two-point manifolds keep the sweep.
// Measured (tests/physics/mass_ratio_test.cpp, 60 s, sleep off, largest
// sideways drift of any box; tumble_compare boxes_3000_stacked, old and new
// binary alternating in one run window, median CPU time per step):
//   stack                              rows one by one   face blocks
//   100 kg on ten 1 kg boxes           fell (13.3 m)       0.36 mm
//   10 kg on ten 1 kg boxes            3.1 mm              0.00 mm
//   1 kg on ten 100 kg boxes           1.6 mm              0.02 mm
//   alternating 1 / 10 kg, 8 boxes     52 mm               0.02 mm
//   alternating 1 / 100 kg, 8 boxes    30 mm               0.02 mm
//   pyramid of 5, top 2 rows 100 kg    1.1 mm              0.89 mm
//   1000 kg on one 1 kg box            31 mm               0.19 mm
//   pyramid of 5, top 2 rows 1000 kg   252 mm              29 mm
//   1000 kg on ten 1 kg boxes          fell                fell
//   alternating 1 / 1000 kg            fell                fell
//   Ragdoll pile (lagrange)            4.3 cm              4.9 cm
//   boxes_3000_stacked CPU per step    28.8, 25.7 ms       28.3, 27.5 ms (1.02x)
//   boxes_3000_stacked drift, penetr.  306 mm, 1.7 mm      196 mm, 1.0 mm
// At 1:1000 the light boxes of a column still tip over: the sweeps over
// manifolds (Gauss-Seidel between the blocks) do not carry a 1000 kg load
// through ten 1 kg boxes in 4 iterations.
// Data layout (after measuring the first version: solveContacts 36%,
// applyImpulse 21%, relativeVelocity 7% of a pyramid_20 run, Bullet's solver
// loop 4%): the substeps read a compact array of body velocities (gathered
// once per step, scattered after), and per point the rows r x n and
// I^-1 (r x n) (and the same for both tangents) computed once per step, all
// 4-wide so a row times a velocity is one packed multiply-add and one
// horizontal sum. Separations are updated once per phase (positions only
// change between the solve and relax phases), with one rotation per side per
// manifold. Momentum bookkeeping reads the accumulated impulses once per
// substep instead of adding up every impulse in double.
// Speculative contacts: a point with positive separation s allows the bodies
// to approach by at most s in this substep (bias = s/h), so a fast body stops
// at the surface instead of tunnelling through it.
//
// Restitution follows Newton's law per impact, in the substep of the impact
// (after its relax sweeps), with the normal velocity at the instant of
// contact. Semi-implicit Euler stores the mean velocity over the last
// substep, so the velocity at a substep boundary is v + a h / 2, with a the
// free relative acceleration along the normal (gravity against a static
// body; zero between two falling bodies), read from the change of the
// normal velocity across the substep's forces. From the boundary velocity
// u0 and separation s at the start of the substep of first push, the free
// motion touches at u_c^2 = u0^2 - 2 a s; the rebound -e u_c is carried to
// where the point is at the end of the substep (u^2 = e^2 u_c^2 + 2 a s_end)
// and stored as u - a h / 2. So an elastic ball keeps its energy exactly
// between impacts and at them. Before (2026-11-25), restitution ran once
// after the substeps on the mean velocity: every impact lost about g h of
// speed (a ball at e = 0.6 was 8% low by its fourth bounce; e = 1 lost 15%
// of its energy in 30 s), and two impacts inside one step merged into one
// inelastic event (Newton's cradle with a 1 cm gap). The impact's impulse
// is not warm started into the next substep (the bodies are separating).
// Friction acts over the whole impact impulse: the restitution pass also
// applies the tangential impulse that stops the slip, within mu times the
// total normal impulse of the impact (compression and restitution), so an
// oblique impact follows Coulomb's law with the rolling transition
// (tests/physics/impact_test.cpp; before, a ball at 3 m/s and 30 degrees
// kept 1.44 of its 1.5 m/s tangential speed where the law gives 1.07).
// Cost (tumble_compare, old and new binary in one run, 2026-11-25, a
// loaded machine): pyramid_20 2.58 -> 2.47 ms median step CPU with the same
// end state, highspeed_1000 1.92 -> 1.77 ms: within the noise.
// The approach speed is read before the impulses of the substep in which
// the point first pushes; read inside the sweep it included what
// neighbours had just done and inflated bounces. Kinetic energy kept after
// 600 steps of spheres at 250 m/s in a closed box with e = 1 (20 m box,
// 1 m walls; measured with restitution after the substeps):
//   spheres   before   vn before the sweep, passes: 1      2       4
//     10       0.72                              1.000   1.000   1.000
//     50                                         0.98    1.007   1.006
//   1000       0.13                              0.61    0.81    1.14
// More passes converge to the simultaneous-impact solution, which gains
// energy in dense clumps, so the default is one pass (never gains).
// Glancing fast spheres: see collideSpheresSwept (narrow_phase.cpp), which
// gives two fast spheres the normal at their time of impact.
//
// Friction: Coulomb with two tangents; the tangential impulse vector is
// clamped to the disc of radius mu * lambda_n (the friction cone, not a box).
//
// Rolling resistance: an angular constraint on the relative angular velocity
// in the tangent plane, its angular impulse clamped to the disc of radius
// arm * sum(lambda_n) with arm = C_rr * rolling radius, so a rolling ball
// feels at most the torque C_rr r N and comes to rest. Spin about the normal
// (drilling) is resisted with the same arm: without it a ball spinning on the
// spot spins for ever and drags whatever rests on it round in circles.
//
// Rim contacts (2026-11-27). A cylinder tilted between standing on its cap
// and lying on its side touches a face with one point of its rim
// (Manifold::rimA/B): the cylinder's support along the normal, which runs
// round the rim as the cylinder turns instead of turning with it. A
// contact's rows are otherwise built once per step, with the lever to the
// step's point and each body's world inverse inertia at the step's start.
// A cylinder spinning about the vertical at 8 rad/s turns 0.13 rad in a
// step, and a tilted one spinning on its rim gained up to 0.8 J in 10 s at
// 60 Hz (friction or none); with 16 steps per 1/60 s under 0.05 J. Two
// things were stale, and each alone left a gain:
//  - the inverse inertia. An impulse P at lever r changes the kinetic
//    energy by P . (u + u') / 2 (u, u' the point's velocity before and
//    after), so never adds any, only if it turns w by I^-1 (r x P) with the
//    body's inertia I now. With the step start's I0^-1 the change of
//    w . I w / 2 has the extra term w . (I I0^-1 - 1) (r x P), first order
//    in the turn and in the spin: the friction impulses of a fast-spinning
//    rim fed it energy. Turning the levers alone, with I0^-1 kept, gained
//    up to 8.3 J (20 deg at 8 rad/s). Turning I^-1 alone removed
//    the gain at 8 rad/s, but not at 3 (10 deg: +0.66 J);
//  - the lever. The step start's support point is no longer at the bottom
//    once the cylinder has turned: the rows hold the velocity of a point
//    that is not the contact (off by the turn since the step's start).
//    Turning the normal lever alone (the friction levers and I0^-1 kept)
//    removed the gain except at 30 deg and 8 rad/s (+0.80 J).
// So for a rim contact every substep (turnRimRows) turns the rim side's
// normal and friction levers to the current support point, both bodies'
// inverse inertia with their turn since the step's start (dq I0^-1 dq^T,
// in the rows and the rolling rows), and takes the separation from the
// support's height (ConvexPiece::support: hh |a.n| + r sqrt(1 - (a.n)^2)
// for axis a), not from a material point on the rim, which rises as it
// turns away from the bottom (this alone changed nothing measurable, but it
// is the contact's height).
// With all three no case of the test gains measurable energy (0 J in
// float, tests/physics/cylinder_test.cpp). Only rim contacts do this:
// every other contact keeps its rows for the step, and turnRimRows runs
// after the separation loop, so other contacts pay nothing.
//
// Threads (WorldSettings::threads). A Gauss-Seidel sweep is sequential: each
// constraint sees the velocities the ones before it left. But a constraint
// only reads and writes the velocities of its two bodies, and only bodies
// that take impulses (awake, dynamic) are written. So each constraint has at
// most two predecessors, the last earlier constraint moving its body a and
// the last moving its body b, and a level, one more than its predecessors'
// highest (a graph colouring that keeps the order: Box2D v3's colouring
// reorders the constraints, and with them the result). Each level is split
// between the threads by work; a thread solves its constraints level by
// level, and before each one waits (spinning) until its predecessors have
// been solved in this pass. Every constraint then reads exactly the
// velocities it reads in the sequential sweep: the result is the sequential
// one, bit for bit, for any number of threads. No deadlock: a thread waits
// only for a lower level, which the other thread reaches before any higher
// one. A sweep's residual is summed per constraint and then in the
// sequential order, with a pool as without. The passes without order
// (separations, approach speeds) are split in plain ranges; restitution
// (rare) runs on the caller in the sequential order.
// What made two threads pay (pile_1015: 1015 boxes, 6930 manifolds, 286
// levels; median step, tumble_compare --threads):
//   each level halved in index order                     1.18x
//   halved across the level's front (below)              1.17x
//   and the constraints stored in the threads' order     1.45x
// A level is a front moving along the broad phase's sweep axis (pairs come
// in its order), so it is cut along the axis with the widest spread that
// the levels do not follow: 8 % of predecessors are then on the other
// thread instead of half. That alone did not pay: each thread still jumped
// through arrays laid out in the sequential order, and the cache misses
// cost what the second thread saved. Stored in the threads' order (copied
// once per step, each thread copying its own share), each thread streams
// through its own constraints and points; the sequential order is kept as
// a list for the sums and restitution.
#include "physics/internal/contact_solver.h"
#include "physics/internal/convex_collision.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "physics/internal/height_field_collision.h"
#include "physics/internal/narrow_phase.h"
#include "physics/internal/worker_pool.h"

namespace tumble::physics {
namespace {

bool takesImpulses(const Body& b) { return b.isDynamic() && b.awake; }

// Threads (see the top of this file). Below kMinThreadedConstraints a
// step's passes stay on the caller: waking the pool costs more than the
// pass (a pass over 100 constraints is a few microseconds).
constexpr std::size_t kMinThreadedConstraints = 128;

// Normal blocks (see the top of this file): numerical limits, not tuning.
// Points closer than a micrometre (squared spread per point, m^2) count as
// one; a spread whose minor axis is under 1/1000 of its major in length is
// a line; a G whose eigenvalues span more than 1e9 is singular (double);
// r may have a part along K's null space of 1e-3 of its size (float
// round-off of rows summed over bodies 1000x apart in mass).
constexpr double kBlockCoincident_m2 = 1e-12;
constexpr double kBlockCollinear = 1e-6;
constexpr double kBlockSingular = 1e-9;
constexpr Real kBlockConsistency = Real(1e-3);

/// Coulomb's cone: scales the tangential impulse (l0, l1) back onto the
/// circle of radius maxF (friction x normal impulse) when it lies outside.
inline void clampToFrictionCone(Real maxF, Real& l0, Real& l1) {
  const Real len2 = l0 * l0 + l1 * l1;
  if (len2 > maxF * maxF) {
    const Real scale = maxF / std::sqrt(len2);
    l0 *= scale;
    l1 *= scale;
  }
}

const Body& heightFieldBody() {
  static const Body ground = [] {
    Body g;
    g.type = BodyType::Static;
    g.alive = true;
    return g;
  }();
  return ground;
}

/// Row times velocity: one packed multiply-add chain and one horizontal sum.
inline Real rowDot(const Vec4r& n, const Vec4r& dv, const Vec4r& jB, const Vec4r& wB, const Vec4r& jA,
                   const Vec4r& wA) {
  return (n.cwiseProduct(dv) + jB.cwiseProduct(wB) - jA.cwiseProduct(wA)).sum();
}

/// A rim side's cylinder (radius r, half height hh) centred at the origin
/// with orientation R: its support point along d is the lever from its
/// centre to the rim point touching, d . support its reach along d.
ConvexPiece rimCylinder(const Mat3& R, Real r, Real hh) {
  ConvexPiece piece;
  piece.kind = ConvexPiece::Kind::Cylinder;
  piece.pose = Pose{Vec3::Zero(), R};
  piece.radius_m = r;
  piece.halfHeight_m = hh;
  return piece;
}

}  // namespace

bool ContactSolver::threaded() const {
  return m_pool && m_pool->threads() > 1 && m_constraints.size() >= kMinThreadedConstraints;
}

void ContactSolver::buildSchedule(std::size_t bodySlots) {
  m_levels = 0;
  m_logical.clear();
  if (!threaded()) return;
  const std::size_t n = m_constraints.size();
  const int threads = m_pool->threads();
  // Levels and predecessors (see "Threads" at the top of this file): a
  // constraint's level is 1 + the highest level of an earlier constraint
  // moving one of its bodies; its predecessors are the last earlier
  // constraint moving its body a and the last moving its body b.
  m_lastConstraint.assign(bodySlots, -1);
  m_levelCount.clear();
  m_level.resize(n);
  m_pred.resize(n);
  for (std::size_t ci = 0; ci < n; ++ci) {
    const Constraint& c = m_constraints[ci];
    std::array<std::int32_t, 2>& pred = m_pred[ci];
    pred = {c.movesA ? m_lastConstraint[c.a] : -1, c.movesB ? m_lastConstraint[c.b] : -1};
    std::uint32_t l = 0;
    for (std::int32_t p : pred)
      if (p >= 0) l = std::max(l, m_level[std::size_t(p)] + 1);
    if (c.movesA) m_lastConstraint[c.a] = std::int32_t(ci);
    if (c.movesB) m_lastConstraint[c.b] = std::int32_t(ci);
    m_level[ci] = l;
    if (m_levelCount.size() <= l) m_levelCount.resize(l + 1, 0);
    ++m_levelCount[l];
  }
  // Each level split between the threads by work (a point's rows are most
  // of a constraint's cost) and by place: a level is a front that moves
  // along the broad phase's sweep axis (pairs come in its order), so it is
  // cut across that axis, along the axis with the widest spread that the
  // level does not follow; a predecessor is then mostly on the same side,
  // and its bodies' velocities in the same core's cache.
  const std::size_t levels = m_levelCount.size();
  int axis = 0;
  {
    double best = -1;
    double meanL = 0;
    for (std::size_t ci = 0; ci < n; ++ci) meanL += m_level[ci];
    meanL /= double(n);
    for (int k = 0; k < 3; ++k) {
      double mean = 0, lo = 1e30, hi = -1e30;
      for (std::size_t ci = 0; ci < n; ++ci) {
        mean += m_place[ci][k];
        lo = std::min<double>(lo, m_place[ci][k]);
        hi = std::max<double>(hi, m_place[ci][k]);
      }
      mean /= double(n);
      double sxy = 0, sxx = 0, syy = 0;
      for (std::size_t ci = 0; ci < n; ++ci) {
        const double x = m_place[ci][k] - mean, y = m_level[ci] - meanL;
        sxy += x * y;
        sxx += x * x;
        syy += y * y;
      }
      const double corr = sxx > 0 && syy > 0 ? std::abs(sxy) / std::sqrt(sxx * syy) : 1;
      const double score = (hi - lo) * (1 - corr);
      if (score > best) best = score, axis = k;
    }
  }
  std::vector<std::uint32_t>& start = m_levelStart;
  start.assign(levels + 1, 0);
  for (std::size_t l = 0; l < levels; ++l) start[l + 1] = start[l] + m_levelCount[l];
  std::vector<std::uint32_t>& byLevel = m_byLevel;
  std::vector<std::uint32_t>& cursor = m_levelCount;  // reused: the next free place of each level
  byLevel.resize(n);
  for (std::size_t l = 0; l < levels; ++l) cursor[l] = start[l];
  for (std::size_t ci = 0; ci < n; ++ci) byLevel[cursor[m_level[ci]]++] = std::uint32_t(ci);
  m_threadOrder.resize(std::size_t(threads));
  for (auto& order : m_threadOrder) order.clear();
  for (std::size_t l = 0; l < levels; ++l) {
    auto first = byLevel.begin() + start[l], last = byLevel.begin() + start[l + 1];
    std::sort(first, last, [&](std::uint32_t x, std::uint32_t y) {
      return m_place[x][axis] < m_place[y][axis] || (m_place[x][axis] == m_place[y][axis] && x < y);
    });
    std::size_t work = 0, done = 0;
    for (auto it = first; it != last; ++it) work += 1 + m_constraints[*it].count;
    for (auto it = first; it != last; ++it) {
      const std::size_t t = std::min<std::size_t>(done * std::size_t(threads) / work, std::size_t(threads) - 1);
      m_threadOrder[t].push_back(*it);
      done += 1 + m_constraints[*it].count;
    }
  }
  // Storage in the threads' order: each thread then streams through its
  // own constraints and points (in the sequential order they were
  // scattered over the whole array, and each miss cost more than the
  // second thread saved). m_logical keeps the sequential order for what
  // is summed or solved in it.
  m_threadStart.assign(std::size_t(threads) + 1, 0);
  m_logical.resize(n);
  std::vector<std::uint32_t>& storageOf = m_storageOf;
  storageOf.resize(n);
  {
    std::uint32_t k = 0;
    for (std::size_t t = 0; t < m_threadOrder.size(); ++t) {
      for (std::uint32_t ci : m_threadOrder[t]) storageOf[ci] = k++;
      m_threadStart[t + 1] = k;
    }
  }
  m_permutedConstraints.resize(n);
  m_permutedPoints.resize(m_points.size());
  m_permutedGeometry.resize(m_points.size());
  m_permutedSeparation.resize(m_points.size());
  m_permutedImpact.resize(m_points.size());
  m_permutedPseudoImpulse.resize(m_points.size());
  m_permutedPred.resize(n);
  // Each thread's first point, then each thread copies its own share (and
  // finds it in its cache in the first pass).
  std::vector<std::uint32_t>& pointStart = m_levelStart;  // reused: per thread
  pointStart.assign(std::size_t(threads) + 1, 0);
  for (std::size_t t = 0; t < m_threadOrder.size(); ++t) {
    std::uint32_t points = 0;
    for (std::uint32_t ci : m_threadOrder[t]) points += m_constraints[ci].count;
    pointStart[t + 1] = pointStart[t] + points;
  }
  m_pool->run([&](int t) {
    std::uint32_t nextPoint = pointStart[std::size_t(t)];
    for (std::uint32_t ci : m_threadOrder[std::size_t(t)]) {
      const std::uint32_t si = storageOf[ci];
      Constraint c = m_constraints[ci];
      std::copy_n(m_points.begin() + c.firstPoint, c.count, m_permutedPoints.begin() + nextPoint);
      std::copy_n(m_geometry.begin() + c.firstPoint, c.count, m_permutedGeometry.begin() + nextPoint);
      std::copy_n(m_separation.begin() + c.firstPoint, c.count, m_permutedSeparation.begin() + nextPoint);
      std::copy_n(m_impact.begin() + c.firstPoint, c.count, m_permutedImpact.begin() + nextPoint);
      std::copy_n(m_pseudoImpulse.begin() + c.firstPoint, c.count, m_permutedPseudoImpulse.begin() + nextPoint);
      c.firstPoint = nextPoint;
      nextPoint += c.count;
      m_permutedConstraints[si] = c;
      for (int side = 0; side < 2; ++side)
        m_permutedPred[si][side] = m_pred[ci][side] < 0 ? -1 : std::int32_t(storageOf[std::size_t(m_pred[ci][side])]);
    }
  });
  for (std::size_t ci = 0; ci < n; ++ci) m_logical[ci] = storageOf[ci];
  m_constraints.swap(m_permutedConstraints);
  m_points.swap(m_permutedPoints);
  m_geometry.swap(m_permutedGeometry);
  m_separation.swap(m_permutedSeparation);
  m_impact.swap(m_permutedImpact);
  m_pseudoImpulse.swap(m_permutedPseudoImpulse);
  m_pred.swap(m_permutedPred);
  for (std::uint32_t& ci : m_external) ci = storageOf[ci];
  for (RoundOffsetRows& r : m_roundOffset) r.constraint = storageOf[r.constraint];
  for (RimRows& r : m_rims) r.constraint = storageOf[r.constraint];
  // The pass counter runs on across steps, so the flags of an earlier
  // step are all below it and need no clearing (only a new array or a
  // wrapped counter starts from zero).
  if (n > m_doneCapacity) {
    m_doneCapacity = std::max(n, 2 * m_doneCapacity);
    m_done = std::make_unique<std::atomic<std::uint32_t>[]>(m_doneCapacity);
    m_pass = 0;
  }
  m_sweepSums.resize(n);
  m_levels = levels;
}

template <class Visit>
void ContactSolver::forEachOrdered(Visit&& visit) const {
  if (!threaded()) {
    for (std::uint32_t ci = 0; ci < m_constraints.size(); ++ci) visit(ci);
    return;
  }
  // Each thread runs its share in level order and waits, before a
  // constraint, until its predecessors of this pass are done (a thread's
  // own are; the other's are usually done by then). No deadlock: a thread
  // waits only for a lower level, which the other thread reaches first.
  if (m_pass == std::numeric_limits<std::uint32_t>::max()) {  // after 4e9 passes: clear and count again
    for (std::size_t ci = 0; ci < m_doneCapacity; ++ci) m_done[ci].store(0, std::memory_order_relaxed);
    m_pass = 0;
  }
  const std::uint32_t pass = ++m_pass;
  std::atomic<std::uint32_t>* done = m_done.get();
  m_pool->run([&](int t) {
    for (std::uint32_t ci = m_threadStart[std::size_t(t)]; ci < m_threadStart[std::size_t(t) + 1]; ++ci) {
      for (std::int32_t p : m_pred[ci]) {
        if (p < 0) continue;
        WorkerPool::Spin spin(m_pool->oversubscribed());
        while (done[p].load(std::memory_order_acquire) != pass) spin();
      }
      visit(ci);
      done[ci].store(pass, std::memory_order_release);
    }
  });
}

template <class Visit>
void ContactSolver::forEachShare(Visit&& visit) const {
  if (!threaded()) {
    visit(std::size_t(0), m_constraints.size());
    return;
  }
  m_pool->run([&](int t) { visit(std::size_t(m_threadStart[std::size_t(t)]), std::size_t(m_threadStart[std::size_t(t) + 1])); });
}

void ContactSolver::prepare(const std::vector<Manifold>& manifolds, const std::vector<Body>& bodies) {
  m_constraints.clear();
  m_points.clear();
  m_geometry.clear();
  m_separation.clear();
  m_impact.clear();
  m_pseudoImpulse.clear();
  m_rolling.clear();
  m_blocks.clear();
  m_roundOffset.clear();
  m_rims.clear();
  m_external.clear();
  m_place.clear();
  const Mat3 zero = Mat3::Zero();
  for (std::uint32_t mi = 0; mi < manifolds.size(); ++mi) {
    const Manifold& m = manifolds[mi];
    if (m.count == 0) continue;  // no rows (and m_place takes a constraint's first point)
    const Body& a = bodies[m.a];
    // The height field is side b of its manifolds: a static body at the
    // origin whose velocity slot is the extra one after the bodies.
    const bool field = m.b == kHeightFieldBody;
    const Body& b = field ? heightFieldBody() : bodies[m.b];
    Constraint c;
    c.movesA = takesImpulses(a);
    c.movesB = takesImpulses(b);
    if (!c.movesA && !c.movesB) continue;  // nothing to solve (asleep against static)
    // Static bodies and the height field have zero velocity for the whole
    // step (kinematic and sleeping ones may not: a script can set one).
    if (!c.movesA && a.type == BodyType::Static) c.fixedSide = 1;
    if (!c.movesB && (field || b.type == BodyType::Static)) c.fixedSide = 2;
    c.a = m.a;
    c.b = field ? std::uint32_t(bodies.size()) : m.b;
    c.manifold = mi;
    c.count = std::uint8_t(m.count);
    c.firstPoint = std::uint32_t(m_points.size());
    c.roundA = m.roundA;
    c.roundB = m.roundB;
    c.roundOffsetA = m.roundA && c.movesA && a.shape.type == ShapeType::Compound;
    c.roundOffsetB = m.roundB && c.movesB && !field && b.shape.type == ShapeType::Compound;
    const Real radiusA = c.roundOffsetA ? childShape(a.shape, m.childA).radius_m : 0;
    const Real radiusB = c.roundOffsetB ? childShape(b.shape, m.childB).radius_m : 0;
    c.invMassA = c.movesA ? a.invMass_per_kg : 0;
    c.invMassB = c.movesB ? b.invMass_per_kg : 0;
    const Mat3& IA = c.movesA ? a.invInertiaWorld : zero;
    const Mat3& IB = c.movesB ? b.invInertiaWorld : zero;
    // Tangent basis perpendicular to the normal.
    const Vec3 n = m.normal;
    Vec3 t0 = std::abs(n.x()) < Real(0.57) ? Vec3(Vec3::UnitX().cross(n)) : Vec3(Vec3::UnitY().cross(n));
    t0.normalize();
    const Vec3 t[2] = {t0, n.cross(t0)};
    c.normal = wide(n);
    c.tangent[0] = wide(t[0]);
    c.tangent[1] = wide(t[1]);
    c.friction = m.friction;
    c.restitution = m.restitution;
    c.rollingArm_m = m.rollingArm_m;
    const Real mass = c.invMassA + c.invMassB;
    for (int i = 0; i < m.count; ++i) {
      const ContactPoint& mp = m.points[i];
      ConstraintPoint p;
      PointGeometry g;
      g.rA = mp.point_m - a.position_m;
      g.rB = mp.point_m - b.position_m;
      // A sphere is touched on its surface along the normal through its
      // centre: its lever arm is the radius along n (a frictionless contact
      // never spins it). The manifold's point lies midway between the
      // surfaces, so a speculative contact's point is outside the sphere
      // and would give a longer arm: the ball then stops slipping at
      // v = w (r + s/2) and rolls too slowly after an impact.
      if (a.shape.type == ShapeType::Sphere) g.rA = n * a.shape.radius_m;
      if (b.shape.type == ShapeType::Sphere) g.rB = -n * b.shape.radius_m;
      // The same for a round child off the centre of mass: the lever runs
      // from its rolling centre (the manifold point lies midway between the
      // surfaces: a radius and half the gap inside) out by its radius.
      if (c.roundOffsetA) g.rA -= n * (mp.separation_m / 2);
      if (c.roundOffsetB) g.rB += n * (mp.separation_m / 2);
      const Vec3 rnA = g.rA.cross(n), rnB = g.rB.cross(n);
      const Vec3 inA = IA * rnA, inB = IB * rnB;
      p.rnA = wide(rnA);
      p.rnB = wide(rnB);
      p.inA = wide(inA);
      p.inB = wide(inB);
      Real k = mass + rnA.dot(inA) + rnB.dot(inB);
      p.normalMass = k > 0 ? 1 / k : 0;
      for (int j = 0; j < 2; ++j) {
        const Vec3 rtA = g.rA.cross(t[j]), rtB = g.rB.cross(t[j]);
        const Vec3 itA = IA * rtA, itB = IB * rtB;
        p.rtA[j] = wide(rtA);
        p.rtB[j] = wide(rtB);
        p.itA[j] = wide(itA);
        p.itB[j] = wide(itB);
        Real kt = mass + rtA.dot(itA) + rtB.dot(itB);
        p.tangentMass[j] = kt > 0 ? 1 / kt : 0;
        p.tangentImpulse[j] = mp.tangentImpulse[j];
      }
      // See roundOffsetA: rA / rB now hold the rolling centre.
      if (c.roundOffsetA) g.rA -= n * radiusA;
      if (c.roundOffsetB) g.rB += n * radiusB;
      p.normalImpulse = mp.normalImpulse;
      g.separation0_m = mp.separation_m;
      m_points.push_back(p);
      m_geometry.push_back(g);
      m_separation.push_back(mp.separation_m);
      m_impact.push_back(PointImpact{});
      m_pseudoImpulse.push_back(0);
    }
    if (m.rollingArm_m > 0) {
      RollingRows r;
      for (int k = 0; k < 3; ++k) {
        const Vec3 axis = k < 2 ? t[k] : n;
        const Vec3 iA = IA * axis, iB = IB * axis;
        r.iA[k] = wide(iA);
        r.iB[k] = wide(iB);
        Real kr = axis.dot(iA + iB);
        r.mass[k] = kr > 0 ? 1 / kr : 0;
      }
      c.rolling = std::int32_t(m_rolling.size());
      m_rolling.push_back(r);
    }
    // Round children off the centre of mass turn their levers every
    // substep, which a block built once per step would not follow.
    if (m.count >= 3 && !c.roundOffsetA && !c.roundOffsetB) prepareNormalBlock(c, m);
    if (!c.movesA || !c.movesB) m_external.push_back(std::uint32_t(m_constraints.size()));
    if (c.roundOffsetA || c.roundOffsetB)
      m_roundOffset.push_back({std::uint32_t(m_constraints.size()), IA, IB, radiusA, radiusB});
    const bool rimA = m.rimA && c.movesA, rimB = m.rimB && c.movesB && !field;
    if (rimA || rimB) {
      RimRows r;
      r.constraint = std::uint32_t(m_constraints.size());
      r.invInertiaA = IA;
      r.invInertiaB = IB;
      if (rimA) {
        r.orientationA = a.orientation.toRotationMatrix();
        r.radiusA_m = a.shape.radius_m;
        r.halfHeightA_m = a.shape.halfHeight_m;
        r.reachA0_m = n.dot(rimCylinder(r.orientationA, r.radiusA_m, r.halfHeightA_m).support(n));
      }
      if (rimB) {
        r.orientationB = b.orientation.toRotationMatrix();
        r.radiusB_m = b.shape.radius_m;
        r.halfHeightB_m = b.shape.halfHeight_m;
        r.reachB0_m = -n.dot(rimCylinder(r.orientationB, r.radiusB_m, r.halfHeightB_m).support(-n));
      }
      m_rims.push_back(r);
    }
    m_place.push_back(m.points[0].point_m);
    m_constraints.push_back(c);
  }
  buildSchedule(bodies.size() + 1);
}

void ContactSolver::prepareNormalBlock(Constraint& c, const Manifold& m) {
  // See "Normal blocks" at the top of this file. In double: K of a light box
  // under a heavy one mixes terms 1000x apart. Fixed 4 x 4 sizes, the rows
  // and columns past the manifold's points zero.
  const int count = m.count;
  const ConstraintPoint* pts = &m_points[c.firstPoint];
  const double mass = double(c.invMassA) + double(c.invMassB);
  Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
  for (int i = 0; i < count; ++i)
    for (int j = 0; j < count; ++j)
      K(i, j) = mass + narrow(pts[i].rnA).cast<double>().dot(narrow(pts[j].inA).cast<double>()) +
                narrow(pts[i].rnB).cast<double>().dot(narrow(pts[j].inB).cast<double>());
  // The points' coordinates in the contact plane, from their centroid, along
  // the principal axes of their spread.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int i = 0; i < count; ++i) centroid += m.points[i].point_m.cast<double>();
  centroid /= count;
  const Eigen::Vector3d t0 = narrow(c.tangent[0]).cast<double>(), t1 = narrow(c.tangent[1]).cast<double>();
  Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
  Eigen::Vector2d uv[kMaxManifoldPoints];
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d d = m.points[i].point_m.cast<double>() - centroid;
    uv[i] = Eigen::Vector2d(d.dot(t0), d.dot(t1));
    spread += uv[i] * uv[i].transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axes;
  axes.computeDirect(spread);
  const double major = axes.eigenvalues()(1), minor = axes.eigenvalues()(0);
  // Points that coincide (to a micrometre) give one row: nothing to block.
  if (!(major > count * kBlockCoincident_m2)) return;
  const int rank = minor > kBlockCollinear * major ? 3 : 2;
  // A null space of more than one dimension (four points on a line) is
  // left to the sweep.
  if (count - rank > 1) return;
  // P: K = P G P^T with P = [1, coordinates]; P^T P is diagonal (N, major,
  // minor), so P^+ = (P^T P)^-1 P^T is P's columns over those.
  Eigen::Matrix<double, 4, 3> P = Eigen::Matrix<double, 4, 3>::Zero();
  for (int i = 0; i < count; ++i) {
    P(i, 0) = 1;
    P(i, 1) = uv[i].dot(axes.eigenvectors().col(1));
    if (rank == 3) P(i, 2) = uv[i].dot(axes.eigenvectors().col(0));
  }
  const double diag[3] = {double(count), major, minor};
  Eigen::Matrix<double, 3, 4> Pplus = Eigen::Matrix<double, 3, 4>::Zero();
  for (int k = 0; k < rank; ++k) Pplus.row(k) = P.col(k).transpose() / diag[k];
  Eigen::Matrix3d G = Pplus * K * Pplus.transpose();
  // A body that cannot turn about some axis (zero inverse inertia) leaves G
  // singular: no block.
  Eigen::Vector3d gl;
  if (rank == 3) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> e;
    e.computeDirect(G, Eigen::EigenvaluesOnly);
    gl = e.eigenvalues();
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> e;
    e.computeDirect(G.topLeftCorner<2, 2>().eval(), Eigen::EigenvaluesOnly);
    gl = Eigen::Vector3d(e.eigenvalues()(0), e.eigenvalues()(1), 0);
  }
  if (!(gl(0) > kBlockSingular * gl(rank - 1))) return;
  Eigen::Matrix3d Ginv = Eigen::Matrix3d::Zero();
  if (rank == 3) Ginv = G.inverse();
  else Ginv.topLeftCorner<2, 2>() = G.topLeftCorner<2, 2>().inverse();
  const Eigen::Matrix4d Kplus = Pplus.transpose() * Ginv * Pplus;
  NormalBlock b;
  for (int i = 0; i < count; ++i)
    for (int j = 0; j < count; ++j) b.invK[i][j] = Real(Kplus(i, j));
  if (count > rank) {
    // The twist: the column of I - P P^+ (the projector on K's null space)
    // with the largest norm, normalised.
    const Eigen::Matrix4d Q = Eigen::Matrix4d::Identity() - P * Pplus;
    int best = 0;
    for (int j = 1; j < count; ++j)
      if (Q.col(j).head(count).squaredNorm() > Q.col(best).head(count).squaredNorm()) best = j;
    const double len = Q.col(best).head(count).norm();
    for (int i = 0; i < count; ++i) b.twist[i] = Real(Q(i, best) / len);
  }
  c.block = std::int32_t(m_blocks.size());
  m_blocks.push_back(b);
}

void ContactSolver::warmStart(std::vector<SolverVelocity>& vel) const {
  forEachOrdered([&](std::uint32_t ci) {
    const Constraint& c = m_constraints[ci];
    SolverVelocity& A = vel[c.a];
    SolverVelocity& B = vel[c.b];
    const ConstraintPoint* pts = &m_points[c.firstPoint];
    Vec4r P = Vec4r::Zero(), LA = Vec4r::Zero(), LB = Vec4r::Zero();
    for (int i = 0; i < c.count; ++i) {
      const ConstraintPoint& p = pts[i];
      const Real ln = p.normalImpulse, l0 = p.tangentImpulse[0], l1 = p.tangentImpulse[1];
      P += ln * c.normal + l0 * c.tangent[0] + l1 * c.tangent[1];
      LA += ln * p.inA + l0 * p.itA[0] + l1 * p.itA[1];
      LB += ln * p.inB + l0 * p.itB[0] + l1 * p.itB[1];
    }
    if (c.movesA) {
      A.linear -= c.invMassA * P;
      A.angular -= LA;
    }
    if (c.movesB) {
      B.linear += c.invMassB * P;
      B.angular += LB;
    }
  });
}

void ContactSolver::turnRoundOffsetLevers(const std::vector<SolverPose>& pose) {
  for (const RoundOffsetRows& r : m_roundOffset) {
    const Constraint& c = m_constraints[r.constraint];
    const Vec3 n = narrow(c.normal);
    const Vec3 t[2] = {narrow(c.tangent[0]), narrow(c.tangent[1])};
    const Real mass = c.invMassA + c.invMassB;
    ConstraintPoint* pts = &m_points[c.firstPoint];
    const PointGeometry* geo = &m_geometry[c.firstPoint];
    for (int i = 0; i < c.count; ++i) {
      ConstraintPoint& p = pts[i];
      const PointGeometry& g = geo[i];
      if (c.roundOffsetA) {
        const Vec3 lever = pose[c.a].dq * g.rA + n * r.radiusA_m;
        p.rnA = wide(Vec3(lever.cross(n)));
        p.inA = wide(Vec3(r.invInertiaA * narrow(p.rnA)));
        for (int j = 0; j < 2; ++j) {
          p.rtA[j] = wide(Vec3(lever.cross(t[j])));
          p.itA[j] = wide(Vec3(r.invInertiaA * narrow(p.rtA[j])));
        }
      }
      if (c.roundOffsetB) {
        const Vec3 lever = pose[c.b].dq * g.rB - n * r.radiusB_m;
        p.rnB = wide(Vec3(lever.cross(n)));
        p.inB = wide(Vec3(r.invInertiaB * narrow(p.rnB)));
        for (int j = 0; j < 2; ++j) {
          p.rtB[j] = wide(Vec3(lever.cross(t[j])));
          p.itB[j] = wide(Vec3(r.invInertiaB * narrow(p.rtB[j])));
        }
      }
      const Real k = mass + narrow(p.rnA).dot(narrow(p.inA)) + narrow(p.rnB).dot(narrow(p.inB));
      p.normalMass = k > 0 ? 1 / k : 0;
      for (int j = 0; j < 2; ++j) {
        const Real kt = mass + narrow(p.rtA[j]).dot(narrow(p.itA[j])) + narrow(p.rtB[j]).dot(narrow(p.itB[j]));
        p.tangentMass[j] = kt > 0 ? 1 / kt : 0;
      }
    }
  }
}

void ContactSolver::turnRimRows(const std::vector<SolverPose>& pose) {
  // See "Rim contacts" at the top of this file.
  for (const RimRows& r : m_rims) {
    const Constraint& c = m_constraints[r.constraint];
    const Vec3 n = narrow(c.normal);
    const Vec3 t[2] = {narrow(c.tangent[0]), narrow(c.tangent[1])};
    const Real mass = c.invMassA + c.invMassB;
    ConstraintPoint& p = m_points[c.firstPoint];
    const PointGeometry& g = m_geometry[c.firstPoint];
    const Mat3 RA = pose[c.a].dq.toRotationMatrix(), RB = pose[c.b].dq.toRotationMatrix();
    const Mat3 IA = RA * r.invInertiaA * RA.transpose(), IB = RB * r.invInertiaB * RB.transpose();
    // The separation: as for any point (updateSeparations), except that a
    // rim side's point is its support, whose height follows the axis, not
    // a material point on the rim (which rises as it turns away).
    Real gap = g.separation0_m + n.dot(pose[c.b].dp - pose[c.a].dp);
    if (r.radiusA_m > 0) {
      const Vec3 lever = rimCylinder(RA * r.orientationA, r.radiusA_m, r.halfHeightA_m).support(n);
      gap -= n.dot(lever) - r.reachA0_m;
      p.rnA = wide(Vec3(lever.cross(n)));
      for (int j = 0; j < 2; ++j) p.rtA[j] = wide(Vec3(lever.cross(t[j])));
    } else if (!(c.roundA && !c.roundOffsetA)) {
      gap -= n.dot(pose[c.a].dq * g.rA - g.rA);
    }
    if (r.radiusB_m > 0) {
      const Vec3 lever = rimCylinder(RB * r.orientationB, r.radiusB_m, r.halfHeightB_m).support(-n);
      gap -= -n.dot(lever) - r.reachB0_m;
      p.rnB = wide(Vec3(lever.cross(n)));
      for (int j = 0; j < 2; ++j) p.rtB[j] = wide(Vec3(lever.cross(t[j])));
    } else if (!(c.roundB && !c.roundOffsetB)) {
      gap += n.dot(pose[c.b].dq * g.rB - g.rB);
    }
    m_separation[c.firstPoint] = gap;
    p.inA = wide(Vec3(IA * narrow(p.rnA)));
    p.inB = wide(Vec3(IB * narrow(p.rnB)));
    const Real k = mass + narrow(p.rnA).dot(narrow(p.inA)) + narrow(p.rnB).dot(narrow(p.inB));
    p.normalMass = k > 0 ? 1 / k : 0;
    for (int j = 0; j < 2; ++j) {
      p.itA[j] = wide(Vec3(IA * narrow(p.rtA[j])));
      p.itB[j] = wide(Vec3(IB * narrow(p.rtB[j])));
      const Real kt = mass + narrow(p.rtA[j]).dot(narrow(p.itA[j])) + narrow(p.rtB[j]).dot(narrow(p.itB[j]));
      p.tangentMass[j] = kt > 0 ? 1 / kt : 0;
    }
    if (c.rolling >= 0) {
      RollingRows& rr = m_rolling[std::size_t(c.rolling)];
      for (int k = 0; k < 3; ++k) {
        const Vec3 axis = k < 2 ? t[k] : n;
        const Vec3 iA = IA * axis, iB = IB * axis;
        rr.iA[k] = wide(iA);
        rr.iB[k] = wide(iB);
        const Real kr = axis.dot(iA + iB);
        rr.mass[k] = kr > 0 ? 1 / kr : 0;
      }
    }
  }
}

void ContactSolver::updateSeparations(const std::vector<SolverPose>& pose) {
  if (!m_roundOffset.empty()) turnRoundOffsetLevers(pose);
  forEachShare([&](std::size_t begin, std::size_t end) {
    for (std::size_t ci = begin; ci < end; ++ci) {
      const Constraint& c = m_constraints[ci];
      const SolverPose& PA = pose[c.a];
      const SolverPose& PB = pose[c.b];
      const Vec3 n = narrow(c.normal);
      const Real base = n.dot(PB.dp - PA.dp);
      // n . (dq r - r) = (dq^-1 n - n) . r: one rotation per side per
      // constraint instead of one per point. Round shapes centred on their
      // body keep their anchor (they roll on it); a round child off the centre
      // of mass turns its rolling centre (rA / rB hold it, see roundOffsetA).
      const Vec3 nA = c.roundA && !c.roundOffsetA ? Vec3::Zero() : Vec3(PA.dq.conjugate() * n - n);
      const Vec3 nB = c.roundB && !c.roundOffsetB ? Vec3::Zero() : Vec3(PB.dq.conjugate() * n - n);
      const PointGeometry* geo = &m_geometry[c.firstPoint];
      Real* separation = &m_separation[c.firstPoint];
      for (int i = 0; i < c.count; ++i) {
        const PointGeometry& g = geo[i];
        separation[i] = g.separation0_m + base + nB.dot(g.rB) - nA.dot(g.rA);
      }
    }
  });
  // Rim contacts overwrite their separation (turnRimRows).
  if (!m_rims.empty()) turnRimRows(pose);
}

void ContactSolver::recordFreeVelocities(const std::vector<SolverVelocity>& vel) {
  forEachShare([&](std::size_t begin, std::size_t end) {
    for (std::size_t ci = begin; ci < end; ++ci) {
      const Constraint& c = m_constraints[ci];
      const SolverVelocity& A = vel[c.a];
      const SolverVelocity& B = vel[c.b];
      const ConstraintPoint* pts = &m_points[c.firstPoint];
      PointImpact* impact = &m_impact[c.firstPoint];
      const Vec4r dv = B.linear - A.linear;
      for (int i = 0; i < c.count; ++i) {
        const ConstraintPoint& p = pts[i];
        if (impact[i].maxNormalImpulse == 0)
          impact[i].freeVelocity0_mps = rowDot(c.normal, dv, p.rnB, B.angular, p.rnA, A.angular);
      }
    }
  });
}

void ContactSolver::captureApproachSpeeds(const std::vector<SolverVelocity>& vel, Real h) {
  // See "Restitution" at the top of this file: u0 is the normal velocity
  // at the start of the substep, a the free relative acceleration, s the
  // separation; the free motion reaches s = 0 at u_c^2 = u0^2 - 2 a s.
  forEachShare([&](std::size_t begin, std::size_t end) {
    for (std::size_t ci = begin; ci < end; ++ci) {
      const Constraint& c = m_constraints[ci];
      const SolverVelocity& A = vel[c.a];
      const SolverVelocity& B = vel[c.b];
      const ConstraintPoint* pts = &m_points[c.firstPoint];
      PointImpact* impact = &m_impact[c.firstPoint];
      const Real* separation = &m_separation[c.firstPoint];
      const Vec4r dv = B.linear - A.linear;
      for (int i = 0; i < c.count; ++i) {
        const ConstraintPoint& p = pts[i];
        PointImpact& q = impact[i];
        if (q.maxNormalImpulse != 0) continue;
        const Real v1 = rowDot(c.normal, dv, p.rnB, B.angular, p.rnA, A.angular);
        const Real a = (v1 - q.freeVelocity0_mps) / h;
        const Real u0 = q.freeVelocity0_mps + a * h / 2;
        Real uc = std::min<Real>(u0, 0);  // touching already: the impact is now
        if (separation[i] > 0) {
          const Real reach2 = u0 * u0 - 2 * a * separation[i];
          uc = (u0 < 0 || a < 0) && reach2 > 0 ? -std::sqrt(reach2) : Real(0);
        }
        q.approachAcceleration_mps2 = a;
        q.relativeVelocity_mps = uc;
      }
    }
  });
}

void ContactSolver::resetSubstepImpulses() {
  for (RollingRows& r : m_rolling) r.impulse[0] = r.impulse[1] = r.impulse[2] = 0;
  forEachShare([&](std::size_t begin, std::size_t end) {
    for (std::size_t ci = begin; ci < end; ++ci) {
      const Constraint& c = m_constraints[ci];
      std::fill_n(m_pseudoImpulse.begin() + c.firstPoint, c.count, Real(0));
    }
  });
}

/// What every constraint of one sweep shares.
struct ContactSolver::SweepConstants {
  Real invH = 0, biasRate = 0, softMassScale = 1, softImpulseScale = 0;
  Real linearSlop_m = 0, maxPushout_mps = 0, baumgarte = 0;
  bool soft = false, split = false;
};

namespace {

/// Row times velocity with one side fixed (kFixedSide 1: A, 2: B; its
/// velocity is zero, so its terms are left out, not multiplied by zero).
template <int kFixedSide>
inline Real rowDotFixed(const Vec4r& n, const Vec4r& vA, const Vec4r& vB, const Vec4r& jB, const Vec4r& wB,
                        const Vec4r& jA, const Vec4r& wA) {
  if constexpr (kFixedSide == 1) return (n.cwiseProduct(vB) + jB.cwiseProduct(wB)).sum();
  else if constexpr (kFixedSide == 2) return -(n.cwiseProduct(vA) + jA.cwiseProduct(wA)).sum();
  else return rowDot(n, vB - vA, jB, wB, jA, wA);
}

}  // namespace

template <int kFixedSide>
bool ContactSolver::solveNormalBlock(const Constraint& c, Vec4r& vA, Vec4r& wA, Vec4r& vB, Vec4r& wB, Real invH,
                                     Real& residual) {
  // See "Normal blocks" at the top of this file: lambda' = lambda - K^+ r,
  // accepted when it is a solution (no pull, r in K's range).
  constexpr bool moveA = kFixedSide != 1, moveB = kFixedSide != 2;
  const NormalBlock& b = m_blocks[std::size_t(c.block)];
  ConstraintPoint* pts = &m_points[c.firstPoint];
  const Real* separation = &m_separation[c.firstPoint];
  const int count = c.count;
  const Vec4r n = c.normal;
  Real r[kMaxManifoldPoints], lambda[kMaxManifoldPoints];
  Real twistPart = 0, size2 = 0;
  for (int i = 0; i < count; ++i) {
    const ConstraintPoint& p = pts[i];
    const Real vn = rowDotFixed<kFixedSide>(n, vA, vB, p.rnB, wB, p.rnA, wA);
    r[i] = vn + (separation[i] > 0 ? separation[i] * invH : Real(0));
    twistPart += b.twist[i] * r[i];
    size2 += r[i] * r[i];
  }
  // The part of r along the twist is what no impulse on this manifold can
  // change: beyond round-off, some point must let go, which the sweep finds.
  if (twistPart * twistPart > kBlockConsistency * kBlockConsistency * size2) return false;
  bool negative = false;
  for (int i = 0; i < count; ++i) {
    Real d = 0;
    for (int j = 0; j < count; ++j) d += b.invK[i][j] * r[j];
    lambda[i] = pts[i].normalImpulse - d;
    negative = negative || lambda[i] < 0;
  }
  if (negative) {
    // Move along the twist (which changes no velocity) to the nearest
    // distribution without pull, if there is one.
    Real lo = -std::numeric_limits<Real>::infinity(), hi = std::numeric_limits<Real>::infinity();
    for (int i = 0; i < count; ++i) {
      const Real t = b.twist[i];
      if (t > 0) lo = std::max(lo, -lambda[i] / t);
      else if (t < 0) hi = std::min(hi, -lambda[i] / t);
      else if (lambda[i] < 0) return false;
    }
    if (!(lo <= hi)) return false;
    const Real s = std::clamp<Real>(0, lo, hi);
    for (int i = 0; i < count; ++i) lambda[i] = std::max<Real>(lambda[i] + s * b.twist[i], 0);
  }
  const Real mA = c.invMassA, mB = c.invMassB;
  PointImpact* impact = &m_impact[c.firstPoint];
  for (int i = 0; i < count; ++i) {
    ConstraintPoint& p = pts[i];
    const Real impulse = lambda[i] - p.normalImpulse;
    p.normalImpulse = lambda[i];
    impact[i].maxNormalImpulse = std::max(impact[i].maxNormalImpulse, impulse);
    residual += impulse * impulse;
    const Vec4r P = impulse * n;
    if constexpr (moveA) vA -= mA * P, wA -= impulse * p.inA;
    if constexpr (moveB) vB += mB * P, wB += impulse * p.inB;
  }
  return true;
}

template <int kFixedSide>
void ContactSolver::solveConstraint(const Constraint& c, std::vector<SolverVelocity>& vel,
                                    std::vector<SolverVelocity>& pseudo, const SweepConstants& k, Real& residual,
                                    Real& magnitude) {
  constexpr bool moveA = kFixedSide != 1, moveB = kFixedSide != 2;
  SolverVelocity& A = vel[c.a];
  SolverVelocity& B = vel[c.b];
  Vec4r vA = Vec4r::Zero(), wA = Vec4r::Zero(), vB = Vec4r::Zero(), wB = Vec4r::Zero();
  if constexpr (moveA) vA = A.linear, wA = A.angular;
  if constexpr (moveB) vB = B.linear, wB = B.angular;
  const Real mA = c.invMassA, mB = c.invMassB;
  const Vec4r n = c.normal;
  ConstraintPoint* pts = &m_points[c.firstPoint];
  const Real* separation = &m_separation[c.firstPoint];
  PointImpact* impact = &m_impact[c.firstPoint];
  const int count = c.count;
  Real totalNormal = 0;
  const bool blockSolved = c.block >= 0 && !k.soft && solveNormalBlock<kFixedSide>(c, vA, wA, vB, wB, k.invH, residual);
  for (int i = 0; i < count && !blockSolved; ++i) {
    ConstraintPoint& p = pts[i];
    const Real sep = separation[i];
    Real bias = 0, massScale = 1, impulseScale = 0;
    if (sep > 0) {
      bias = sep * k.invH;  // speculative
    } else if (k.soft) {
      bias = std::max(k.biasRate * std::min<Real>(sep + k.linearSlop_m, 0), -k.maxPushout_mps);
      massScale = k.softMassScale;
      impulseScale = k.softImpulseScale;
    }
    const Real vn = rowDotFixed<kFixedSide>(n, vA, vB, p.rnB, wB, p.rnA, wA);
    Real impulse = -p.normalMass * massScale * (vn + bias) - impulseScale * p.normalImpulse;
    const Real newImpulse = std::max<Real>(p.normalImpulse + impulse, 0);
    impulse = newImpulse - p.normalImpulse;
    p.normalImpulse = newImpulse;
    impact[i].maxNormalImpulse = std::max(impact[i].maxNormalImpulse, impulse);
    residual += impulse * impulse;
    const Vec4r P = impulse * n;
    if constexpr (moveA) vA -= mA * P, wA -= impulse * p.inA;
    if constexpr (moveB) vB += mB * P, wB += impulse * p.inB;
  }
  for (int i = 0; i < count; ++i) {
    totalNormal += pts[i].normalImpulse;
    magnitude += pts[i].normalImpulse * pts[i].normalImpulse;
  }
  // Friction, clamped to the cone.
  const Vec4r t0 = c.tangent[0], t1 = c.tangent[1];
  for (int i = 0; i < count; ++i) {
    ConstraintPoint& p = pts[i];
    const Real vt0 = rowDotFixed<kFixedSide>(t0, vA, vB, p.rtB[0], wB, p.rtA[0], wA);
    const Real vt1 = rowDotFixed<kFixedSide>(t1, vA, vB, p.rtB[1], wB, p.rtA[1], wA);
    const Real old0 = p.tangentImpulse[0], old1 = p.tangentImpulse[1];
    Real l0 = old0 - p.tangentMass[0] * vt0;
    Real l1 = old1 - p.tangentMass[1] * vt1;
    clampToFrictionCone(c.friction * p.normalImpulse, l0, l1);
    p.tangentImpulse[0] = l0;
    p.tangentImpulse[1] = l1;
    const Real d0 = l0 - old0, d1 = l1 - old1;
    residual += d0 * d0 + d1 * d1;
    const Vec4r P = d0 * t0 + d1 * t1;
    if constexpr (moveA) vA -= mA * P, wA -= d0 * p.itA[0] + d1 * p.itA[1];
    if constexpr (moveB) vB += mB * P, wB += d0 * p.itB[0] + d1 * p.itB[1];
  }
  if (c.rolling >= 0) {
    RollingRows& r = m_rolling[std::size_t(c.rolling)];
    const Vec4r dw = wB - wA;
    const Real old0 = r.impulse[0], old1 = r.impulse[1], old2 = r.impulse[2];
    Real r0 = old0 - r.mass[0] * dw.dot(t0);
    Real r1 = old1 - r.mass[1] * dw.dot(t1);
    const Real maxR = c.rollingArm_m * totalNormal, len2 = r0 * r0 + r1 * r1;
    if (len2 > maxR * maxR) {
      const Real scale = maxR / std::sqrt(len2);
      r0 *= scale;
      r1 *= scale;
    }
    const Real r2 = std::clamp(old2 - r.mass[2] * dw.dot(n), -maxR, maxR);
    r.impulse[0] = r0;
    r.impulse[1] = r1;
    r.impulse[2] = r2;
    const Real d0 = r0 - old0, d1 = r1 - old1, d2 = r2 - old2;
    residual += d0 * d0 + d1 * d1 + d2 * d2;
    if constexpr (moveA) wA -= d0 * r.iA[0] + d1 * r.iA[1] + d2 * r.iA[2];
    if constexpr (moveB) wB += d0 * r.iB[0] + d1 * r.iB[1] + d2 * r.iB[2];
  }
  if (moveA && c.movesA) {
    A.linear = vA;
    A.angular = wA;
  }
  if (moveB && c.movesB) {
    B.linear = vB;
    B.angular = wB;
  }
  if (!k.split) return;
  // Split-impulse position correction: pseudo-velocities that remove
  // beta * (depth - slop) / h of the overlap, accumulated per substep.
  // Pseudo-velocities are zero for bodies that take no impulses.
  SolverVelocity& PA = pseudo[c.a];
  SolverVelocity& PB = pseudo[c.b];
  Real* pseudoImpulses = &m_pseudoImpulse[c.firstPoint];
  for (int i = 0; i < count; ++i) {
    ConstraintPoint& p = pts[i];
    const Real depth = -(separation[i] + k.linearSlop_m);
    Real& pseudoImpulse = pseudoImpulses[i];
    if (depth <= 0 && pseudoImpulse == 0) continue;
    const Real target = std::min(k.baumgarte * k.invH * std::max<Real>(depth, 0), k.maxPushout_mps);
    const Real pvn = rowDotFixed<kFixedSide>(n, PA.linear, PB.linear, p.rnB, PB.angular, p.rnA, PA.angular);
    const Real newImpulse = std::max<Real>(pseudoImpulse + p.normalMass * (target - pvn), 0);
    const Real dl = newImpulse - pseudoImpulse;
    pseudoImpulse = newImpulse;
    residual += dl * dl;
    if (moveA && c.movesA) {
      PA.linear -= (mA * dl) * n;
      PA.angular -= dl * p.inA;
    }
    if (moveB && c.movesB) {
      PB.linear += (mB * dl) * n;
      PB.angular += dl * p.inB;
    }
  }
}

Real ContactSolver::solve(std::vector<SolverVelocity>& vel, std::vector<SolverVelocity>& pseudo,
                          const SolverSettings& s, bool useBias) {
  Real residual = 0, magnitude = 0;
  // Soft constraint coefficients (Box2D v3 b2MakeSoft).
  const Real hertz = std::min(s.contactHertz, Real(0.25) / s.h);
  const Real omega = 2 * kPi * hertz, zeta = s.contactDampingRatio;
  const Real a1 = 2 * zeta + s.h * omega, a2 = s.h * omega * a1, a3 = 1 / (1 + a2);
  SweepConstants k;
  k.biasRate = omega / a1;
  k.softMassScale = a2 * a3;
  k.softImpulseScale = a3;
  k.invH = 1 / s.h;
  k.linearSlop_m = s.linearSlop_m;
  k.maxPushout_mps = s.maxPushout_mps;
  k.baumgarte = s.baumgarte;
  k.soft = useBias && s.softContacts;
  k.split = useBias && !s.softContacts;
  // Each constraint's sums on their own, then added in index order: the
  // same with a pool as without ("Threads" at the top of this file).
  auto one = [&](std::uint32_t ci, Real& r, Real& m) {
    const Constraint& c = m_constraints[ci];
    if (c.fixedSide == 1) solveConstraint<1>(c, vel, pseudo, k, r, m);
    else if (c.fixedSide == 2) solveConstraint<2>(c, vel, pseudo, k, r, m);
    else solveConstraint<0>(c, vel, pseudo, k, r, m);
  };
  if (threaded()) {
    forEachOrdered([&](std::uint32_t ci) {
      std::array<Real, 2>& sums = m_sweepSums[ci];
      sums = {0, 0};
      one(ci, sums[0], sums[1]);
    });
    for (std::uint32_t ci : m_logical) {
      residual += m_sweepSums[ci][0];
      magnitude += m_sweepSums[ci][1];
    }
  } else {
    for (std::uint32_t ci = 0; ci < m_constraints.size(); ++ci) {
      Real r = 0, m = 0;
      one(ci, r, m);
      residual += r;
      magnitude += m;
    }
  }
  m_lastMagnitude = magnitude;
  return residual;
}

Eigen::Vector3d ContactSolver::applyRestitution(std::vector<SolverVelocity>& vel, const SolverSettings& s) {
  Eigen::Vector3d external = Eigen::Vector3d::Zero();
  // The points that first pushed in this substep and approached fast enough.
  bool any = false;
  for (const Constraint& c : m_constraints) {
    if (c.restitution == 0) continue;
    PointImpact* impact = &m_impact[c.firstPoint];
    for (int i = 0; i < c.count; ++i) {
      PointImpact& q = impact[i];
      q.bouncing = !q.bounced && q.maxNormalImpulse > 0 && q.relativeVelocity_mps < -s.restitutionThreshold_mps;
      any = any || q.bouncing;
    }
  }
  if (!any) return external;
  // Gauss-Seidel over the bouncing points. More than one pass converges to
  // the simultaneous-impact solution, which in clumps of fast spheres gains
  // energy (measured at the top of this file), so the default is one pass.
  for (int it = 0; it < std::max(1, s.restitutionIterations); ++it) {
    bool changed = false;
    // In the sequential order (storage is in the threads' order with threads).
    for (std::size_t k = 0; k < m_constraints.size(); ++k) {
      const Constraint& c = m_constraints[m_logical.empty() ? k : m_logical[k]];
      if (c.restitution == 0) continue;
      SolverVelocity& A = vel[c.a];
      SolverVelocity& B = vel[c.b];
      ConstraintPoint* pts = &m_points[c.firstPoint];
      const Real* separation = &m_separation[c.firstPoint];
      const PointImpact* impact = &m_impact[c.firstPoint];
      const Vec4r& n = c.normal;
      for (int i = 0; i < c.count; ++i) {
        ConstraintPoint& p = pts[i];
        const PointImpact& q = impact[i];
        if (!q.bouncing) continue;
        // Newton's law at the instant of impact (-e u_c leaving the
        // surface), carried by the free motion to where the point is now
        // (separation s, at most a substep's travel from touching):
        // u^2 = e^2 u_c^2 + 2 a s; then written as the velocity that the
        // next substep's forces turn into u at the substep boundary.
        const Real a = q.approachAcceleration_mps2, e = c.restitution;
        const Real u2 = e * e * q.relativeVelocity_mps * q.relativeVelocity_mps + 2 * a * separation[i];
        const Real target = std::sqrt(std::max<Real>(u2, 0)) - a * s.h / 2;
        const Real vn = rowDot(n, B.linear - A.linear, p.rnB, B.angular, p.rnA, A.angular);
        const Real newImpulse = std::max<Real>(p.normalImpulse - p.normalMass * (vn - target), 0);
        const Real dn = newImpulse - p.normalImpulse;
        p.normalImpulse = newImpulse;
        // Coulomb friction over the whole impact impulse (compression and
        // restitution): the tangential impulse that stops the slip, within
        // the cone of the total normal impulse. A ball stops slipping and
        // rolls if the cone allows it (Routh's rolling transition).
        const Vec4r dvt = B.linear - A.linear;
        const Real vt0 = rowDot(c.tangent[0], dvt, p.rtB[0], B.angular, p.rtA[0], A.angular);
        const Real vt1 = rowDot(c.tangent[1], dvt, p.rtB[1], B.angular, p.rtA[1], A.angular);
        const Real old0 = p.tangentImpulse[0], old1 = p.tangentImpulse[1];
        Real l0 = old0 - p.tangentMass[0] * vt0, l1 = old1 - p.tangentMass[1] * vt1;
        clampToFrictionCone(c.friction * p.normalImpulse, l0, l1);
        p.tangentImpulse[0] = l0;
        p.tangentImpulse[1] = l1;
        const Real d0 = l0 - old0, d1 = l1 - old1;
        if (dn == 0 && d0 == 0 && d1 == 0) continue;
        changed = true;
        const Vec4r P = dn * n + d0 * c.tangent[0] + d1 * c.tangent[1];
        if (c.movesA) {
          A.linear -= c.invMassA * P;
          A.angular -= dn * p.inA + d0 * p.itA[0] + d1 * p.itA[1];
        }
        if (c.movesB) {
          B.linear += c.invMassB * P;
          B.angular += dn * p.inB + d0 * p.itB[0] + d1 * p.itB[1];
        }
        if (!c.movesA || !c.movesB) {
          const Eigen::Vector3d Pd = narrow(P).cast<double>();
          external += c.movesB ? Pd : Eigen::Vector3d(-Pd);
        }
      }
    }
    if (!changed) break;
  }
  // The impact is over: the next substep must not warm start its impulse
  // (it would push the separating bodies apart again before the solve takes
  // it back). The event keeps the impact's size.
  for (std::size_t i = 0; i < m_points.size(); ++i) {
    PointImpact& q = m_impact[i];
    if (!q.bouncing) continue;
    ConstraintPoint& p = m_points[i];
    q.bouncing = false;
    q.bounced = true;
    p.impactImpulse = std::max(p.impactImpulse, p.normalImpulse);
    p.normalImpulse = 0;
    p.tangentImpulse[0] = p.tangentImpulse[1] = 0;
  }
  return external;
}

Eigen::Vector3d ContactSolver::externalImpulse() const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::uint32_t ci : m_external) {
    const Constraint& c = m_constraints[ci];
    Real ln = 0, l0 = 0, l1 = 0;
    const ConstraintPoint* pts = &m_points[c.firstPoint];
    for (int i = 0; i < c.count; ++i) {
      ln += pts[i].normalImpulse;
      l0 += pts[i].tangentImpulse[0];
      l1 += pts[i].tangentImpulse[1];
    }
    // What the fixed side gives the moving side: +P on b, -P on a.
    Eigen::Vector3d P = narrow(ln * c.normal + l0 * c.tangent[0] + l1 * c.tangent[1]).cast<double>();
    sum += c.movesB ? P : Eigen::Vector3d(-P);
  }
  return sum;
}

void ContactSolver::store(std::vector<Manifold>& manifolds) const {
  for (const Constraint& c : m_constraints) {
    Manifold& m = manifolds[c.manifold];
    for (int i = 0; i < c.count; ++i) {
      const ConstraintPoint& p = m_points[c.firstPoint + i];
      m.points[i].normalImpulse = p.normalImpulse;
      m.points[i].tangentImpulse[0] = p.tangentImpulse[0];
      m.points[i].tangentImpulse[1] = p.tangentImpulse[1];
      m.points[i].impactImpulse = std::max(p.impactImpulse, p.normalImpulse);
    }
  }
}

}  // namespace tumble::physics
