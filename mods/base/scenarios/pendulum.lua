-- Eberly's simple pendulum as a reduced-coordinate model: one angle theta,
--   theta'' = -(g / L) sin theta,
-- stepped by ode.system in double (any integrator: --set method=verlet).
-- Exact period for amplitude theta0: T = 4 sqrt(L / g) K(sin(theta0 / 2)),
-- K the complete elliptic integral of the first kind (Landau & Lifshitz
-- sec. 11). Energy per unit mass E = L^2 w^2 / 2 - g L cos theta is
-- conserved.
--
-- Expectations: the period from the upward zero crossings within 0.1 % of
-- theory (rk4 at 1/240 s: the error is ~1e-8); the energy drift within
-- 1e-6 of m g L.
--
--   tumble run base:pendulum
--   tumble run base:pendulum --set method=verlet --set amplitude=170

local ode_models = require "lib.ode_models"

local scenario = {
  title = "Simple pendulum (reduced coordinates, ode.system)",
  duration = 12,
}

local L = 2          -- m, rod length
local PIVOT = {0, 4, 0}
local G
local sys, bob, period, drift, theta0

local function energy(y) return 0.5 * L * L * y[2] * y[2] - G * L * math.cos(y[1]) end

function scenario.on_start(ctx)
  local gv = world.gravity()
  G = math.sqrt(gv.x ^ 2 + gv.y ^ 2 + gv.z ^ 2)
  theta0 = math.rad(param("amplitude", 60))
  world.plane{color = {0.55, 0.57, 0.6}}
  sys = ode.system{
    state = {theta0, 0},
    method = param("method", "rk4"),
    derivative = function(t, y) return {y[2], -G / L * math.sin(y[1])} end,
    jacobian = function(t, y) return {{0, 1}, {-G / L * math.cos(y[1]), 0}} end,
    energy = energy,
  }
  bob = world.sphere{type = "kinematic", radius = 0.15, position = PIVOT, color = {0.9, 0.4, 0.2}}
  period = ode_models.period_tracker()
  drift = ode_models.drift_tracker(G * L)
end

local function bob_position()
  local th = sys:get(1)
  return {PIVOT[1] + L * math.sin(th), PIVOT[2] - L * math.cos(th), PIVOT[3]}
end

function scenario.on_update(ctx, dt)
  sys:step(dt, 4)
  local p = bob_position()
  bob:set_position(p)
  draw_line(PIVOT, p, {0.8, 0.8, 0.8})
  period.feed(sys:time(), sys:get(1))
  drift.feed(sys:energy())
  hud_text(ode_models.cost_line(sys))
end

function scenario.on_finish(ctx)
  local theory = 4 * math.sqrt(L / G) * ode_models.elliptic_k(math.sin(theta0 / 2))
  expect("period / theory", (period.period() or 0) / theory, {min = 0.999, max = 1.001})
  expect("energy drift / (g L)", drift.worst, {max = 1e-6})
end

return scenario
