-- Effects: the five base emitters in one scene, each driven the way a game
-- would drive it, with checks that what is emitted matches the definitions.
--   fire + smoke   on a pile of logs (steady emitters at fixed points)
--   rain           over the whole scene (a 30 m box 14 m up)
--   dust           a burst when the crate lands (on_contact), and a stream
--                  from a sliding sled, attached to it, rate from its speed
--   sparks         a one-shot burst wherever the steel ball hits something
--
--   tumble run base:effects --screenshot fx.png --at 2
--
-- The checks: a steady emitter holds rate x mean lifetime particles (Little's
-- law: fire 90/s x 0.75 s = 67.5, rain 1800/s x 1.025 s = 1845); the dust
-- emitter rides on the sled; one-shot sparks free themselves once their last
-- spark has died; nothing exceeds its max_count.

local scenario = {
  title = "Effects: dust, smoke, fire, rain and sparks",
  duration = 6,  -- s
}

local fire, smoke, rain, sled_dust
local ground, crate, ball, sled
local crate_landed = false
local dust_bursts, spark_bursts = 0, 0
local sparks = {}          -- {emitter, time}
local fire_sum, rain_sum, samples = 0, 0, 0
local sled_dust_peak, rider_error = 0, 0
local smoke_top, rain_low = 0, math.huge
local total_peak = 0
local SLED_OFFSET = {0, -0.2, -0.45}  -- m, the sled's back edge, low

function scenario.on_start(ctx)
  ground = world.plane{friction = 0.5, color = {0.45, 0.5, 0.42}}
  -- A pile of logs for the fire.
  for i = 0, 3 do
    local along_x = i % 2 == 0
    world.box{size = along_x and {1.6, 0.25, 0.25} or {0.25, 0.25, 1.6},
              position = {0, 0.125 + 0.25 * i, 0}, mass = 8, color = {0.35, 0.22, 0.12}}
  end
  fire = particles.spawn("base:fire", {position = {0, 1.0, 0}})
  smoke = particles.spawn("base:smoke", {position = {0, 1.7, 0}})
  rain = particles.spawn("base:rain", {position = {0, 14, 0}})
  crate = world.box{size = {1, 1, 1}, position = {2.5, 3, 1.2}, mass = 20, color = {0.7, 0.55, 0.3}}
  ball = world.sphere{radius = 0.3, position = {-2.2, 4, 1.5}, mass = 2, restitution = 0.6, color = {0.6, 0.62, 0.7}}
  sled = world.box{size = {0.8, 0.4, 1.2}, position = {-1.2, 0.2, -3.5}, velocity = {0, 0, 4}, friction = 0.5,
                   mass = 30, color = {0.2, 0.35, 0.7}}
  sled_dust = particles.spawn("base:dust", {body = sled, offset = SLED_OFFSET}, {rate = 0})
end

function scenario.on_update(ctx, dt)
  -- Dust from the sled, like wheels from tyre slip: rate from its speed.
  local v = sled:velocity()
  local speed = math.sqrt(v.x * v.x + v.z * v.z)
  sled_dust:set_rate(speed > 0.05 and 30 * speed or 0)
  sled_dust_peak = math.max(sled_dust_peak, sled_dust:count())
  -- The attached emitter sits at the offset point of the sled (upright, no turn).
  local p, e = sled:position(), sled_dust:position()
  local dx, dy, dz = e.x - p.x - SLED_OFFSET[1], e.y - p.y - SLED_OFFSET[2], e.z - p.z - SLED_OFFSET[3]
  if ctx.time > 0 then rider_error = math.max(rider_error, math.sqrt(dx * dx + dy * dy + dz * dz)) end
  if ctx.time >= 2 then  -- past the longest fire and rain lifetimes: steady state
    fire_sum = fire_sum + fire:count()
    rain_sum = rain_sum + rain:count()
    samples = samples + 1
  end
  total_peak = math.max(total_peak, particles.count())
  local _, hi = smoke:bounds()
  if hi then smoke_top = math.max(smoke_top, hi.y) end
  local lo = rain:bounds()
  if lo then rain_low = math.min(rain_low, lo.y) end
end

function scenario.on_contact(ctx, a, b, impulse, point, normal)
  -- The crate's first touch of the ground (the impulse reported when a
  -- contact begins is only its first substep's share, so the pair decides).
  if not crate_landed and ((a == crate and b == ground) or (a == ground and b == crate)) then
    crate_landed = true
    dust_bursts = dust_bursts + 1
    particles.burst("base:dust", 60, {position = {point.x, 0.1, point.z}}, {speed = {1.5, 3.5}})
  end
  if (a == ball or b == ball) and impulse > 3 then
    spark_bursts = spark_bursts + 1
    sparks[#sparks + 1] = {particles.spawn("base:sparks", {position = point}), ctx.time}
  end
end

function scenario.on_finish(ctx)
  expect("fire holds rate x mean life = 67.5 particles", fire_sum / math.max(1, samples), {min = 60, max = 75})
  expect("rain holds rate x mean life = 1845 drops", rain_sum / math.max(1, samples), {min = 1760, max = 1930})
  expect("smoke holds about rate x mean life = 72 puffs", smoke:count(), {min = 55, max = 90})
  -- Buoyancy 0.35 m/s^2 against drag 0.4/s: rising at up to ~0.9 m/s + its
  -- start speed for up to 5 s: the top puffs climb 3 to 5 m above the fire.
  expect("smoke rises above the fire, m", smoke_top, {min = 4.5, max = 7.0})
  -- Drops start 13.75..14.25 m up at 9.5..10 m/s; with gravity and drag
  -- 0.3/s, y(t) = y0 - (g/c) t + (g/c - v0)(1 - e^(-c t)) / c: after their
  -- 1.0..1.05 s the lowest is 0.1 m below the ground.
  expect("rain ends at the ground, m", rain_low, {min = -0.3, max = 0.3})
  expect("one dust burst when the crate landed", dust_bursts, {min = 1, max = 1})
  expect("sparks where the ball hit", spark_bursts, {min = 1})
  local stale = 0
  for _, s in ipairs(sparks) do
    -- duration 0.05 s + longest spark 0.9 s: gone one second after the hit
    if ctx.time - s[2] > 1.0 and s[1]:alive() then stale = stale + 1 end
  end
  expect("finished spark bursts freed themselves", stale, {max = 0})
  expect("sled dust rode on the sled, m", rider_error, {max = 0.01})
  expect("the sliding sled kicked up dust", sled_dust_peak, {min = 20})
  -- It stopped after v / (mu g) = 0.8 s; the last dust (2.4 s) is long gone.
  expect("no dust once the sled stood still", sled_dust:count(), {max = 0})
  expect("never more than the max_counts allow", total_peak, {max = 200 + 200 + 2500 + 600 + 600 + 400 * #sparks})
end

return scenario
