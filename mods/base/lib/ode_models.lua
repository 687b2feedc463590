-- Shared helpers of the reduced-coordinate (Lagrangian) model scenarios:
-- pendulum, bead_wire, foucault, top, pulley. Each steps an ode.system and
-- draws it with kinematic bodies and draw_line.

local M = {}

-- Complete elliptic integral of the first kind K(k) by the arithmetic-
-- geometric mean: K = pi / (2 AGM(1, sqrt(1 - k^2))).
function M.elliptic_k(k)
  local a, b = 1, math.sqrt(1 - k * k)
  for _ = 1, 30 do
    a, b = (a + b) / 2, math.sqrt(a * b)
    if math.abs(a - b) < 1e-15 then break end
  end
  return math.pi / (2 * a)
end

-- Period of a signal from its upward zero crossings (linear interpolation
-- between samples). feed(t, value); period() -> mean period or nil.
function M.period_tracker()
  local tracker = {crossings = {}}
  local last_t, last_v
  function tracker.feed(t, v)
    if last_v and last_v < 0 and v >= 0 then
      tracker.crossings[#tracker.crossings + 1] = last_t + (t - last_t) * (-last_v) / (v - last_v)
    end
    last_t, last_v = t, v
  end
  function tracker.period()
    local c = tracker.crossings
    if #c < 2 then return nil end
    return (c[#c] - c[1]) / (#c - 1)
  end
  return tracker
end

-- Relative drift tracker: feed(value); worst() -> max |value / first - 1|
-- measured against `scale` (a non-zero energy scale) when given.
function M.drift_tracker(scale)
  local tracker = {worst = 0}
  local first
  function tracker.feed(v)
    first = first or v
    local s = scale or math.abs(first)
    tracker.worst = math.max(tracker.worst, math.abs(v - first) / s)
  end
  return tracker
end

-- The cost of the Lua derivative so far, for the HUD and the report.
function M.cost_line(sys)
  local s = sys:stats()
  local us = s.derivative_calls > 0 and s.lua_seconds / s.derivative_calls * 1e6 or 0
  return string.format("%s: %d derivative calls, %.2f us each (Lua)", s.method, s.derivative_calls, us)
end

return M
