-- Eberly's bead on a wire: a frictionless bead slides on the wire
-- y = a x^2 under gravity. One generalised coordinate x; from the
-- Lagrangian L = 1/2 m (1 + f'^2) x'^2 - m g f(x),
--   x'' = -f'(x) (g + f''(x) x'^2) / (1 + f'(x)^2),   f' = 2 a x, f'' = 2 a.
-- Energy per unit mass E = 1/2 (1 + f'^2) x'^2 + g f is conserved.
-- Period from rest at x0 (substituting x = x0 sin phi, which removes the
-- turning-point singularity):
--   T = 4 * integral_0^{pi/2} sqrt((1 + 4 a^2 x0^2 sin^2 phi) / (2 g a)) dphi,
-- evaluated by Simpson's rule (smooth integrand: 1e-12 with 400 panels).
--
-- Expectations: period within 0.1 % of that; energy drift within 1e-6 of
-- g f(x0); the bead turns at +-x0 (within 1 mm).
--
--   tumble run base:bead_wire
--   tumble run base:bead_wire --set method=heun

local ode_models = require "lib.ode_models"

local scenario = {
  title = "Bead on a wire (reduced coordinates, ode.system)",
  duration = 10,
}

local A = 0.5            -- 1/m, wire y = A x^2
local X0 = 2             -- m, release point
local BASE = {0, 0.5, 0} -- m, the wire's lowest point in the world
local G
local sys, bead, period, drift
local xmin, xmax = math.huge, -math.huge

local function f(x) return A * x * x end

function scenario.on_start(ctx)
  local gv = world.gravity()
  G = math.sqrt(gv.x ^ 2 + gv.y ^ 2 + gv.z ^ 2)
  world.plane{color = {0.55, 0.57, 0.6}}
  sys = ode.system{
    state = {X0, 0},
    method = param("method", "rk4"),
    derivative = function(t, y)
      local fp = 2 * A * y[1]
      return {y[2], -fp * (G + 2 * A * y[2] * y[2]) / (1 + fp * fp)}
    end,
    energy = function(y)
      local fp = 2 * A * y[1]
      return 0.5 * (1 + fp * fp) * y[2] * y[2] + G * f(y[1])
    end,
  }
  bead = world.sphere{type = "kinematic", radius = 0.1, position = {BASE[1] + X0, BASE[2] + f(X0), BASE[3]},
                      color = {0.9, 0.7, 0.2}}
  period = ode_models.period_tracker()
  drift = ode_models.drift_tracker(G * f(X0))
end

function scenario.on_update(ctx, dt)
  sys:step(dt, 4)
  local x = sys:get(1)
  bead:set_position{BASE[1] + x, BASE[2] + f(x), BASE[3]}
  local n = 40
  for i = 0, n - 1 do
    local x1, x2 = -2.5 + 5 * i / n, -2.5 + 5 * (i + 1) / n
    draw_line({BASE[1] + x1, BASE[2] + f(x1), BASE[3]}, {BASE[1] + x2, BASE[2] + f(x2), BASE[3]}, {0.8, 0.8, 0.8})
  end
  period.feed(sys:time(), sys:get(2))  -- velocity crosses zero upward at the left turning point
  drift.feed(sys:energy())
  xmin, xmax = math.min(xmin, x), math.max(xmax, x)
  hud_text(ode_models.cost_line(sys))
end

function scenario.on_finish(ctx)
  local n, sum = 400, 0
  local function g(phi) return math.sqrt((1 + 4 * A * A * X0 * X0 * math.sin(phi) ^ 2) / (2 * G * A)) end
  local h = (math.pi / 2) / n
  for i = 0, n do
    local w = (i == 0 or i == n) and 1 or (i % 2 == 1 and 4 or 2)
    sum = sum + w * g(i * h)
  end
  local theory = 4 * sum * h / 3
  expect("period / theory", (period.period() or 0) / theory, {min = 0.999, max = 1.001})
  expect("energy drift / (g f(x0))", drift.worst, {max = 1e-6})
  expect("turning points |x| - x0 (m)", math.max(math.abs(xmin), xmax) - X0, {min = -1e-3, max = 1e-3})
end

return scenario
