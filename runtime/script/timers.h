#pragma once
// Timers of one scenario (timer.after, timer.every; bind_timer.cpp): a
// min-heap on (due time, creation order) in simulated time. The functions
// live in a Lua registry table keyed by id, so cancelling removes the
// function and a popped timer without one is skipped.
//
// The host fires due timers among the after-step callbacks (and once after
// on_start, for those due at 0): a timer due at t fires after the first step
// that ends at or after t, at most once per firing round, in order of due
// time and then of creation. Timers made while firing wait for the next
// round, so a timer that re-arms itself cannot keep a round going.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

struct lua_State;

namespace tumble::script {

class TimerQueue {
 public:
  /// Called for each due timer with its function on top of the stack
  /// (popped by the call). Returns false when the timer failed or asked to
  /// stop (timer.every returning false); `failed` says which.
  using Fire = std::function<bool(bool periodic, bool* failed)>;
  static constexpr int kMaxConsecutiveErrors = 3;
  /// Timers waiting at once (timer.after / every past it raise an error).
  static constexpr std::size_t kMaxPending = 10000;
  /// Timers fired in one round (one step); the rest stay due for the next.
  /// With timer.every firing at most once per round, this bounds the Lua
  /// calls a step makes for timers whatever their periods.
  static constexpr int kMaxFiredPerRound = 1000;

  explicit TimerQueue(lua_State* L);
  ~TimerQueue();
  TimerQueue(const TimerQueue&) = delete;
  TimerQueue& operator=(const TimerQueue&) = delete;

  /// The function on top of the stack is popped. Returns the timer's id (> 0).
  std::uint32_t add(double now_s, double delay_s, double period_s);
  /// False if it had already fired (once), been cancelled or stopped.
  bool cancel(std::uint32_t id);
  bool active(std::uint32_t id) const;
  /// Timers still to fire.
  std::size_t activeCount() const;
  /// Heap entries (active timers plus cancelled ones not yet dropped): cheap.
  std::size_t pendingCount() const { return m_heap.size(); }
  /// True if a timer is due at time_s (cheap: one comparison).
  bool anyDue(double time_s) const { return !m_heap.empty() && m_heap.front().due_s <= time_s + kTimeSlack_s; }
  /// Fires every timer due at time_s (see the header). `onGaveUp` is called
  /// when a timer.every is cancelled after kMaxConsecutiveErrors failures.
  void fireDue(double time_s, const Fire& fire, const std::function<void()>& onGaveUp);
  /// Drops every timer (hot reload with on_reload).
  void clear();

  /// A waiting timer's schedule, for snapshots of a running scene
  /// (scenario_state.cpp): exact due time, period, order and error count.
  struct Schedule {
    double due_s = 0, period_s = 0;
    std::uint64_t seq = 0;
    std::uint32_t id = 0;
    std::int32_t errors = 0;
  };
  /// Timers still to fire, in heap order.
  std::vector<Schedule> schedule() const;
  std::uint32_t nextId() const { return m_nextId; }
  std::uint64_t nextSeq() const { return m_seq; }
  /// Where timer `id`'s function was defined (its file's path and line), or "?".
  std::string definedAt(std::uint32_t id) const;
  /// Puts a saved schedule back over timers made again with the same ids
  /// (by on_start): timers not in it are dropped. Refused (false, nothing
  /// changed) if a timer in it has no function here.
  bool restoreSchedule(const std::vector<Schedule>& schedule, std::uint32_t nextId, std::uint64_t nextSeq);

 private:
  static constexpr double kTimeSlack_s = 1e-9;  ///< due times computed by sums of steps
  struct Timer {
    double due_s = 0, period_s = 0;  ///< period 0: fires once
    std::uint64_t seq = 0;           ///< creation order: ties fire in it
    std::uint32_t id = 0;
    int errors = 0;                  ///< consecutive failures
  };
  static bool later(const Timer& a, const Timer& b) {
    return a.due_s != b.due_s ? a.due_s > b.due_s : a.seq > b.seq;
  }

  lua_State* m_L;
  int m_functionsRef = 0;  ///< registry table id -> function
  std::vector<Timer> m_heap;
  std::uint32_t m_nextId = 1;
  std::uint64_t m_seq = 0;
};

}  // namespace tumble::script
