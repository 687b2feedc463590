-- Applied springs and the world's integrator (integrator = "sdirk2" below,
-- or --integrator NAME).
--
--   stiff: a 1 kg ball hangs from a spring with k = 1e6 N/m (k/m = 1e6,
--     omega = 1000 rad/s; omega h = 2.1 with 8 substeps at 60 Hz, past the
--     limit 2 of the default symplectic Euler). SDIRK2 is L-stable: the
--     stiff mode is damped and the ball settles at its static sag m g / k
--     = 9.81 um below the spring's rest end. Expectation: sag within 1 %.
--   soft: a 1 kg ball on a spring with k/m = 100 (period 2 pi / 10 =
--     0.628 s) bobs under gravity. Expectation: period within 0.5 % (SDIRK2
--     is second order: its phase error is far below that at h = 1/480 s).
--   pair: two balls joined by a spring fly apart and back in free fall;
--     internal forces keep the centre of mass on the free-fall parabola
--     (expectation: within 1 mm).
--
--   tumble run base:springs                       (sdirk2: every expectation holds)
--   tumble run base:springs --integrator symplectic_euler   (the stiff spring blows up)
--   tumble run base:springs --integrator rk4      (omega h = 2.1 < 2.83: stable, undamped)

local scenario = {
  title = "Springs: stiff and soft, with an implicit integrator",
  duration = 4,
  integrator = "sdirk2",
}

local G
local stiff, soft, a, b
local TOP = {0, 4, 0}
local bob_y, prev_v, crossings = nil, nil, {}
local worst_com = 0
local com0, v0

function scenario.on_start(ctx)
  local gv = world.gravity()
  G = math.sqrt(gv.x ^ 2 + gv.y ^ 2 + gv.z ^ 2)
  world.box{type = "static", size = {6, 0.2, 1}, position = {0, 4.1, 0}, color = {0.4, 0.4, 0.45}}
  stiff = world.sphere{radius = 0.1, mass = 1, position = {-2, 3, 0}, sleep = false, color = {0.9, 0.3, 0.2}}
  world.spring{a = stiff, anchor = {-2, 4, 0}, stiffness = 1e6, rest_length = 1}
  soft = world.sphere{radius = 0.1, mass = 1, position = {0, 3, 0}, sleep = false, color = {0.3, 0.6, 0.9}}
  world.spring{a = soft, anchor = {0, 4, 0}, stiffness = 100, rest_length = 1}
  a = world.sphere{radius = 0.1, mass = 1, position = {6, 8, 0}, velocity = {-1, 2, 0}, sleep = false, color = {0.3, 0.8, 0.4}}
  b = world.sphere{radius = 0.1, mass = 2, position = {7, 8, 0}, velocity = {1, 2, 0.5}, sleep = false, color = {0.3, 0.8, 0.4}}
  world.spring{a = a, b = b, stiffness = 300, rest_length = 1}
  local pa, pb = a:position(), b:position()
  com0 = {(pa.x + 2 * pb.x) / 3, (pa.y + 2 * pb.y) / 3, (pa.z + 2 * pb.z) / 3}
  v0 = {(-1 + 2 * 1) / 3, 2, 1 / 3}
end

function scenario.on_update(ctx, dt)
  for _, ball in ipairs({stiff, soft}) do
    local p = ball:position()
    draw_line({p.x, 4, 0}, {p.x, p.y, p.z}, {0.9, 0.9, 0.3})
  end
  local pa, pb = a:position(), b:position()
  draw_line({pa.x, pa.y, pa.z}, {pb.x, pb.y, pb.z}, {0.9, 0.9, 0.3})
  -- The pair's centre of mass against the free-fall parabola (time = end of this step's predecessor).
  local t = ctx.time
  local c = {(pa.x + 2 * pb.x) / 3, (pa.y + 2 * pb.y) / 3, (pa.z + 2 * pb.z) / 3}
  local e = {com0[1] + v0[1] * t, com0[2] + v0[2] * t - G * t * t / 2, com0[3] + v0[3] * t}
  if t < 2 then  -- the pair flies clear of the beam (x > 5)
    worst_com = math.max(worst_com, math.sqrt((c[1] - e[1]) ^ 2 + (c[2] - e[2]) ^ 2 + (c[3] - e[3]) ^ 2))
  end
  -- Upward crossings of the soft ball's velocity.
  local v = soft:velocity().y
  if prev_v and prev_v < 0 and v >= 0 then crossings[#crossings + 1] = t - dt * v / (v - prev_v) end
  prev_v = v
end

function scenario.on_finish(ctx)
  local sag = 1 - (4 - stiff:position().y)  -- m below the rest end (y = 3)
  expect("stiff spring sag / (m g / k)", -sag / (G / 1e6), {min = 0.99, max = 1.01})
  local period = #crossings >= 2 and (crossings[#crossings] - crossings[1]) / (#crossings - 1) or 0
  expect("soft spring period / (2 pi / 10)", period / (2 * math.pi / 10), {min = 0.995, max = 1.005})
  expect("spring pair centre of mass off the parabola (m)", worst_com, {max = 1e-3})
end

return scenario
