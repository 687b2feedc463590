-- Eberly's Foucault pendulum, small-amplitude form: the bob moves in the
-- horizontal plane (x, y) of a frame turning with the Earth; only the
-- vertical component W = Omega sin(latitude) of the Earth's rotation acts
-- on horizontal motion, through the Coriolis acceleration -2 Omega x v:
--   x'' = -w0^2 x + 2 W y',    y'' = -w0^2 y - 2 W x',    w0^2 = g / L.
-- Exact solution (z = x + i y, released at rest at x = A):
--   z(t) = e^{-i W t} (A cos(w t) + i A (W / w) sin(w t)),  w = sqrt(w0^2 + W^2),
-- i.e. the swing plane turns clockwise (seen from above) at rate W. The
-- real W (7.3e-5 rad/s at the pole) needs hours to show; the default is
-- exaggerated to 0.05 rad/s (--set rate=...).
--
-- Expectations: the bob within 1e-6 m of the exact solution over the run,
-- and the swing plane, read from the bob's direction at its last turning
-- point (largest distance from the centre), turned by -W t (within 0.01
-- rad, the sampling at 60 Hz).
--
--   tumble run base:foucault
--   tumble run base:foucault --set rate=0.2

local ode_models = require "lib.ode_models"

local scenario = {
  title = "Foucault pendulum (ode.system)",
  duration = 20,
}

local L = 10          -- m
local AMP = 1         -- m, release offset
local PIVOT = {0, 11, 0}
local G, W, w0, w
local sys, bob, worst = nil, nil, 0
local prev
local trail = {}
local r1, r2 = 0, 0            -- the last two distances from the centre
local last_turn                -- {t, angle} at the last local maximum

-- Plane (x, y) to world: x -> X, y -> -Z (so that (x, y, up) is right-handed).
local function world_of(x, y)
  local h = math.sqrt(math.max(L * L - x * x - y * y, 0))
  return {PIVOT[1] + x, PIVOT[2] - h, PIVOT[3] - y}
end

function scenario.on_start(ctx)
  local gv = world.gravity()
  G = math.sqrt(gv.x ^ 2 + gv.y ^ 2 + gv.z ^ 2)
  W = param("rate", 0.05)
  w0 = math.sqrt(G / L)
  w = math.sqrt(w0 * w0 + W * W)
  world.plane{color = {0.55, 0.57, 0.6}}
  sys = ode.system{
    state = {AMP, 0, 0, 0},  -- x, y, x', y'
    method = param("method", "rk4"),
    derivative = function(t, s)
      return {s[3], s[4], -w0 * w0 * s[1] + 2 * W * s[4], -w0 * w0 * s[2] - 2 * W * s[3]}
    end,
  }
  bob = world.sphere{type = "kinematic", radius = 0.2, position = world_of(AMP, 0), color = {0.85, 0.3, 0.3}}
end

function scenario.on_update(ctx, dt)
  sys:step(dt, 4)
  local t, x, y = sys:time(), sys:get(1), sys:get(2)
  -- exact: e^{-iWt} (A cos wt + i A W/w sin wt)
  local re, im = AMP * math.cos(w * t), AMP * W / w * math.sin(w * t)
  local c, s = math.cos(-W * t), math.sin(-W * t)
  local ex, ey = c * re - s * im, s * re + c * im
  worst = math.max(worst, math.sqrt((x - ex) ^ 2 + (y - ey) ^ 2))
  local r = math.sqrt(x * x + y * y)
  if r1 > r2 and r1 >= r and prev then last_turn = prev end
  r2, r1 = r1, r
  prev = {t = t, angle = math.atan(y, x)}
  local p = world_of(x, y)
  bob:set_position(p)
  draw_line(PIVOT, p, {0.8, 0.8, 0.8})
  trail[#trail + 1] = {p[1], 0.02, p[3]}
  if #trail > 600 then table.remove(trail, 1) end
  for i = 2, #trail do draw_line(trail[i - 1], trail[i], {0.9, 0.6, 0.2}) end
  hud_text(string.format("swing plane turned %.1f deg", math.deg(W * t)), ode_models.cost_line(sys))
end

function scenario.on_finish(ctx)
  expect("largest distance from the exact solution (m)", worst, {max = 1e-6})
  -- Stepped through the whole run (its own time over the run's).
  expect("pendulum stepped to the end (its time / run time)", sys:time() / ctx.time, {min = 0.999, max = 1.001})
  -- The swing plane (a line: angles modulo pi) at the last turning point.
  local d = (last_turn.angle + W * last_turn.t) % math.pi
  if d > math.pi / 2 then d = d - math.pi end
  expect("swing plane turn + W t at the last turning point (rad)", d, {min = -0.01, max = 0.01})
end

return scenario
