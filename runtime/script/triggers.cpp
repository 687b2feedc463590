#include "script/triggers.h"

#include <algorithm>

#include "physics/world.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace tumble::script {

std::uint32_t TriggerSet::add(const Vec3& center_m, const Vec3& halfSize_m, const Quat& orientation, int onEnterIdx,
                              int onExitIdx) {
  auto slot = std::find_if(m_triggers.begin(), m_triggers.end(), [](const Trigger& t) { return t.id == 0; });
  Trigger& t = slot != m_triggers.end() ? *slot : m_triggers.emplace_back();
  t.id = m_nextId++;
  t.inside.clear();
  t.center_m = center_m;
  t.half_m = halfSize_m;
  t.toBox = orientation.conjugate();
  if (onEnterIdx) {
    lua_pushvalue(m_L, onEnterIdx);
    t.onEnterRef = luaL_ref(m_L, LUA_REGISTRYINDEX);
  }
  if (onExitIdx) {
    lua_pushvalue(m_L, onExitIdx);
    t.onExitRef = luaL_ref(m_L, LUA_REGISTRYINDEX);
  }
  ++m_live;
  return t.id;
}

bool TriggerSet::remove(std::uint32_t id) {
  for (Trigger& t : m_triggers) {
    if (t.id != id || id == 0) continue;
    if (t.onEnterRef) luaL_unref(m_L, LUA_REGISTRYINDEX, t.onEnterRef);
    if (t.onExitRef) luaL_unref(m_L, LUA_REGISTRYINDEX, t.onExitRef);
    t.id = 0;  // the slot (and its vectors' capacity) is reused
    t.onEnterRef = t.onExitRef = 0;
    t.inside.clear();
    --m_live;
    return true;
  }
  return false;
}

void TriggerSet::clear() {
  for (Trigger& t : m_triggers)
    if (t.id != 0) remove(t.id);
}

const std::vector<physics::BodyId>* TriggerSet::bodiesIn(std::uint32_t id) const {
  for (const Trigger& t : m_triggers)
    if (t.id == id && id != 0) return &t.inside;
  return nullptr;
}

void TriggerSet::update(const physics::World& world, const Call& call) {
  // 1. Who is inside now (non-static bodies, by centre of mass), in body
  //    index order, compared with the last step: enters and exits.
  m_events.clear();
  auto before = [](physics::BodyId a, physics::BodyId b) {
    return a.index != b.index ? a.index < b.index : a.generation < b.generation;
  };
  for (Trigger& t : m_triggers) {
    if (t.id == 0) continue;
    t.scratch.clear();
    world.forEachBody([&](physics::BodyId id, const physics::Body& b) {
      if (b.type == physics::BodyType::Static) return;
      if (((t.toBox * (b.position_m - t.center_m)).cwiseAbs() - t.half_m).maxCoeff() <= 0) t.scratch.push_back(id);
    });
    std::size_t i = 0, j = 0;
    while (i < t.inside.size() || j < t.scratch.size()) {
      if (j == t.scratch.size() || (i < t.inside.size() && before(t.inside[i], t.scratch[j]))) {
        if (t.onExitRef) m_events.push_back({t.id, t.inside[i], false});
        ++i;
      } else if (i == t.inside.size() || before(t.scratch[j], t.inside[i])) {
        if (t.onEnterRef) m_events.push_back({t.id, t.scratch[j], true});
        ++j;
      } else {
        ++i, ++j;
      }
    }
    std::swap(t.inside, t.scratch);
  }
  // 2. Call back.
  for (const Event& e : m_events) {
    int ref = 0;
    for (const Trigger& t : m_triggers)
      if (t.id == e.trigger) ref = e.enter ? t.onEnterRef : t.onExitRef;
    if (!ref) continue;  // the trigger was removed by an earlier callback
    lua_rawgeti(m_L, LUA_REGISTRYINDEX, ref);
    call(e.body, e.trigger, e.enter);
  }
}

bool TriggerSet::anyFrom(std::uint32_t firstId) const {
  for (const Trigger& t : m_triggers)
    if (t.id != 0 && t.id >= firstId) return true;
  return false;
}

void TriggerSet::saveState(ByteWriter& w) const {
  w.pod(m_nextId);
  w.pod(std::uint64_t(m_triggers.size()));
  for (const Trigger& t : m_triggers) {
    w.pod(t.id);
    if (t.id != 0) w.vec(t.inside);
  }
}

Status TriggerSet::restoreState(ByteReader& r, std::size_t bodySlots, bool apply) {
  const auto nextId = r.pod<std::uint32_t>();
  const auto slots = r.pod<std::uint64_t>();
  // Each slot takes at least its id: a damaged count allocates no more than the bytes could hold.
  if (!r.ok() || slots > (std::uint64_t(1) << 20) || slots > r.remaining() / sizeof(std::uint32_t))
    return makeError("damaged (trigger slots)");
  // Read and checked whole before anything changes.
  std::vector<std::uint32_t> ids(slots);
  std::vector<std::vector<physics::BodyId>> inside(slots);
  for (std::size_t i = 0; i < slots; ++i) {
    ids[i] = r.pod<std::uint32_t>();
    if (ids[i] == 0) continue;
    inside[i] = r.vec<physics::BodyId>(bodySlots);
    const std::uint32_t here = i < m_triggers.size() ? m_triggers[i].id : 0;
    if (!r.ok()) return makeError("damaged (trigger " + std::to_string(ids[i]) + ")");
    if (here != ids[i])
      return makeError("trigger " + std::to_string(ids[i]) +
                       " is in the snapshot but on_start did not make it here (made later, or the scenario changed)");
    for (const physics::BodyId& b : inside[i])
      if (b.index >= bodySlots) return makeError("damaged (trigger " + std::to_string(ids[i]) + ")");
  }
  if (!r.ok() || nextId < 1) return makeError("damaged (triggers)");
  for (std::size_t i = slots; i < m_triggers.size(); ++i)
    if (m_triggers[i].id != 0)
      return makeError("trigger " + std::to_string(m_triggers[i].id) + " was made here but is not in the snapshot");
  if (!apply) return Ok{};
  for (std::size_t i = 0; i < slots; ++i) {
    if (i >= m_triggers.size()) m_triggers.emplace_back();  // a slot of a trigger made and removed since
    if (ids[i] == 0 && m_triggers[i].id != 0) remove(m_triggers[i].id);  // removed since
    m_triggers[i].inside = std::move(inside[i]);
  }
  m_nextId = nextId;
  return Ok{};
}

}  // namespace tumble::script
