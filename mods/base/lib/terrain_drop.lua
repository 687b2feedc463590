-- Shared by the terrain scenarios (hills, island): static rocks around a
-- drop zone, spheres and boxes dropped 3 m above the terrain, and the
-- expectations that they come to rest on its surface: every body's centre is
-- at most its bounding radius + 0.15 m above the terrain height under it (as
-- world.raycast finds it), no part of any body is more than 2 cm inside the
-- terrain (a box's corners, and points of a sphere's lower half, against the
-- terrain height under each), nearly all stopped.
--
--   local terrain_drop = require "lib.terrain_drop"
--   return terrain_drop.scenario{title = ..., duration = 12, terrain = {...},
--                                center = function() return x, z end}
--
-- center() gives the drop zone's middle (m); it may read param().
-- def.time_of_day and def.weather set the sky (environment.set); --set
-- time_of_day=H and --set weather=storm override them. Rocks are drawn with
-- the shipped rock model over their collision boxes, and trees (drawn only,
-- collision = "none") stand around the zone: neither changes the physics.

local terrain_drop = {}

-- Terrain hit straight down at (x, z): the first one that is not a body.
local function ground_hit(x, z)
  for _, hit in ipairs(world.raycast_all({x, 2000, z}, {0, -1, 0}, 5000)) do
    if not hit.body:is_valid() then return hit end
  end
  return nil
end

-- v rotated by the unit quaternion q.
local function rotate(q, x, y, z)
  local cx, cy, cz = q.y * z - q.z * y, q.z * x - q.x * z, q.x * y - q.y * x
  local dx, dy, dz = q.y * cz - q.z * cy, q.z * cx - q.x * cz, q.x * cy - q.y * cx
  return x + 2 * (q.w * cx + dx), y + 2 * (q.w * cy + dy), z + 2 * (q.w * cz + dz)
end

-- How deep the body reaches into the terrain (m; <= 0 when it does not),
-- nil where there is no terrain under it.
local function sink_depth(e)
  local p = e.body:position()
  if e.size then  -- box: each corner against the terrain height under it
    local q, deepest = e.body:orientation(), -math.huge
    for sx = -1, 1, 2 do
      for sy = -1, 1, 2 do
        for sz = -1, 1, 2 do
          local x, y, z = rotate(q, sx * e.size[1] / 2, sy * e.size[2] / 2, sz * e.size[3] / 2)
          local hit = ground_hit(p.x + x, p.z + z)
          if not hit then return nil end
          deepest = math.max(deepest, hit.point.y - (p.y + y))
        end
      end
    end
    return deepest
  end
  -- sphere: points of its lower half (the bottom, and rings 30 and 60
  -- degrees up from it) against the terrain height under each
  local deepest = -math.huge
  for ring = 0, 2 do
    local a = math.rad(30 * ring)
    for k = 0, (ring == 0 and 0 or 7) do
      local phi = k * math.pi / 4
      local x, y, z = e.radius * math.sin(a) * math.cos(phi), -e.radius * math.cos(a), e.radius * math.sin(a) * math.sin(phi)
      local hit = ground_hit(p.x + x, p.z + z)
      if not hit then return nil end
      deepest = math.max(deepest, hit.point.y - (p.y + y))
    end
  end
  return deepest
end

local function ground(x, z)
  local hit = ground_hit(x, z)
  return hit and hit.point.y or nil
end

function terrain_drop.scenario(def)
  local scenario = {title = def.title, duration = def.duration, terrain = def.terrain}
  local center = def.center or function() return 0, 0 end
  local bodies = {}


  -- The shipped rock model (tools/meshgen) spans x -0.88..0.92, y -0.21..0.89,
  -- z -0.72..0.77 m; scaled over a rock's box with 15 % to spare, so the
  -- box's corners stay inside the rounder rock.
  local rock_min, rock_max = {-0.87769, -0.21122, -0.72266}, {0.92194, 0.89165, 0.76573}
  local function rock_look(body, size)
    local scale, offset = {}, {}
    for k = 1, 3 do
      scale[k] = 1.15 * size[k] / (rock_max[k] - rock_min[k])
      offset[k] = -scale[k] * 0.5 * (rock_min[k] + rock_max[k])
    end
    body:set_model("base:assets/models/rock.obj", {scale = scale, offset = offset})
  end

  function scenario.on_start(ctx)
    environment.set{time_of_day = param("time_of_day", def.time_of_day or 15.5),
                    weather = param("weather", def.weather or "clear"), clouds = def.clouds or 0.4}
    local cx, cz = center()
    if not ground(cx, cz) then
      expect("terrain present", false)
      world.plane{friction = 0.6}
      return
    end
    -- Static rocks around the drop zone: boxes partly sunk into the ground.
    for i = 1, param("rocks", 12) do
      local a = i * 2.4
      local x, z = cx + math.cos(a) * (14 + i * 0.7), cz + math.sin(a) * (14 + i * 0.7)
      local s = 0.8 + math.random() * 1.2
      local size = {s, s * 0.7, s * 1.1}
      local rock = world.box{type = "static", size = size, position = {x, ground(x, z) + s * 0.15, z},
                             rotation = {0, math.random() * 3, 0}, friction = 0.8, color = {0.45, 0.43, 0.4}}
      rock_look(rock, size)
    end
    -- Trees on a wider ring (fixed positions: no random numbers drawn, so
    -- the bodies below are placed exactly as before).
    for i = 1, param("trees", 10) do
      local a = i * 0.63 + 0.3
      local r = 24 + (i % 3) * 5
      local x, z = cx + math.cos(a) * r, cz + math.sin(a) * r
      local y = ground(x, z)
      if y then
        world.add_static_model("base:assets/models/tree.obj", {position = {x, y - 0.1, z}, rotation = {0, a * 2.7, 0},
                                                               scale = 0.9 + (i % 4) * 0.15, collision = "none"})
      end
    end
    local palette = {{0.85, 0.35, 0.25}, {0.25, 0.55, 0.85}, {0.95, 0.75, 0.2}, {0.4, 0.75, 0.4}}
    local count = param("count", 24)
    for i = 1, count do
      local x = cx + ((i - 1) % 6 - 2.5) * 3 + (math.random() - 0.5)
      local z = cz + ((i - 1) // 6 - 1.5) * 3 + (math.random() - 0.5)
      local y = ground(x, z) + 3
      local color = palette[(i - 1) % #palette + 1]
      local b, radius, size
      if i % 2 == 0 then
        radius = 0.3 + math.random() * 0.3
        b = world.sphere{radius = radius, position = {x, y, z}, density = 500, friction = 0.7,
                         restitution = 0.3, rolling_resistance = 0.3, color = color}
      else
        local sx, sy, sz = 0.6 + math.random() * 0.5, 0.4 + math.random() * 0.4, 0.6 + math.random() * 0.5
        radius = math.sqrt(sx * sx + sy * sy + sz * sz) / 2
        size = {sx, sy, sz}
        b = world.box{size = {sx, sy, sz}, position = {x, y, z}, rotation = {math.random(), math.random(), 0},
                      density = 500, friction = 0.7, restitution = 0.1, color = color}
      end
      bodies[#bodies + 1] = {body = b, radius = radius, size = size}
    end
  end

  function scenario.on_finish(ctx)
    if #bodies == 0 then return end
    local fastest, resting, below, above, sunk = 0, 0, math.huge, -math.huge, -math.huge
    for _, e in ipairs(bodies) do
      local p = e.body:position()
      local g = ground(p.x, p.z) or -math.huge
      fastest = math.max(fastest, e.body:speed())
      if e.body:speed() < 0.1 then resting = resting + 1 end
      below = math.min(below, p.y - g)               -- centre above the terrain, m
      above = math.max(above, p.y - g - e.radius)    -- gap beyond the bounding radius, m
      local depth = sink_depth(e) or math.huge  -- no terrain under it: it fell off
      if depth > 0.02 then print(string.format("sunk %.3f m: %s at %.2f %.2f %.2f", depth, e.size and "box" or "sphere", p.x, p.y, p.z)) end
      sunk = math.max(sunk, depth)
    end
    -- Most bodies have stopped; a ball on a slope steeper than its rolling
    -- resistance allows (tan > ~C_rr) rightly keeps rolling, but none races.
    expect("bodies at rest (fraction slower than 0.1 m/s)", resting / #bodies, {min = 0.9})
    expect("no body still racing downhill", fastest, {max = 3})
    expect("no body fell through the terrain", below, {min = 0})
    expect("no body sank into the terrain (deepest point inside it, m)", sunk, {max = 0.02})
    expect("every body rests on the terrain", above, {max = 0.15})
  end
  return scenario
end

return terrain_drop
