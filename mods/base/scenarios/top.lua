-- Eberly's spinning top in Euler angles: a symmetric top on a fixed tip,
-- tilt theta, precession phi, spin psi; moments I1 (about the tip, across
-- the axis) and I3 (along it), centre of mass l from the tip. From
--   L = I1/2 (theta'^2 + phi'^2 sin^2 theta) + I3/2 (psi' + phi' cos theta)^2 - m g l cos theta
-- phi and psi are cyclic: w3 = psi' + phi' cos theta and
-- p_phi = I1 phi' sin^2 theta + I3 w3 cos theta are constants, so
--   phi'  = (p_phi - I3 w3 cos theta) / (I1 sin^2 theta),  psi' = w3 - phi' cos theta,
--   theta'' = (I1 phi'^2 sin theta cos theta - I3 w3 phi' sin theta + m g l sin theta) / I1.
-- State {theta, phi, psi, theta'}; energy
--   E = I1/2 (theta'^2 + phi'^2 sin^2 theta) + I3/2 w3^2 + m g l cos theta.
-- Released with phi' = theta' = 0 at theta0 and spinning at w3 = 100 rad/s
-- it nods (nutation) between theta0 and theta1, where theta' = 0 again:
-- energy and p_phi give I1/2 phi'(theta1)^2 sin^2 theta1 = m g l (cos theta0
-- - cos theta1), solved here by bisection (about 2 I1 m g l sin theta0 /
-- (I3 w3)^2 deep for a fast top). On average it precesses at the slow root
-- of I1 cos theta W^2 - I3 w3 W + m g l = 0 (steady precession; m g l /
-- (I3 w3) in the fast-top limit; Goldstein sec. 5.7).
--
-- Expectations: energy drift within 1e-6 of m g l; the deepest tilt within
-- 1 % of theta1 - theta0; the mean precession rate within 1 % of the
-- steady rate at the mean tilt.
--
--   tumble run base:top
--   tumble run base:top --set spin=60

local ode_models = require "lib.ode_models"

local scenario = {
  title = "Spinning top in Euler angles (ode.system)",
  duration = 10,
}

local M, LCM = 1, 0.1        -- kg, m from the tip to the centre of mass
local I1, I3 = 0.005, 0.004  -- kg m^2
local TIP = {0, 0.02, 0}
local G, W3, PPHI, THETA0
local sys, knob, drift
local theta_max = 0

local function phidot(theta) return (PPHI - I3 * W3 * math.cos(theta)) / (I1 * math.sin(theta) ^ 2) end

local function axis(theta, phi) return {math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi)} end

function scenario.on_start(ctx)
  local gv = world.gravity()
  G = math.sqrt(gv.x ^ 2 + gv.y ^ 2 + gv.z ^ 2)
  W3 = param("spin", 100)
  THETA0 = math.rad(param("tilt", 20))
  PPHI = I3 * W3 * math.cos(THETA0)  -- phi' = 0 at release
  world.plane{color = {0.55, 0.57, 0.6}}
  sys = ode.system{
    state = {THETA0, 0, 0, 0},
    method = param("method", "rk4"),
    derivative = function(t, y)
      local th = y[1]
      local pd = phidot(th)
      local s, c = math.sin(th), math.cos(th)
      return {y[4], pd, W3 - pd * c, (I1 * pd * pd * s * c - I3 * W3 * pd * s + M * G * LCM * s) / I1}
    end,
    energy = function(y)
      local pd = phidot(y[1])
      return 0.5 * I1 * (y[4] ^ 2 + pd * pd * math.sin(y[1]) ^ 2) + 0.5 * I3 * W3 * W3 + M * G * LCM * math.cos(y[1])
    end,
  }
  knob = world.sphere{type = "kinematic", radius = 0.06, position = {0, 1, 0}, color = {0.9, 0.5, 0.2}}
  drift = ode_models.drift_tracker(M * G * LCM)
end

function scenario.on_update(ctx, dt)
  sys:step(dt, 16)  -- nutation at I3 w3 / I1 = 80 rad/s: w h = 0.08
  local th, phi, psi = sys:get(1), sys:get(2), sys:get(3)
  theta_max = math.max(theta_max, th)
  -- Drawn 8x larger than the model so it can be seen.
  local scale = 8
  local a = axis(th, phi)
  local top = {TIP[1] + a[1] * 2 * LCM * scale, TIP[2] + a[2] * 2 * LCM * scale, TIP[3] + a[3] * 2 * LCM * scale}
  knob:set_position(top)
  draw_line(TIP, top, {0.9, 0.9, 0.9})
  -- A disc of spokes at the centre of mass, turned by psi (shows the spin).
  local c = {TIP[1] + a[1] * LCM * scale, TIP[2] + a[2] * LCM * scale, TIP[3] + a[3] * LCM * scale}
  local e1 = {math.cos(th) * math.cos(phi), -math.sin(th), math.cos(th) * math.sin(phi)}
  local e2 = {-math.sin(phi), 0, math.cos(phi)}
  for k = 0, 5 do
    local ang = psi + k * math.pi / 3
    local r = 0.35
    local p = {c[1] + r * (math.cos(ang) * e1[1] + math.sin(ang) * e2[1]),
               c[2] + r * (math.cos(ang) * e1[2] + math.sin(ang) * e2[2]),
               c[3] + r * (math.cos(ang) * e1[3] + math.sin(ang) * e2[3])}
    draw_line(c, p, k == 0 and {0.9, 0.2, 0.2} or {0.6, 0.6, 0.9})
  end
  drift.feed(sys:energy())
  hud_text(ode_models.cost_line(sys))
end

function scenario.on_finish(ctx)
  -- theta1: the other root of I1/2 (phi' sin)^2 - m g l (cos theta0 - cos theta).
  local function g(th) return 0.5 * I1 * (phidot(th) * math.sin(th)) ^ 2 - M * G * LCM * (math.cos(THETA0) - math.cos(th)) end
  local lo, hi = THETA0 + 1e-9, THETA0 + 0.5
  local fast_depth = 2 * I1 * M * G * LCM * math.sin(THETA0) / (I3 * W3) ^ 2
  lo = THETA0 + 0.1 * fast_depth  -- g < 0 just past theta0, > 0 beyond theta1
  for _ = 1, 200 do
    local mid = (lo + hi) / 2
    if g(mid) < 0 then lo = mid else hi = mid end
  end
  local depth = lo - THETA0
  local c = math.cos(THETA0 + depth / 2)
  local steady = (I3 * W3 - math.sqrt((I3 * W3) ^ 2 - 4 * I1 * c * M * G * LCM)) / (2 * I1 * c)
  local rate = sys:get(2) / sys:time()
  expect("energy drift / (m g l)", drift.worst, {max = 1e-6})
  expect("nutation depth / theory", (theta_max - THETA0) / depth, {min = 0.99, max = 1.01})
  expect("mean precession rate / steady precession", rate / steady, {min = 0.99, max = 1.01})
end

return scenario
