-- Newton's cradle: a row of equal balls; one (or two) swing in from the left
-- and the same number leave on the right while the rest stay still.
--
-- There are no joints yet, so the balls are free spheres in zero gravity
-- standing in for the bottom of the swing, with small gaps between them. The
-- gap matters: in the impulse-based model (Mirtich) collisions are resolved
-- one pair at a time, and a free row only reproduces the cradle if each
-- impact is a separate event. For two equal masses and e = 1, Newton's
-- restitution law plus conservation of momentum give
--     v1' = v2,  v2' = v1            (the balls swap velocities)
-- so momentum m v0 is handed along the row ball by ball and the last ball
-- leaves with v0; with k balls pulled back, the last k leave with v0.
-- Exactly: total momentum k m v0 and kinetic energy k m v0^2 / 2 are
-- conserved (frictionless, e = 1, no gravity), and every other ball ends at
-- rest.
--
-- How big a gap: the engine applies restitution in the substep of each
-- impact (1/480 s at the default 8 substeps), so impacts inside one 1/60 s
-- step stay separate events as long as the struck ball does not reach the
-- next one within about one substep: measured at v0 = 2 m/s, gaps of 2 cm,
-- 1 cm and 5 mm send the last ball off at exactly v0; 3 mm merges two
-- impacts (1.01 m/s, half the energy lost). Until 2026-11-25 restitution
-- ran once per step and 1 cm already failed. The default gap, 0.6 v0 dt
-- (2 cm at 2 m/s), dates from then; `--set gap=0.003` shows the limit.
--
--   tumble run base:cradle                     (one ball pulled back)
--   tumble run base:cradle --set pulled=2      (two balls)
--   tumble run base:cradle --set count=8 --set speed=4

local scenario = {
  title = "Newton's cradle: momentum passes along the row",
  duration = 2,  -- seconds: the impact at ~0.25 s, then the last ball flies off
}

local RADIUS = 0.25  -- m
local GAP            -- m, between neighbours at rest (see above)
local MASS = 1       -- kg, every ball
local PULL = 0.5     -- m, how far the moving balls start behind their rest places
local HEIGHT = 1.2   -- m, above the (decorative) floor; gravity is off, nothing falls

local balls = {}
local count, pulled, v0
local p0, e0              -- initial momentum (N s) and kinetic energy (J)
local max_p_err = 0       -- largest |p - p0| / p0 over the run
local max_e_err = 0       -- largest |E - e0| / e0 over the run

local function totals()
  local p, e = 0, 0
  for _, b in ipairs(balls) do
    p = p + b:mass() * b:velocity().x
    e = e + b:kinetic_energy()
  end
  return p, e
end

function scenario.on_start(ctx)
  world.set_gravity{0, 0, 0}
  -- A floor far below, only to give the eye a reference: the balls never
  -- reach it with gravity off.
  world.plane{color = {0.55, 0.57, 0.6}}
  count = math.floor(param("count", 5))
  pulled = math.floor(param("pulled", 1))
  -- Above the 1 m/s restitution threshold (WorldSettings::restitutionThreshold_mps),
  -- below which contacts do not bounce by design.
  v0 = param("speed", 2)  -- m/s
  -- ctx.dt is 0 in on_start, so the default 60 Hz step is assumed here.
  GAP = param("gap", 0.6 * v0 / 60)
  assert(pulled >= 1 and pulled < count, "cradle: need 1 <= pulled < count")
  local pitch = 2 * RADIUS + GAP
  for i = 1, count do
    local x = (i - (count + 1) / 2) * pitch
    local moving = i <= pulled
    if moving then x = x - PULL end
    balls[i] = world.sphere{radius = RADIUS, position = {x, HEIGHT, 0}, mass = MASS,
                            velocity = {moving and v0 or 0, 0, 0},
                            friction = 0, restitution = 1, rolling_resistance = 0, sleep = false,
                            color = moving and {0.85, 0.3, 0.25} or {0.75, 0.77, 0.8}}
  end
  p0 = pulled * MASS * v0
  e0 = pulled * MASS * v0 * v0 / 2
end

function scenario.on_update(ctx, dt)
  local p, e = totals()
  max_p_err = math.max(max_p_err, math.abs(p - p0) / p0)
  max_e_err = math.max(max_e_err, math.abs(e - e0) / e0)
  hud_text(string.format("momentum error %.2g, energy error %.2g", max_p_err, max_e_err))
end

function scenario.on_finish(ctx)
  -- The last `pulled` balls leave with v0; the exact answer is v0 itself.
  -- 1% allows float rounding over the count - 1 exchanges (m/s).
  local slowest_leaver, fastest_stayer = math.huge, 0
  for i = 1, count do
    local v = balls[i]:velocity()
    if i > count - pulled then
      slowest_leaver = math.min(slowest_leaver, v.x)
      expect(string.format("ball %d leaves with v0 (m/s)", i), v.x, {min = 0.99 * v0, max = 1.01 * v0})
    else
      fastest_stayer = math.max(fastest_stayer, math.sqrt(v.x ^ 2 + v.y ^ 2 + v.z ^ 2))
    end
  end
  -- Every other ball is left (almost) at rest: below 1% of v0 (m/s).
  expect("other balls at rest (m/s)", fastest_stayer, {max = 0.01 * v0})
  -- Conserved: momentum (equal and opposite impulses, no external force)
  -- and kinetic energy (e = 1, no friction), worst relative error over the
  -- whole run; rounding alone is ~1e-6, 1% catches any lost or invented bounce.
  expect("momentum conserved (relative error)", max_p_err, {max = 0.001})
  expect("kinetic energy conserved (relative error)", max_e_err, {max = 0.01})
  print(string.format("cradle: %d balls, %d pulled at %.2f m/s, gap %.1f cm; leavers >= %.4f m/s, "
                      .. "others <= %.4f m/s, momentum err %.2g, energy err %.2g",
                      count, pulled, v0, GAP * 100, slowest_leaver, fastest_stayer, max_p_err, max_e_err))
end

return scenario
