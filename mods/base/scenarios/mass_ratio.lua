-- Heavy on light: two-box stacks whose top box is 100 and 1000 times heavier
-- than the 1 kg box it stands on (same 1 m cubes; a steel block on a crate).
--
-- Physics: still a static equilibrium, so the exact answer is that nothing
-- moves. The light box is squeezed between the ground (normal force
-- (1 + R) m g) and the heavy box (R m g). For an iterative solver this is the
-- hard case: an impulse on the light box changes its velocity R times more
-- than the same impulse changes the heavy one's, so Gauss-Seidel converges
-- slowly (the effective-mass ratio is the condition number), the light box
-- gets squashed into the ground, and any sideways error in its friction
-- impulses walks the heavy box off. Sleep is allowed (resting is the right
-- end state); the tests also run it with physics.sleep=false.
--
--   tumble run base:mass_ratio
--   tumble run base:mass_ratio --set ratios=10000 --set physics.sleep=false

local scenario = {
  title = "Mass ratio: 100 kg and 1000 kg boxes on 1 kg boxes",
  duration = 5,  -- seconds
}

local SIZE = 1.0    -- m, cube edge
local LIGHT = 1     -- kg
local stacks = {}   -- {ratio, light, heavy, start positions, worst figures}

local function new_stack(ratio, x)
  local light = world.box{size = {SIZE, SIZE, SIZE}, position = {x, SIZE / 2, 0}, mass = LIGHT,
                          friction = 0.6, color = {0.85, 0.7, 0.45}}
  -- The heavier the box, the darker: steel-grey for 1000 kg.
  local shade = 0.75 - 0.15 * math.log(ratio, 10)
  local heavy = world.box{size = {SIZE, SIZE, SIZE}, position = {x, 1.5 * SIZE, 0}, mass = LIGHT * ratio,
                          friction = 0.6, color = {shade, shade, shade + 0.05}}
  return {ratio = ratio, light = light, heavy = heavy, x = x,
          drift = 0, light_drift = 0, heavy_sink = 0, light_sink = 0, min_up = 1}
end

function scenario.on_start(ctx)
  world.plane{friction = 0.6, color = {0.55, 0.57, 0.6}}
  -- `--set ratios=R` runs one stack of ratio R instead of the two defaults.
  local ratios = {100, 1000}
  local only = param("ratios", 0)
  if only > 0 then ratios = {only} end
  for i, r in ipairs(ratios) do
    stacks[i] = new_stack(r, (i - (#ratios + 1) / 2) * 3)
  end
end

function scenario.on_update(ctx, dt)
  for _, s in ipairs(stacks) do
    local ph, pl = s.heavy:position(), s.light:position()
    s.drift = math.max(s.drift, math.sqrt((ph.x - s.x) ^ 2 + ph.z ^ 2))
    s.light_drift = math.max(s.light_drift, math.sqrt((pl.x - s.x) ^ 2 + pl.z ^ 2))
    s.heavy_sink = math.max(s.heavy_sink, 1.5 * SIZE - ph.y)
    s.light_sink = math.max(s.light_sink, 0.5 * SIZE - pl.y)
    s.min_up = math.min(s.min_up, s.heavy:up().y, s.light:up().y)
    -- Still: the fastest either box moved from 1 s before the default end on.
    if ctx.time >= scenario.duration - 1 then
      s.late_speed = math.max(s.late_speed or 0, s.heavy:speed(), s.light:speed())
    end
  end
end

function scenario.on_finish(ctx)
  local summary = {}
  for _, s in ipairs(stacks) do
    local tag = string.format("1:%d", s.ratio)
    -- Tolerances (m). The exact answer is no motion at all. Up to 1:100 the
    -- stack is held to the 20-box stack's 1 cm sideways and to the engine's
    -- 2 cm penetration bound (measured: 0.4 mm drift, 1.6 mm sink). Above
    -- that, the engine's declared tolerance at 1:1000 is 3 cm
    -- (tests/physics StacksWithLargeMassRatiosStand); measured here at the
    -- defaults, worst over 5 s: 27.6 mm heavy-box drift and 23.7 mm sink
    -- (the run report's penetration_max_m, 27.6 mm, exceeds the 2 cm the
    -- engine holds elsewhere). "Standing" itself would allow 0.5 m, where
    -- the heavy box tips off, so these bounds are the engine's, not slack.
    local tol = s.ratio <= 100 and {drift = 0.01, sink = 0.02} or {drift = 0.03, sink = 0.03}
    expect(tag .. " heavy box horizontal drift", s.drift, {max = tol.drift})
    expect(tag .. " light box horizontal drift", s.light_drift, {max = tol.drift})
    -- The heavy box does sink: two resting contacts settle into the overlap
    -- the slop allows (> 0.1 mm); a world that never steps leaves it at 0.
    expect(tag .. " heavy box sink", s.heavy_sink, {min = 1e-4, max = tol.sink})
    expect(tag .. " light box sink", s.light_sink, {max = tol.sink})
    -- Upright (tilt under 2.6 degrees).
    expect(tag .. " boxes upright", s.min_up, {min = 0.999})
    -- Still during the last second of the default 5 s run (from t = 4 s on),
    -- below the sleep threshold's speed (m/s).
    expect(tag .. " at rest in the last second", s.late_speed or math.huge, {max = 0.05})
    summary[#summary + 1] = string.format("%s drift %.2f/%.2f mm sink %.2f/%.2f mm last-second speed %.3f m/s", tag,
                                          s.drift * 1000, s.light_drift * 1000, s.heavy_sink * 1000,
                                          s.light_sink * 1000, s.late_speed or -1)
  end
  print("mass_ratio (heavy/light): " .. table.concat(summary, "; "))
end

return scenario
