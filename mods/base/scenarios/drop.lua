-- The default scenario: boxes, spheres and capsules fall onto a plane,
-- bounce and settle. Its expectations check that every body comes to rest
-- above the plane: nothing sinks in, nothing keeps moving, nothing explodes.
--
--   tumble run base:drop --seconds 5 --report r.json
--   tumble run base:drop --set count=40        (more bodies)

local scenario = {
  title = "Drop: boxes, spheres and capsules settle on a plane",
  duration = 6,  -- seconds, when run without --seconds/--steps
}

local bodies = {}

-- Height of the lowest point of a body above y = 0, from its shape.
local function lowest_point(b, shape, size)
  local p = b:position()
  local up = b:up()
  if shape == "sphere" then
    return p.y - size.radius
  elseif shape == "capsule" then
    return p.y - math.abs(up.y) * size.length / 2 - size.radius
  end
  -- box: support in -y of an oriented box is the sum of |axis_i . y| * half_i;
  -- checking the 8 corners is simpler than rebuilding the rotation here.
  local q = b:orientation()
  local function rotate(x, y, z)
    -- v' = v + 2 w (q x v) + 2 q x (q x v)
    local cx = q.y * z - q.z * y
    local cy = q.z * x - q.x * z
    local cz = q.x * y - q.y * x
    local dx = q.y * cz - q.z * cy
    local dy = q.z * cx - q.x * cz
    local dz = q.x * cy - q.y * cx
    return x + 2 * (q.w * cx + dx), y + 2 * (q.w * cy + dy), z + 2 * (q.w * cz + dz)
  end
  local low = math.huge
  for sx = -1, 1, 2 do
    for sy = -1, 1, 2 do
      for sz = -1, 1, 2 do
        local _, y = rotate(sx * size.x / 2, sy * size.y / 2, sz * size.z / 2)
        low = math.min(low, p.y + y)
      end
    end
  end
  return low
end

function scenario.on_start(ctx)
  world.plane{friction = 0.6, color = {0.55, 0.57, 0.6}}
  local count = param("count", 18)
  local palette = {{0.85, 0.35, 0.25}, {0.25, 0.55, 0.85}, {0.95, 0.75, 0.2}, {0.4, 0.75, 0.4}}
  for i = 1, count do
    local kind = ({"box", "sphere", "capsule"})[(i - 1) % 3 + 1]
    -- A 3 x 3 grid per layer, layers 1.8 m apart, with a little jitter: no two
    -- bodies start overlapping and none falls more than a few metres.
    local slot = (i - 1) % 9
    local layer = (i - 1) // 9
    local x = (slot % 3 - 1) * 1.8 + (math.random() - 0.5) * 0.3
    local z = (slot // 3 - 1) * 1.8 + (math.random() - 0.5) * 0.3
    local y = 1.5 + layer * 1.8
    local rotation = {(math.random() - 0.5) * 2, (math.random() - 0.5) * 2, (math.random() - 0.5) * 2}
    local color = palette[(i - 1) % #palette + 1]
    local b, size
    if kind == "box" then
      size = {x = 0.6 + math.random() * 0.6, y = 0.4 + math.random() * 0.5, z = 0.6 + math.random() * 0.6}
      b = world.box{size = {size.x, size.y, size.z}, position = {x, y, z}, rotation = rotation,
                    density = 500, friction = 0.6, restitution = 0.1, color = color}
    elseif kind == "sphere" then
      size = {radius = 0.3 + math.random() * 0.3}
      b = world.sphere{radius = size.radius, position = {x, y, z}, density = 500,
                       friction = 0.6, restitution = 0.5, rolling_resistance = 0.2, color = color}
    else
      size = {radius = 0.2 + math.random() * 0.15, length = 0.6 + math.random() * 0.6}
      b = world.capsule{radius = size.radius, length = size.length, position = {x, y, z},
                        rotation = rotation, density = 500, friction = 0.6, restitution = 0.2,
                        rolling_resistance = 0.2, color = color}
    end
    bodies[#bodies + 1] = {body = b, shape = kind, size = size, start_y = y}
  end
end

function scenario.on_finish(ctx)
  local fastest, lowest, highest, fell = 0, math.huge, -math.huge, math.huge
  for _, entry in ipairs(bodies) do
    fell = math.min(fell, entry.start_y - entry.body:position().y)
    fastest = math.max(fastest, entry.body:speed())
    local low = lowest_point(entry.body, entry.shape, entry.size)
    lowest = math.min(lowest, low)
    highest = math.max(highest, entry.body:position().y)
  end
  -- At rest: after a few seconds every body has stopped (m/s).
  expect("all bodies at rest", fastest, {max = 0.05})
  -- Above the plane: no body sank into it by more than 2 cm (m).
  expect("nothing sank into the plane", lowest, {min = -0.02})
  -- Nothing was launched away or fell through.
  expect("all bodies near the ground", highest, {min = 0, max = 5})
  -- Every body fell (m): bodies of the lowest layer start with their
  -- centres 1.5 m up and end on the plane, centre at most 0.95 m up (a
  -- capsule on its end: 0.35 + 0.6), a fall of at least 0.55 m; each upper
  -- layer starts 1.8 m above the one below and lands on it or beside it.
  -- 0.3 m leaves room for a body propped on another; a world that does
  -- not step gives 0.
  expect("every body fell", fell, {min = 0.3})
end

return scenario
