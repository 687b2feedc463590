#include "script/timers.h"

#include <algorithm>

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace tumble::script {

TimerQueue::TimerQueue(lua_State* L) : m_L(L) {
  lua_newtable(L);
  m_functionsRef = luaL_ref(L, LUA_REGISTRYINDEX);
}

TimerQueue::~TimerQueue() = default;  // the registry table goes with the Lua state

std::uint32_t TimerQueue::add(double now_s, double delay_s, double period_s) {
  Timer t;
  t.id = m_nextId++;
  t.seq = m_seq++;
  t.due_s = now_s + delay_s;
  t.period_s = period_s;
  lua_rawgeti(m_L, LUA_REGISTRYINDEX, m_functionsRef);
  lua_insert(m_L, -2);
  lua_rawseti(m_L, -2, t.id);  // pops the function
  lua_pop(m_L, 1);
  m_heap.push_back(t);
  std::push_heap(m_heap.begin(), m_heap.end(), later);
  return t.id;
}

bool TimerQueue::active(std::uint32_t id) const {
  lua_rawgeti(m_L, LUA_REGISTRYINDEX, m_functionsRef);
  const bool isActive = lua_rawgeti(m_L, -1, id) != LUA_TNIL;
  lua_pop(m_L, 2);
  return isActive;
}

bool TimerQueue::cancel(std::uint32_t id) {
  // The heap entry stays and is skipped when it comes due.
  const bool wasActive = active(id);
  lua_rawgeti(m_L, LUA_REGISTRYINDEX, m_functionsRef);
  lua_pushnil(m_L);
  lua_rawseti(m_L, -2, id);
  lua_pop(m_L, 1);
  return wasActive;
}

std::size_t TimerQueue::activeCount() const {
  lua_rawgeti(m_L, LUA_REGISTRYINDEX, m_functionsRef);
  std::size_t n = 0;
  lua_pushnil(m_L);
  while (lua_next(m_L, -2) != 0) {
    lua_pop(m_L, 1);
    ++n;
  }
  lua_pop(m_L, 1);
  return n;
}

void TimerQueue::clear() {
  luaL_unref(m_L, LUA_REGISTRYINDEX, m_functionsRef);
  lua_newtable(m_L);
  m_functionsRef = luaL_ref(m_L, LUA_REGISTRYINDEX);
  m_heap.clear();
}

void TimerQueue::fireDue(double time_s, const Fire& fire, const std::function<void()>& onGaveUp) {
  const std::uint64_t seqLimit = m_seq;  // timers made while firing wait for the next round
  int fired = 0;
  while (!m_heap.empty() && m_heap.front().due_s <= time_s + kTimeSlack_s && m_heap.front().seq < seqLimit &&
         fired < kMaxFiredPerRound) {
    std::pop_heap(m_heap.begin(), m_heap.end(), later);
    Timer t = m_heap.back();
    m_heap.pop_back();
    lua_rawgeti(m_L, LUA_REGISTRYINDEX, m_functionsRef);
    if (lua_rawgeti(m_L, -1, t.id) != LUA_TFUNCTION) {  // cancelled
      lua_pop(m_L, 2);
      continue;
    }
    lua_remove(m_L, -2);
    ++fired;
    bool failed = false;
    bool again = fire(t.period_s > 0, &failed) && t.period_s > 0;
    if (!failed) {
      t.errors = 0;
    } else if (t.period_s > 0 && ++t.errors < kMaxConsecutiveErrors) {
      again = true;
    } else if (t.period_s > 0) {
      onGaveUp();
    }
    if (again && active(t.id)) {
      // Keep the phase (due += period) but fire at most once per round.
      t.due_s += t.period_s;
      if (t.due_s <= time_s + kTimeSlack_s) t.due_s = time_s + t.period_s;
      // A period shorter than the slack (timer.every(1e-10, f)) would be
      // due again at once: it waits for the next round, as new timers do.
      if (t.due_s <= time_s + kTimeSlack_s) t.seq = m_seq++;
      m_heap.push_back(t);
      std::push_heap(m_heap.begin(), m_heap.end(), later);
    } else {
      cancel(t.id);
    }
  }
}

}  // namespace tumble::script

namespace tumble::script {

std::vector<TimerQueue::Schedule> TimerQueue::schedule() const {
  std::vector<Schedule> out;
  for (const Timer& t : m_heap)
    if (active(t.id)) out.push_back(Schedule{t.due_s, t.period_s, t.seq, t.id, t.errors});
  return out;
}

std::string TimerQueue::definedAt(std::uint32_t id) const {
  lua_rawgeti(m_L, LUA_REGISTRYINDEX, m_functionsRef);
  std::string where = "?";
  if (lua_rawgeti(m_L, -1, id) == LUA_TFUNCTION) {
    lua_Debug ar;
    lua_getinfo(m_L, ">S", &ar);  // pops the function
    const std::string source = ar.source ? ar.source : "?";
    where = (source.rfind('@', 0) == 0 ? source.substr(1) : std::string(ar.short_src)) + ":" +
            std::to_string(ar.linedefined);
  } else {
    lua_pop(m_L, 1);
  }
  lua_pop(m_L, 1);
  return where;
}

bool TimerQueue::restoreSchedule(const std::vector<Schedule>& schedule, std::uint32_t nextId, std::uint64_t nextSeq) {
  for (const Schedule& s : schedule)
    if (!active(s.id)) return false;
  std::vector<std::uint32_t> keep;
  for (const Schedule& s : schedule) keep.push_back(s.id);
  for (const Timer& t : m_heap)
    if (std::find(keep.begin(), keep.end(), t.id) == keep.end()) cancel(t.id);
  m_heap.clear();
  for (const Schedule& s : schedule) m_heap.push_back(Timer{s.due_s, s.period_s, s.seq, s.id, s.errors});
  std::make_heap(m_heap.begin(), m_heap.end(), later);
  m_nextId = nextId;
  m_seq = nextSeq;
  return true;
}

}  // namespace tumble::script
