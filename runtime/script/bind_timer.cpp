// Lua table `timer` and type Timer: callbacks after a delay or at a period,
// in simulated time (the fixed-step clock), so they are deterministic.
#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module timer
/// Calls a function after a delay or every period, in simulated time. Timers
/// are checked after each physics step, after on_contact and the triggers:
/// a timer due at t fires after the first step that ends at or after t (so
/// before the next on_update), at most once per step, in order of due time
/// and then of creation; ctx.time is the time the step ended. Timers made
/// in on_start with delay 0 fire right after on_start. They count from the
/// time of the callback that made them (0 in on_start). A failing
/// timer.every is cancelled after 3 failures in a row.

namespace {

constexpr const char* kTimerMeta = "tumble.Timer";

struct TimerRef {
  std::uint32_t id;
};

std::uint32_t checkTimer(lua_State* L, int idx) {
  auto* ref = static_cast<TimerRef*>(luaL_testudata(L, idx, kTimerMeta));
  if (!ref) throw LuaArgError(std::string("expected a Timer, got ") + luaL_typename(L, idx));
  return ref->id;
}

int add(lua_State* L, const char* fn, bool repeat) {
  double seconds = checkNumber(L, 1, (std::string(fn) + " seconds").c_str());
  if (repeat ? seconds <= 0 : seconds < 0)
    throw LuaArgError(std::string(fn) + ": seconds must be " + (repeat ? "> 0" : ">= 0") + ", got " +
                      std::to_string(seconds));
  if (!lua_isfunction(L, 2))
    throw LuaArgError(std::string(fn) + ": argument 2 must be a function, got " + luaL_typename(L, 2));
  lua_settop(L, 2);
  ScenarioHost* host = ScenarioHost::from(L);
  if (host->timers().pendingCount() >= TimerQueue::kMaxPending)
    throw LuaArgError(std::string(fn) + ": " + std::to_string(TimerQueue::kMaxPending) +
                      " timers are already waiting (the limit); cancel some or use one timer.every");
  std::uint32_t id = host->timers().add(host->now_s(), seconds, repeat ? seconds : 0);  // pops the function
  auto* ref = static_cast<TimerRef*>(lua_newuserdatauv(L, sizeof(TimerRef), 0));
  ref->id = id;
  luaL_setmetatable(L, kTimerMeta);
  return 1;
}

/// @function timer.after
/// Calls fn(ctx) once, `seconds` of simulated time from now.
/// @param seconds number delay, s (>= 0; 0 means the next step)
/// @param fn function called as fn(ctx)
/// @return Timer a handle to cancel it
/// @example timer.after(2, function() world.sphere{position = {0, 10, 0}} end)
int timerAfter(lua_State* L) { return add(L, "timer.after", false); }

/// @function timer.every
/// Calls fn(ctx) every `seconds` of simulated time until cancelled or until
/// fn returns false.
/// @param seconds number period, s (> 0; shorter than a step means every step)
/// @param fn function called as fn(ctx); return false to stop
/// @return Timer a handle to cancel it
/// @example local n = 0
/// @example timer.every(0.5, function() n = n + 1; return n < 10 end)
int timerEvery(lua_State* L) { return add(L, "timer.every", true); }

/// @class Timer
/// A handle returned by timer.after and timer.every.

/// @function Timer:cancel
/// Stops the timer; it will not fire again.
/// @return boolean true if it was still active
int timerCancel(lua_State* L) {
  lua_pushboolean(L, ScenarioHost::from(L)->timers().cancel(checkTimer(L, 1)));
  return 1;
}

/// @function Timer:active
/// @return boolean false once it fired (timer.after), was cancelled or stopped
int timerActive(lua_State* L) {
  lua_pushboolean(L, ScenarioHost::from(L)->timers().active(checkTimer(L, 1)));
  return 1;
}

int timerToString(lua_State* L) {
  auto* ref = static_cast<TimerRef*>(luaL_checkudata(L, 1, kTimerMeta));
  lua_pushfstring(L, "Timer(%d)", int(ref->id));
  return 1;
}

const luaL_Reg kTimer[] = {
    {"after", guarded<timerAfter>},
    {"every", guarded<timerEvery>},
    {nullptr, nullptr},
};
const luaL_Reg kMethods[] = {
    {"cancel", guarded<timerCancel>},
    {"active", guarded<timerActive>},
    {nullptr, nullptr},
};

}  // namespace

void openTimerBindings(lua_State* L, int envIndex) {
  registerType(L, {kTimerMeta, kMethods, timerToString});
  registerModule(L, envIndex, "timer", kTimer);
}

}  // namespace tumble::script
