// JointSystem::saveState / restoreState: the joints' state between two
// steps as exact bits, for snapshots of a running scene (app/scene_state.h).
//
// What a later step reads and so must come back bit for bit:
//   - every joint slot: the definition as it is now (setMotor and
//     setWorldAnchor change it), generation, liveness, the last forces; the
//     free list (which slot the next joint gets) and the joint order;
//   - the solver asked for and the one running (past the Lagrange cost cap
//     the impulse solver stands in);
//   - Lagrange: per body slot the velocity the joints last left it with and
//     when a contact last moved it (the next solve's q' and the compliance
//     of contact), the step counter those are compared with, the substeps'
//     clock, and the results of the last step not yet collected (forces per
//     joint, joints found broken);
//   - impulse: the accumulated impulses per joint (warm starts) and the last
//     step's outputs (forces, broken flags);
//   - the error and cost-cap figures the run report reads.
// Everything else is rebuilt by each step from these and the World (rows,
// the sparse system and its factorization, the impulse solver's geometry).
#include <algorithm>
#include <cmath>

#include "core/byte_stream.h"
#include "physics/internal/impulse_joints.h"
#include "physics/internal/lagrange_solver.h"
#include "physics/joints/joint_system.h"

namespace tumble::physics {

namespace {

constexpr std::uint32_t kStateMagic = 0x544a4e54;  // "TJNT"
constexpr std::uint32_t kStateVersion = 1;
constexpr std::size_t kMaxSlots = std::size_t(1) << 24;

static_assert(kBitwise<JointDef>);
static_assert(kBitwise<JointSettings>);
static_assert(kBitwise<JointBreakEvent>);
static_assert(kBitwise<JointSolveStats>);
static_assert(kBitwise<JointSystem::Impl::Memo>);

}  // namespace

std::string JointSystem::saveState() const {
  static_assert(kBitwise<Slot>);
  const Impl& im = *m_impl;
  TUMBLE_ASSERT(!im.inStep, "JointSystem::saveState inside a step");
  ByteWriter w;
  w.pod(kStateMagic);
  w.pod(kStateVersion);
  w.pod(m_settings);
  w.pod(std::uint8_t(runningSolver()));
  w.vec(m_slots);
  w.vec(m_freeList);
  w.pod(std::int32_t(m_jointCount));
  w.pod(std::uint8_t(m_orderDirty));
  w.vec(m_broken);
  w.pod(m_stats);
  w.pod(m_maxAnchorError_m);
  w.pod(std::int64_t(m_stepsOverCostCap));
  w.pod(m_overCostCapWorkPerRow);
  w.vec(im.order);
  w.vec(im.ev.slots);
  w.vec(im.ev.generations);
  w.vec(im.jointForce);
  w.vec(im.jointTorque);
  w.vec(im.memo);
  w.pod(im.serial);
  w.pod(im.time_s);
  w.vec(im.pendingBreaks);
  w.pod(std::uint8_t(im.resultsPending));
  w.pod(std::uint8_t(im.overCostCap));
  if (m_impulse) m_impulse->saveState(w);
  return w.take();
}

Status JointSystem::restoreState(const std::string& bytes) {
  ByteReader r(bytes);
  if (r.pod<std::uint32_t>() != kStateMagic || !r.ok()) return makeError("not a joint state");
  if (const auto v = r.pod<std::uint32_t>(); v != kStateVersion)
    return makeError("joint state version " + std::to_string(v) + ", this build reads " + std::to_string(kStateVersion));
  const auto settings = r.pod<JointSettings>();
  const auto running = r.pod<std::uint8_t>();
  auto slots = r.vec<Slot>(kMaxSlots);
  auto freeList = r.vec<std::uint32_t>(kMaxSlots);
  const auto jointCount = r.pod<std::int32_t>();
  const auto orderDirty = r.pod<std::uint8_t>();
  auto broken = r.vec<JointBreakEvent>(kMaxSlots);
  const auto stats = r.pod<JointSolveStats>();
  const auto maxError = r.pod<double>();
  const auto stepsOver = r.pod<std::int64_t>();
  const auto overWork = r.pod<double>();
  auto order = r.vec<std::uint32_t>(kMaxSlots);
  auto evSlots = r.vec<std::uint32_t>(kMaxSlots);
  auto evGenerations = r.vec<std::uint32_t>(kMaxSlots);
  auto jointForce = r.vec<lagrange::V3>(kMaxSlots);
  auto jointTorque = r.vec<lagrange::V3>(kMaxSlots);
  auto memo = r.vec<Impl::Memo>(kMaxSlots);
  const auto serial = r.pod<std::uint64_t>();
  const auto time_s = r.pod<double>();
  auto pendingBreaks = r.vec<JointBreakEvent>(kMaxSlots);
  const auto resultsPending = r.pod<std::uint8_t>();
  const auto overCostCap = r.pod<std::uint8_t>();
  if (!r.ok()) return makeError("joint state: damaged (truncated)");

  // Checked against this World and the joints' own arrays, so that damaged
  // or hand-made bytes cannot make the next step read outside an array.
  const auto kind = JointSolverKind(running);
  if ((running != std::uint8_t(JointSolverKind::Lagrange) && running != std::uint8_t(JointSolverKind::Impulse)) ||
      (settings.solver != JointSolverKind::Lagrange && settings.solver != JointSolverKind::Impulse) ||
      (settings.solver == JointSolverKind::Impulse && kind != JointSolverKind::Impulse))
    return makeError("joint state: damaged (solver)");
  if (!validBools(settings.gyroscopic, settings.postStabilize, settings.projectPositions) ||
      settings.maxActiveSetIterations < 0 || settings.maxActiveSetIterations > 1000 ||
      !(settings.lagrangeMaxFactorWorkPerRow >= 0) || !std::isfinite(settings.impulseHertz) ||
      !std::isfinite(settings.impulseDampingRatio) || !std::isfinite(settings.stiffness_per_s2) ||
      !std::isfinite(settings.damping_per_s) || !std::isfinite(settings.compliance))
    return makeError("joint state: damaged (settings)");
  const std::size_t n = slots.size();
  int alive = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Slot& s = slots[i];
    if (!validBools(s.alive, s.def.enableLimit, s.def.enableMotor))
      return makeError("joint state: damaged (joint " + std::to_string(i) + ")");
    if (!s.alive) continue;
    ++alive;
    if (s.generation % 2 == 0 || std::uint32_t(s.def.type) > std::uint32_t(JointType::Fixed))
      return makeError("joint state: damaged (joint " + std::to_string(i) + ")");
    // A joint may outlive its body until the next step drops it, so a dead
    // body is allowed here; a body slot the World never had is not.
    if (s.def.bodyA.isNull() || s.def.bodyA.index >= m_world.bodySlotCount() ||
        (!s.def.bodyB.isNull() && s.def.bodyB.index >= m_world.bodySlotCount()))
      return makeError("joint " + std::to_string(i) +
                       " holds a body slot this world does not have (restore the world first, with the same bodies)");
    if (m_world.isValid(s.def.bodyA) && (s.def.bodyB.isNull() || m_world.isValid(s.def.bodyB)))
      if (Status st = validateJointDef(m_world, s.def); !st)
        return makeError("joint " + std::to_string(i) + ": " + st.error());
  }
  if (alive != jointCount) return makeError("joint state: damaged (joint count)");
  for (std::uint32_t i : freeList)
    if (i >= n || slots[i].alive) return makeError("joint state: damaged (free slots)");
  for (std::uint32_t i : order)
    if (i >= n) return makeError("joint state: damaged (joint order)");
  for (std::uint32_t i : evSlots)
    if (i >= n) return makeError("joint state: damaged (last solve)");
  if (!allDistinct(freeList) || !allDistinct(order) || evGenerations.size() != evSlots.size() ||
      jointForce.size() != jointTorque.size() || jointForce.size() > evSlots.size())
    return makeError("joint state: damaged (arrays)");
  for (const auto* events : {&broken, &pendingBreaks})
    for (const JointBreakEvent& e : *events)
      if (e.id.index >= n) return makeError("joint state: damaged (breaks)");

  // The solver first: switching resets the Lagrange solver's memory, which
  // is then put back.
  m_settings.solver = settings.solver;
  runSolver(kind);
  if (m_impulse)
    if (Status st = m_impulse->restoreState(r, n); !st) return st;
  if (!r.atEnd()) return makeError("joint state: damaged (bytes after the end)");
  m_settings = settings;
  m_slots = std::move(slots);
  m_freeList = std::move(freeList);
  m_jointCount = jointCount;
  m_orderDirty = orderDirty != 0;
  m_broken = std::move(broken);
  m_stats = stats;
  m_maxAnchorError_m = maxError;
  m_stepsOverCostCap = long(stepsOver);
  m_overCostCapWorkPerRow = overWork;
  Impl& im = *m_impl;
  im.order = std::move(order);
  im.ev.slots = std::move(evSlots);
  im.ev.generations = std::move(evGenerations);
  im.ev.defs.clear();
  for (std::uint32_t i : im.ev.slots) im.ev.defs.push_back(&m_slots[i].def);
  im.ev.bodies.assign(im.ev.slots.size(), {-1, -1});
  im.jointForce = std::move(jointForce);
  im.jointTorque = std::move(jointTorque);
  im.memo = std::move(memo);
  im.serial = serial;
  im.time_s = time_s;
  im.pendingBreaks = std::move(pendingBreaks);
  im.resultsPending = resultsPending != 0;
  im.overCostCap = overCostCap != 0;
  im.inStep = false;
  im.states.clear();
  im.slotOf.clear();
  im.rows.clear();
  // The island links follow the joints (refreshLinks), which the World's own
  // state holds already.
  return Ok{};
}

void ImpulseJoints::saveState(ByteWriter& w) const {
  static_assert(kBitwise<Accum>);
  static_assert(kBitwise<Output>);
  w.vec(m_accum);
  w.vec(m_out);
}

Status ImpulseJoints::restoreState(ByteReader& r, std::size_t slotCount) {
  auto accum = r.vec<Accum>(slotCount);
  auto out = r.vec<Output>(slotCount);
  // prepare() grows both together and indexes both by slot.
  if (!r.ok() || accum.size() != out.size()) return makeError("joint state: damaged (impulse solver)");
  for (const Output& o : out)
    if (!validBools(o.broken)) return makeError("joint state: damaged (impulse solver)");
  m_accum = std::move(accum);
  m_out = std::move(out);
  return Ok{};
}

}  // namespace tumble::physics
