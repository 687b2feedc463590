// Snapshots of ropes and cloth (Deformable::saveState, DeformableSystem::
// saveState): what a later step reads, as exact bits. The springs are not
// stored (they follow from the definition, which the scenario makes again);
// everything that changes while running is: particle positions and
// velocities, pins (scripts pin and unpin), wind, material, the counters,
// and the last implicit solve's velocity change, from which the next
// conjugate-gradient solve starts (without it a rope loaded from a snapshot
// takes other CG iterates and ends elsewhere).
#include <cmath>

#include "physics/deformable.h"

namespace tumble::physics {

namespace {

constexpr std::uint32_t kStateMagic = 0x5444464d;  // "TDFM"
constexpr std::uint32_t kStateVersion = 1;
constexpr std::size_t kMaxValues = std::size_t(1) << 26;

void writeVector(ByteWriter& w, const Eigen::VectorXd& v) {
  w.vec(std::vector<double>(v.data(), v.data() + v.size()));
}

/// size values, or (emptyToo) none.
bool readVector(ByteReader& r, Eigen::VectorXd& out, std::size_t size, bool emptyToo = false) {
  const std::vector<double> v = r.vec<double>(kMaxValues);
  if (!r.ok() || (v.size() != size && !(emptyToo && v.empty()))) return false;
  out = Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size()));
  return true;
}

/// What must match between the saved deformable and the one made again.
struct Layout {
  std::uint8_t kind = 0;
  std::int32_t columns = 0, rows = 0, particles = 0, springs = 0;
  bool operator==(const Layout&) const = default;
};

std::string describe(const Layout& l) {
  return std::string(l.kind == 0 ? "a rope of " : "a cloth of ") + std::to_string(l.particles) + " particles";
}

Layout layoutOf(const Deformable& d, int columns, int rows, std::size_t springs) {
  return Layout{std::uint8_t(d.kind()), columns, rows, d.particleCount(), std::int32_t(springs)};
}

}  // namespace

void Deformable::saveState(ByteWriter& w) const {
  static_assert(kBitwise<Pin>);
  static_assert(kBitwise<DeformableMaterial>);
  static_assert(kBitwise<DeformableStats>);
  w.pod(layoutOf(*this, m_columns, m_rows, m_springs.size()));
  writeVector(w, m_x);
  writeVector(w, m_v);
  w.vec(m_pins);
  w.vec(m_pinOf);
  w.pod(m_wind);
  w.pod(m_material);
  w.pod(m_stats);
  writeVector(w, lastSolve());
}

Status Deformable::restoreState(ByteReader& r, std::size_t bodySlots) {
  const Layout here = layoutOf(*this, m_columns, m_rows, m_springs.size());
  const auto saved = r.pod<Layout>();
  if (!r.ok()) return makeError("damaged (truncated)");
  if (!(saved == here))
    return makeError("the snapshot holds " + describe(saved) + " here, the scenario made " + describe(here));
  const std::size_t n = std::size_t(here.particles) * 3;
  Eigen::VectorXd x, v, dv;
  if (!readVector(r, x, n) || !readVector(r, v, n)) return makeError("damaged (particles)");
  auto pins = r.vec<Pin>(std::size_t(here.particles));
  auto pinOf = r.vec<int>(std::size_t(here.particles));
  const auto wind = r.pod<Eigen::Vector3d>();
  const auto material = r.pod<DeformableMaterial>();
  const auto stats = r.pod<DeformableStats>();
  if (!readVector(r, dv, n, true)) return makeError("damaged (last solve)");
  if (!r.ok() || pinOf.size() != std::size_t(here.particles)) return makeError("damaged (pins)");
  // Indices are checked so that damaged or hand-made bytes cannot make the
  // next step read outside its arrays.
  for (std::size_t p = 0; p < pins.size(); ++p) {
    const Pin& pin = pins[p];
    if (pin.particle < 0 || pin.particle >= here.particles || pinOf[std::size_t(pin.particle)] != int(p) ||
        (!pin.body.isNull() && pin.body.index >= bodySlots) || !pin.point.allFinite())
      return makeError("damaged (pin " + std::to_string(p) + ")");
  }
  for (int i : pinOf)
    if (i < -1 || i >= int(pins.size())) return makeError("damaged (pins)");
  if (material.substeps < 1 || material.substeps > 64 || !(material.radius_m > 0))
    return makeError("damaged (material)");
  m_x = std::move(x);
  m_v = std::move(v);
  m_pins = std::move(pins);
  m_pinOf = std::move(pinOf);
  m_wind = wind;
  m_material = material;
  m_stats = stats;
  setLastSolve(std::move(dv));
  return Ok{};
}

std::string DeformableSystem::saveState() const {
  ByteWriter w;
  w.pod(kStateMagic);
  w.pod(kStateVersion);
  w.pod(std::int32_t(m_nextId));
  w.pod(std::uint64_t(m_items.size()));
  for (const auto& [id, d] : m_items) {
    w.pod(std::int32_t(id));
    w.pod(std::uint8_t(d != nullptr));
    if (d) d->saveState(w);
  }
  return w.take();
}

Status DeformableSystem::restoreState(const std::string& bytes, std::size_t bodySlots) {
  ByteReader r(bytes);
  if (r.pod<std::uint32_t>() != kStateMagic || !r.ok()) return makeError("not a rope and cloth state");
  if (const auto v = r.pod<std::uint32_t>(); v != kStateVersion)
    return makeError("rope and cloth state version " + std::to_string(v) + ", this build reads " +
                     std::to_string(kStateVersion));
  const auto nextId = r.pod<std::int32_t>();
  const auto items = r.pod<std::uint64_t>();
  if (!r.ok()) return makeError("rope and cloth state: damaged (truncated)");
  if (items != m_items.size() || nextId != m_nextId)
    return makeError("the snapshot holds " + std::to_string(items) + " ropes and cloths made, the scenario made " +
                     std::to_string(m_items.size()) + " (a snapshot goes back into a scene with the same ropes and cloth)");
  // Checked whole before anything changes: a refused restore leaves the
  // system as it was.
  std::vector<std::unique_ptr<Deformable>> restored(m_items.size());
  for (std::size_t k = 0; k < m_items.size(); ++k) {
    const auto id = r.pod<std::int32_t>();
    const auto present = r.pod<std::uint8_t>();
    if (!r.ok() || id != m_items[k].first) return makeError("rope and cloth state: damaged (ids)");
    if (!present) continue;
    const Deformable* here = m_items[k].second.get();
    if (!here)
      return makeError("rope or cloth " + std::to_string(id) +
                       " was removed here but not in the snapshot (a snapshot goes back into a scene with the same "
                       "ropes and cloth)");
    auto copy = std::unique_ptr<Deformable>(new Deformable(*here));
    copy->useOwnSolver();  // not the original's scratch
    if (Status st = copy->restoreState(r, bodySlots); !st)
      return makeError("rope or cloth " + std::to_string(id) + ": " + st.error());
    restored[k] = std::move(copy);
  }
  if (!r.atEnd()) return makeError("rope and cloth state: damaged (bytes after the end)");
  for (std::size_t k = 0; k < m_items.size(); ++k) m_items[k].second = std::move(restored[k]);
  return Ok{};
}

}  // namespace tumble::physics
