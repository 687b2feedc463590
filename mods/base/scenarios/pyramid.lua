-- A 2D pyramid of boxes: a base row of 20, each row above one box shorter and
-- shifted by half a box, 20 + 19 + ... + 1 = 210 boxes (the classic solver
-- benchmark, as in Box2D's samples and tools/compare's pyramid_20).
--
-- Physics: every box rests on two boxes of the row below (the top one on
-- two as well), a statically determinate-looking but actually indeterminate
-- load path; the exact rigid answer is still "nothing moves". The bottom
-- centre boxes carry about 20 boxes' weight. A solver that does not converge
-- lets the middle sag (boxes sink into each other) and the sides spread
-- (boxes slide outwards on the ground), which is what is measured.
--
--   tumble run base:pyramid --report r.json
--   tumble run base:pyramid --set base=30

local scenario = {
  title = "Pyramid: 210 boxes, base of 20",
  duration = 8,  -- seconds; long enough to settle or to start sliding apart
}

local SIZE = 1.0   -- m, cube edge
local GAP = 0.02   -- m, horizontal gap between neighbours in a row, so no side
                   -- contacts (and no side friction) take part: each box stands
                   -- only on the two below it
local boxes = {}
local top = nil
local max_drift = 0       -- m, largest horizontal displacement of any box, over the run
local max_sink = 0        -- m, largest downward displacement of any box, over the run

function scenario.on_start(ctx)
  world.plane{friction = 0.6, color = {0.55, 0.57, 0.6}}
  local base = math.floor(param("base", 20))
  local pitch = SIZE + GAP
  for row = 0, base - 1 do
    local n = base - row
    local y = SIZE / 2 + row * SIZE
    for i = 0, n - 1 do
      local x = (i - (n - 1) / 2) * pitch
      -- Rows alternate warm/cool so the courses read clearly in play.
      local c = row % 2 == 0 and {0.85, 0.5, 0.25} or {0.95, 0.8, 0.55}
      local b = world.box{size = {SIZE, SIZE, SIZE}, position = {x, y, 0}, density = 500,
                          friction = 0.6, restitution = 0, color = c}
      boxes[#boxes + 1] = {body = b, x0 = x, y0 = y, z0 = 0}
      top = boxes[#boxes]
    end
  end
end

function scenario.on_update(ctx, dt)
  for _, e in ipairs(boxes) do
    local p = e.body:position()
    max_drift = math.max(max_drift, math.sqrt((p.x - e.x0) ^ 2 + (p.z - e.z0) ^ 2))
    max_sink = math.max(max_sink, e.y0 - p.y)
  end
  hud_text(string.format("max drift %.1f mm, max sink %.1f mm", max_drift * 1000, max_sink * 1000))
end

function scenario.on_finish(ctx)
  local top_sink = top.y0 - top.body:position().y
  local fastest = 0
  for _, e in ipairs(boxes) do fastest = math.max(fastest, e.body:speed()) end

  -- Every box kept its place: no box moved sideways by more than 1 cm (m),
  -- the stack's own bound; a box sliding off its supports moves by 0.25 m+.
  expect("max horizontal drift of any box", max_drift, {max = 0.01})
  -- Vertical: the exact answer is no sink. The top box is `base` contacts
  -- above the ground; each may keep an overlap up to the solver's slop
  -- (5 mm, WorldSettings::linearSlop_m) and the engine's own bound on
  -- penetration is 2 cm (tests/physics), so no box, the top included, may
  -- sink by more than 2 cm over the run (m); a crushed pyramid sinks by more.
  -- It does sink: resting contacts settle into the overlap the slop allows,
  -- so a pyramid that carries its weight sinks by more than 0.1 mm; a
  -- world that never steps leaves it at exactly 0.
  expect("top box sink", top_sink, {min = 1e-4, max = 0.02})
  expect("largest sink of any box", max_sink, {max = 0.02})
  -- At rest at the end (m/s).
  expect("pyramid at rest", fastest, {max = 0.05})
  print(string.format("pyramid: %d boxes, max drift %.2f mm, max sink %.2f mm, top sink %.2f mm, fastest %.3f m/s",
                      #boxes, max_drift * 1000, max_sink * 1000, top_sink * 1000, fastest))
end

return scenario
