-- Eberly's mass-spring-pulley: a pulley (a disc of mass MP, I = MP R^2 / 2)
-- hangs from the ceiling on a spring k; a rope over it carries m1 on one
-- side and m2 on the other. Two coordinates: y, how far the axle has moved
-- down, and x, how far the rope has run towards m1. Downward speeds: axle
-- y', m1 y' + x', m2 y' - x'; the disc turns at x' / R. So
--   T = 1/2 [MP y'^2 + (I/R^2) x'^2 + m1 (y' + x')^2 + m2 (y' - x')^2]
--   V = 1/2 k y^2 - (MP + m1 + m2) g y - (m1 - m2) g x
-- and M q'' = Q with M = [[MP + m1 + m2, m1 - m2], [m1 - m2, I/R^2 + m1 + m2]],
-- Q = [(MP + m1 + m2) g - k y, (m1 - m2) g]; the derivative solves this 2x2.
-- Eliminating x'' leaves y'' = -(k / Ms) (y - y_eq) with the Schur
-- complement Ms = M11 - M12^2 / M22: the axle bobs at w = sqrt(k / Ms)
-- about y_eq = (M11 - M12 (m1 - m2) / M22) g / k while the rope runs
-- with constant acceleration.
--
-- Expectations: the axle's period within 0.1 % of 2 pi / w; energy
-- T + V conserved within 1e-6 of its scale (MP + m1 + m2) g y_eq.
--
--   tumble run base:pulley

local ode_models = require "lib.ode_models"

local scenario = {
  title = "Mass-spring-pulley (ode.system)",
  duration = 4,
}

local K = 200                  -- N/m
local MP, R = 1, 0.25          -- kg, m (disc)
local M1, M2 = 1.6, 1.5        -- kg
local CEILING = {0, 6, 0}
local SPRING0 = 1.5            -- m, drawn length of the unstretched spring
local ROPE = 2                 -- m, each side at the start
local G, M11, M12, M22, YEQ
local sys, axle, b1, b2, period, drift

function scenario.on_start(ctx)
  local gv = world.gravity()
  G = math.sqrt(gv.x ^ 2 + gv.y ^ 2 + gv.z ^ 2)
  M11, M12, M22 = MP + M1 + M2, M1 - M2, MP / 2 + M1 + M2
  YEQ = (M11 - M12 * (M1 - M2) / M22) * G / K
  world.plane{color = {0.55, 0.57, 0.6}}
  world.box{type = "static", size = {2, 0.1, 1}, position = {0, CEILING[2] + 0.05, 0}, color = {0.4, 0.4, 0.45}}
  sys = ode.system{
    state = {0, 0, 0, 0},  -- y, x, y', x'
    method = param("method", "rk4"),
    derivative = function(t, s)
      local q1, q2 = M11 * G - K * s[1], (M1 - M2) * G
      local det = M11 * M22 - M12 * M12
      return {s[3], s[4], (M22 * q1 - M12 * q2) / det, (M11 * q2 - M12 * q1) / det}
    end,
    energy = function(s)
      local T = 0.5 * (MP * s[3] ^ 2 + MP / 2 * s[4] ^ 2 + M1 * (s[3] + s[4]) ^ 2 + M2 * (s[3] - s[4]) ^ 2)
      return T + 0.5 * K * s[1] ^ 2 - M11 * G * s[1] - (M1 - M2) * G * s[2]
    end,
  }
  axle = world.sphere{type = "kinematic", radius = R, position = {0, CEILING[2] - SPRING0, 0}, color = {0.6, 0.6, 0.7}}
  b1 = world.box{type = "kinematic", size = {0.3, 0.3, 0.3}, position = {-R, 0, 0}, color = {0.85, 0.35, 0.25}}
  b2 = world.box{type = "kinematic", size = {0.28, 0.28, 0.28}, position = {R, 0, 0}, color = {0.3, 0.55, 0.85}}
  period = ode_models.period_tracker()
  drift = ode_models.drift_tracker(M11 * G * YEQ)
end

function scenario.on_update(ctx, dt)
  sys:step(dt, 4)
  local y, x = sys:get(1), sys:get(2)
  local ay = CEILING[2] - SPRING0 - y
  axle:set_position{0, ay, 0}
  local p1 = {-R, ay - ROPE - x, 0}
  local p2 = {R, ay - ROPE + x, 0}
  b1:set_position(p1)
  b2:set_position(p2)
  -- Spring as a zig-zag, ropes as lines.
  local n, top = 12, CEILING[2]
  for i = 0, n - 1 do
    local ya, yb = top - (top - ay) * i / n, top - (top - ay) * (i + 1) / n
    draw_line({(i % 2 == 0) and -0.1 or 0.1, ya, 0}, {(i % 2 == 0) and 0.1 or -0.1, yb, 0}, {0.9, 0.9, 0.3})
  end
  draw_line({-R, ay, 0}, p1, {0.8, 0.8, 0.8})
  draw_line({R, ay, 0}, p2, {0.8, 0.8, 0.8})
  period.feed(sys:time(), y - YEQ)
  drift.feed(sys:energy())
  hud_text(ode_models.cost_line(sys))
end

function scenario.on_finish(ctx)
  local ms = M11 - M12 * M12 / M22
  local theory = 2 * math.pi / math.sqrt(K / ms)
  expect("axle period / 2 pi sqrt(Ms / k)", (period.period() or 0) / theory, {min = 0.999, max = 1.001})
  expect("energy drift / ((MP + m1 + m2) g y_eq)", drift.worst, {max = 1e-6})
end

return scenario
