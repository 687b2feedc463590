-- Cylinders on a slope and on the ground:
--   green log (a solid cylinder lying across the slope): rolls down at
--                a = g sin theta / (1 + 1/2) = 2/3 g sin theta;
--   blue sphere beside it: rolls at 5/7 g sin theta, so it pulls ahead;
--   orange drum standing on its cap on the ground: stays put;
--   grey log dropped on its side on the ground: comes to rest on its side.
--
-- Physics. A body rolling without slipping has m a = m g sin theta - F and
-- I alpha = F r with alpha = a / r, so a = g sin theta / (1 + I / (m r^2)):
-- I = m r^2 / 2 for a solid cylinder (any length), 2/5 m r^2 for a sphere.
-- The cylinder needs F = 1/3 m g sin theta <= mu m g cos theta, i.e.
-- mu >= tan theta / 3; the slope has friction 1, enough up to 70 degrees.
--
-- Accelerations are measured from velocity differences along the slope
-- between t = 0.25 s (after contact has settled) and t = 1.25 s.
--
--   tumble run base:rolling
--   tumble run base:rolling --set angle=12 --set radius=0.15

local scenario = {
  title = "Rolling: a cylinder and a sphere race down a slope; a drum stands, a log lies",
  duration = 3,  -- seconds
}

local G = 9.81          -- m/s^2, the engine's default gravity (-y); read back below
local LENGTH = 10       -- m, along the slope
local WIDTH = 6         -- m, across (z)
local THICK = 0.5       -- m
local T1, T2 = 0.25, 1.25  -- s, measurement window

local theta, radius
local down              -- unit vector down the slope
local log, ball, drum, lying
local drum_start
local samples = {}      -- samples[name] = {t1 =, v1 =, t2 =, v2 =, w2 =}
local max_drum_move = 0 -- m

local function along(v) return v.x * down[1] + v.y * down[2] + v.z * down[3] end

function scenario.on_start(ctx)
  local gv = world.gravity()
  G = math.sqrt(gv.x ^ 2 + gv.y ^ 2 + gv.z ^ 2)
  theta = math.rad(param("angle", 25))
  radius = param("radius", 0.3)
  local c, s = math.cos(theta), math.sin(theta)
  local u = {-c, s, 0}      -- up the slope
  local n = {s, c, 0}       -- surface normal
  down = {c, -s, 0}
  local centre = {0, LENGTH / 2 * s + THICK / 2 * c, 0}
  world.plane{friction = 0.6, color = {0.55, 0.57, 0.6}}
  world.box{type = "static", size = {LENGTH, THICK, WIDTH}, position = centre, rotation = {0, 0, -theta},
            friction = 1, color = {0.45, 0.5, 0.6}}
  local function on_slope(a, z, h)
    local off = THICK / 2 + h
    return {centre[1] + u[1] * a + n[1] * off, centre[2] + u[2] * a + n[2] * off, z}
  end
  local start = 3.5  -- m up the slope from the centre
  -- The log's axis (its local y) along z, across the slope.
  log = world.cylinder{radius = radius, height = 1.2, position = on_slope(start, -1.2, radius),
                       rotation = {math.pi / 2, 0, 0}, friction = 1, mass = 20, sleep = false,
                       color = {0.4, 0.75, 0.4}}
  ball = world.sphere{radius = radius, position = on_slope(start, 1.2, radius), friction = 1,
                      rolling_resistance = 0, sleep = false, color = {0.25, 0.55, 0.85}}
  -- Both beside the ramp (it spans z from -3 to 3), out of the rollers' way.
  drum = world.cylinder{radius = 0.35, height = 0.9, position = {0, 0.45, -5}, mass = 40,
                        color = {0.9, 0.55, 0.2}}
  lying = world.cylinder{radius = 0.25, height = 1.4, position = {0, 0.8, 5}, rotation = {math.pi / 2, 0, 0.05},
                         mass = 30, color = {0.6, 0.6, 0.62}}
  drum_start = drum:position()
end

function scenario.on_update(ctx, dt)
  local p = drum:position()
  max_drum_move = math.max(max_drum_move, math.sqrt((p.x - drum_start.x) ^ 2 + (p.y - drum_start.y) ^ 2
                                                    + (p.z - drum_start.z) ^ 2))
  for name, b in pairs({log = log, ball = ball}) do
    local s = samples[name] or {}
    samples[name] = s
    if not s.t1 and ctx.time >= T1 then
      s.t1, s.v1 = ctx.time, along(b:velocity())
    elseif not s.t2 and ctx.time >= T2 then
      local w = b:angular_velocity()
      s.t2, s.v2, s.w2 = ctx.time, along(b:velocity()), math.sqrt(w.x ^ 2 + w.y ^ 2 + w.z ^ 2)
    end
  end
  hud_text(string.format("slope %.0f deg: cylinder 2/3 g sin, sphere 5/7 g sin", math.deg(theta)))
end

function scenario.on_finish(ctx)
  local l, b = samples.log, samples.ball
  assert(l and l.t2 and b and b.t2, "rolling: run for at least " .. T2 .. " s to measure the accelerations")
  local a_log = (l.v2 - l.v1) / (l.t2 - l.t1)
  local a_ball = (b.v2 - b.v1) / (b.t2 - b.t1)
  local want_log = 2 / 3 * G * math.sin(theta)
  local want_ball = 5 / 7 * G * math.sin(theta)
  -- Rolling: within 1% (m/s^2), and without slipping, w r = v, within 1% (m/s).
  expect("rolling cylinder acceleration (m/s^2)", a_log, {min = 0.99 * want_log, max = 1.01 * want_log})
  expect("cylinder rolls without slipping: w r (m/s)", l.w2 * radius, {min = 0.99 * l.v2, max = 1.01 * l.v2})
  expect("rolling sphere acceleration (m/s^2)", a_ball, {min = 0.99 * want_ball, max = 1.01 * want_ball})
  -- Standing on its cap: no motion beyond 1 mm (the contact settling into its slop).
  expect("drum on its cap stays (m moved)", max_drum_move, {max = 0.001})
  -- Lying: the centre ends one radius above the ground, the axis level.
  local p, up = lying:position(), lying:up()
  expect("log lies on its side: centre height (m)", p.y, {min = 0.25 - 0.003, max = 0.25 + 0.003})
  expect("log lies on its side: axis level (|up.y|)", math.abs(up.y), {max = 0.01})
  print(string.format("rolling %.1f deg: cylinder a %.4f (want %.4f, %+.2f%%), w r / v %.4f; sphere a %.4f "
                      .. "(want %.4f, %+.2f%%); drum moved %.3f mm; log at %.4f m",
                      math.deg(theta), a_log, want_log, 100 * (a_log / want_log - 1), l.w2 * radius / l.v2,
                      a_ball, want_ball, 100 * (a_ball / want_ball - 1), max_drum_move * 1000, p.y))
end

return scenario
