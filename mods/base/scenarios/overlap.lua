-- 50 unit cubes spawned on top of each other: random positions in a
-- 2 x 2.5 x 2 m block of space, so every box overlaps several others, often
-- by most of its size. A game does this all the time (a spawner, a level
-- loaded in the wrong place, a teleport) and the engine must untangle it
-- gently.
--
-- Physics: overlap is not a state real bodies can be in, so there is no
-- force that "should" act; what is required is that removing it adds no
-- energy. With position-only correction (split impulses: the push-out never
-- enters the velocities, WorldSettings::maxPushoutSpeed_mps) the only kinetic
-- energy the boxes can get comes from falling. 50 m^3 of boxes do not fit in
-- the 10 m^3 they were spawned in, so the push-out lifts the pile (measured:
-- the highest centre reaches 3.8 to 4.7 m over seeds 1-10), and a free fall
-- from 4.7 m ends at sqrt(2 g h) = 9.6 m/s; the issue's bound, 10 m/s, is
-- just above that (a box fired out of the pile would be far faster). The
-- lifted pile then collapses, boxes tumble off it and all settle by ~7.5 s.
-- At the end every pair of boxes must be separated, checked exactly with
-- the separating-axis test on the oriented boxes (15 axes), allowing the
-- engine's 2 cm penetration bound.
--
--   tumble run base:overlap
--   tumble run base:overlap --seed 7 --set count=80

local scenario = {
  title = "Overlap: 50 boxes spawned inside each other separate gently",
  duration = 10,  -- seconds: separated in about 1 s, the lifted pile collapses and settles by ~7.5 s
}

local HALF = 0.5   -- m, half edge of the cubes
local boxes = {}
local max_speed = 0     -- m/s, fastest any box moved at any step
local max_height = 0    -- m, highest any box centre went

-- Unit axes of a body's frame in world coordinates, from its quaternion.
local function axes(q)
  local w, x, y, z = q.w, q.x, q.y, q.z
  return {
    {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)},
    {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)},
    {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)},
  }
end

local function dot(a, b) return a[1] * b[1] + a[2] * b[2] + a[3] * b[3] end
local function cross(a, b) return {a[2] * b[3] - a[3] * b[2], a[3] * b[1] - a[1] * b[3], a[1] * b[2] - a[2] * b[1]} end

-- Penetration depth of two equal cubes (m; <= 0 when separated): the
-- smallest overlap of their projections over the 15 separating axes.
local function penetration(pa, qa, pb, qb)
  local A, B = axes(qa), axes(qb)
  local d = {pb.x - pa.x, pb.y - pa.y, pb.z - pa.z}
  local candidates = {A[1], A[2], A[3], B[1], B[2], B[3]}
  for i = 1, 3 do
    for j = 1, 3 do
      local c = cross(A[i], B[j])
      local len = math.sqrt(dot(c, c))
      if len > 1e-6 then candidates[#candidates + 1] = {c[1] / len, c[2] / len, c[3] / len} end
    end
  end
  local depth = math.huge
  for _, L in ipairs(candidates) do
    local ra = HALF * (math.abs(dot(A[1], L)) + math.abs(dot(A[2], L)) + math.abs(dot(A[3], L)))
    local rb = HALF * (math.abs(dot(B[1], L)) + math.abs(dot(B[2], L)) + math.abs(dot(B[3], L)))
    depth = math.min(depth, ra + rb - math.abs(dot(d, L)))
  end
  return depth
end

-- Lowest corner of a cube above y = 0 (m).
local function lowest(p, q)
  local A = axes(q)
  return p.y - HALF * (math.abs(A[1][2]) + math.abs(A[2][2]) + math.abs(A[3][2]))
end

function scenario.on_start(ctx)
  world.plane{friction = 0.6, color = {0.55, 0.57, 0.6}}
  local count = math.floor(param("count", 50))
  local palette = {{0.85, 0.35, 0.25}, {0.25, 0.55, 0.85}, {0.95, 0.75, 0.2}, {0.4, 0.75, 0.4}, {0.7, 0.45, 0.8}}
  for i = 1, count do
    -- Uniform in x, z in [-1, 1] m and centre height in [0.5, 3] m (math.random
    -- is seeded with the run's seed), random orientation.
    local p = {math.random() * 2 - 1, 0.5 + math.random() * 2.5, math.random() * 2 - 1}
    local r = {(math.random() - 0.5) * 2, (math.random() - 0.5) * 2, (math.random() - 0.5) * 2}
    boxes[i] = world.box{size = {2 * HALF, 2 * HALF, 2 * HALF}, position = p, rotation = r, density = 500,
                         friction = 0.6, restitution = 0, color = palette[(i - 1) % #palette + 1]}
  end
end

function scenario.on_update(ctx, dt)
  for _, b in ipairs(boxes) do
    max_speed = math.max(max_speed, b:speed())
    max_height = math.max(max_height, b:position().y)
  end
  hud_text(string.format("fastest box so far %.2f m/s", max_speed))
end

function scenario.on_finish(ctx)
  local worst, overlapping, low, fastest = -math.huge, 0, math.huge, 0
  local state = {}
  for i, b in ipairs(boxes) do
    state[i] = {p = b:position(), q = b:orientation()}
    low = math.min(low, lowest(state[i].p, state[i].q))
    fastest = math.max(fastest, b:speed())
  end
  for i = 1, #boxes do
    for j = i + 1, #boxes do
      local pi, pj = state[i].p, state[j].p
      -- Cubes whose centres are further apart than their diagonals cannot touch.
      if (pi.x - pj.x) ^ 2 + (pi.y - pj.y) ^ 2 + (pi.z - pj.z) ^ 2 < 3 * (2 * HALF) ^ 2 then
        local depth = penetration(pi, state[i].q, pj, state[j].q)
        worst = math.max(worst, depth)
        if depth > 0.02 then overlapping = overlapping + 1 end
      end
    end
  end
  worst = math.max(worst, 0)
  -- Gently: no box ever faster than 10 m/s (free fall from the top of the
  -- spawn volume alone reaches 7.7 m/s; see the top of the file).
  expect("fastest box over the run (m/s)", max_speed, {max = 10})
  -- Separated: no pair of boxes overlaps by more than the engine's 2 cm
  -- penetration bound at the end (m, separating-axis depth).
  expect("deepest box-box overlap at the end (m)", worst, {max = 0.02})
  -- Nothing pushed into the floor, within the 2 cm penetration bound (m).
  expect("lowest corner above the floor (m)", low, {min = -0.02})
  -- Settled at the end (m/s).
  expect("all boxes at rest", fastest, {max = 0.05})
  print(string.format("overlap: %d boxes, fastest %.2f m/s, highest %.2f m, end: deepest overlap %.2f mm "
                      .. "(%d pairs > 2 cm), lowest corner %.2f mm, fastest now %.3f m/s",
                      #boxes, max_speed, max_height, worst * 1000, overlapping, low * 1000, fastest))
end

return scenario
