// Lua table `hud`: what the driving HUD's lap widget and minimap show. The
// speedometer, rev counter and gear come from the vehicle itself; a scenario
// with a timer, gates or laps hands those figures over here, and the app
// (app/driving_hud.cpp) draws them.
//
//   hud.set_gates(gates)                              -- once: gate centres for the minimap
//   hud.set_lap{time = t, best = best, gate = k, gates = n}   -- every step
#include <cmath>
#include <set>

#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module hud
/// The driving HUD's lap and gate widget and the minimap's gates. The HUD
/// shows the speed, rpm and gear of the driven car by itself; a scenario
/// with a lap timer or gates tells it the figures with hud.set_lap (every
/// step, or whenever they change) and where the gates are with
/// hud.set_gates. The next gate is highlighted on the minimap.

namespace {

// A whole number >= 0 in an optional field (0 when absent).
int optCountField(lua_State* L, int t, const char* key, const char* fn) {
  const double v = optNumberField(L, t, key, 0);
  if (v < 0 || v != std::floor(v) || v > 1e6)
    throw LuaArgError(std::string(fn) + ": " + key + " must be a whole number >= 0, got " + std::to_string(v));
  return int(v);
}

std::optional<double> optSeconds(lua_State* L, int t, const char* key, const char* fn) {
  if (rawGetField(L, t, key) == LUA_TNIL) {
    lua_pop(L, 1);
    return std::nullopt;
  }
  lua_pop(L, 1);
  const double v = optNumberField(L, t, key, 0);
  if (v < 0) throw LuaArgError(std::string(fn) + ": " + key + " must be >= 0 s, got " + std::to_string(v));
  return v;
}

/// @class LapFigures
/// @field time number the lap being driven, s (>= 0)
/// @field last? number the previous lap, s
/// @field best? number the best lap, s (e.g. read back with save.read)
/// @field gate? integer the next gate, 1..gates (shown as "gate k of n"; the minimap highlights it)
/// @field gates? integer how many gates a lap has
/// @field lap? integer the lap being driven, 1..laps (shown as "lap k of n" when laps > 0)
/// @field laps? integer how many laps the run has
/// @field finished? boolean the run is over: the HUD shows the time as final

/// @function hud.set_lap
/// Shows (or updates) the lap widget of the driving HUD: current lap time,
/// last and best lap, gate k of n, lap k of n. The figures stay until the
/// next call; the scenario keeps the timer.
/// @param figures LapFigures the figures to show
/// @example hud.set_lap{time = lap_time, best = best, gate = next_gate, gates = #gates}
int hudSetLap(lua_State* L) {
  const char* fn = "hud.set_lap";
  if (!lua_istable(L, 1)) throw LuaArgError(std::string(fn) + ": expected a table {time = s, best = s, gate = k, gates = n, ...}");
  checkFields(L, 1, fn, {"time", "last", "best", "gate", "gates", "lap", "laps", "finished"});
  LapDisplay lap;
  auto time = optSeconds(L, 1, "time", fn);
  if (!time) throw LuaArgError(std::string(fn) + ": time (the current lap, s) is required");
  lap.shown = true;
  lap.time_s = *time;
  lap.last_s = optSeconds(L, 1, "last", fn);
  lap.best_s = optSeconds(L, 1, "best", fn);
  lap.gate = optCountField(L, 1, "gate", fn);
  lap.gates = optCountField(L, 1, "gates", fn);
  lap.lap = optCountField(L, 1, "lap", fn);
  lap.laps = optCountField(L, 1, "laps", fn);
  lap.finished = optBoolField(L, 1, "finished", false);
  if (lap.gate > lap.gates)
    throw LuaArgError(std::string(fn) + ": gate " + std::to_string(lap.gate) + " is past gates = " + std::to_string(lap.gates));
  ScenarioHost::from(L)->presentation().lap = lap;
  return 0;
}

/// @function hud.clear_lap
/// Hides the lap widget (until the next hud.set_lap).
/// @example hud.clear_lap()
int hudClearLap(lua_State* L) {
  ScenarioHost::from(L)->presentation().lap = LapDisplay{};
  return 0;
}

/// @function hud.set_gates
/// Where the gates are, in order, for the minimap (numbered dots; the next
/// gate from hud.set_lap is highlighted). Replaces the previous list; an
/// empty table removes them.
/// @param gates table a list of points {x, z} (ground position) or {x, y, z}, m
/// @example hud.set_gates{{40, 0}, {110, 25}, {120, 90}}
int hudSetGates(lua_State* L) {
  const char* fn = "hud.set_gates";
  if (!lua_istable(L, 1)) throw LuaArgError(std::string(fn) + ": expected a list of points {{x, z}, ...}");
  std::vector<Vec3> gates;
  const lua_Integer n = luaL_len(L, 1);
  if (n > 1000) throw LuaArgError(std::string(fn) + ": at most 1000 gates, got " + std::to_string(n));
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, 1, i);
    const std::string where = std::string(fn) + ": gate " + std::to_string(i);
    if (!lua_istable(L, -1)) throw LuaArgError(where + " must be a table {x, z} or {x, y, z}");
    const int idx = lua_gettop(L);
    const lua_Integer len = luaL_len(L, idx);
    if (len == 2) {
      lua_rawgeti(L, idx, 1);
      lua_rawgeti(L, idx, 2);
      const double x = checkNumber(L, -2, where.c_str()), z = checkNumber(L, -1, where.c_str());
      lua_pop(L, 2);
      gates.emplace_back(Real(x), 0, Real(z));
    } else if (len == 3) {
      gates.push_back(checkVec3(L, idx, where.c_str()));
    } else {
      throw LuaArgError(where + " must be a table {x, z} or {x, y, z}, got " + std::to_string(len) + " numbers");
    }
    lua_pop(L, 1);
  }
  ScenarioHost::from(L)->presentation().gates_m = std::move(gates);
  return 0;
}

const luaL_Reg kHud[] = {
    {"set_lap", guarded<hudSetLap>},
    {"clear_lap", guarded<hudClearLap>},
    {"set_gates", guarded<hudSetGates>},
    {nullptr, nullptr},
};

}  // namespace

void openHudBindings(lua_State* L, int envIndex) { registerModule(L, envIndex, "hud", kHud); }

}  // namespace tumble::script
