-- A centre of mass moved off the shape's centroid (center_of_mass = {...}).
-- Two capsules (radius 0.3 m, core 1 m) stand tilted 60 degrees on the
-- floor. The uniform one has its centre of mass at its middle, 0.43 m to
-- the side of the round bottom it stands on, and falls over. The weighted
-- one carries its centre of mass 0.2 m below the centre of its bottom cap
-- (a weeble): whatever the tilt, the floor's push passes on the upright
-- side of it, so it rocks back and, with some angular damping, comes to
-- rest upright. Then body:position() reports the moved centre, and bad
-- definitions are refused with the field named.
local uniform, weighted

local function tilt_cos(b) return b:up().y end

return {
  title = "Centre of mass: a weeble stands up, a uniform capsule falls",
  duration = 8,
  on_start = function(ctx)
    world.plane{friction = 1}
    local tilt = math.rad(60)
    -- The bottom cap's centre 0.3 m above the floor; the capsule's middle
    -- 0.5 m from it along the tilted axis.
    local function stand(x, extra)
      local def = {radius = 0.3, length = 1, rotation = {0, 0, tilt}, friction = 1, angular_damping = 2, sleep = false,
                   position = {x - 0.5 * math.sin(tilt), 0.3 + 0.5 * math.cos(tilt), 0}}
      for k, v in pairs(extra or {}) do def[k] = v end
      return world.capsule(def)
    end
    uniform = stand(-2)
    weighted = stand(2, {center_of_mass = {0, -0.7, 0}})
    expect("both start tilted 60 degrees (cos)", tilt_cos(weighted), {min = 0.49, max = 0.51})

    -- body:position() is the centre of mass: the definition's position is the shape's.
    local box = world.box{size = {2, 1, 1}, position = {10, 5, 0}, center_of_mass = {0.8, 0, 0}, type = "dynamic"}
    local p = box:position()
    expect("position() reports the moved centre (m off)", math.abs(p.x - 10.8) + math.abs(p.y - 5), {max = 1e-5})
    box:remove()
    -- A hull's center_of_mass is in the frame its points are given in.
    local hull = world.hull{points = {{0, 0, 0}, {2, 0, 0}, {0, 0, 2}, {2, 0, 2}, {0, 2, 0}, {2, 2, 0}, {0, 2, 2}, {2, 2, 2}},
                            position = {20, 5, 0}, center_of_mass = {0.5, 0.5, 0.5}}
    p = hull:position()
    expect("a hull's centre in its points' frame (m off)", math.abs(p.x - 20.5) + math.abs(p.y - 5.5) + math.abs(p.z - 0.5), {max = 1e-5})
    hull:remove()

    local refused = 0
    local bad = {
      {world.box, {size = {1, 1, 1}, center_of_mass = {0.6, 0, 0}}, "outside"},
      {world.sphere, {radius = 1, center_of_mass = {0 / 0, 0, 0}}, "center_of_mass"},
      {world.box, {type = "static", center_of_mass = {0, 0, 0}}, "dynamic"},
      {world.capsule, {radius = 0.2, length = 1, center_of_mass = {0, 1, 0}}, "outside"},
      {world.sphere, {radius = 1, center_of_mass = "low"}, "center_of_mass"},
    }
    for _, case in ipairs(bad) do
      local ok, err = pcall(case[1], case[2])
      if not ok and tostring(err):find("center_of_mass", 1, true) and tostring(err):find(case[3], 1, true) then
        refused = refused + 1
      end
    end
    expect("bad centres refused with the field and the reason named (of 5)", refused, {min = 5})
  end,
  on_finish = function(ctx)
    expect("the weeble stands back up (cos of its tilt)", tilt_cos(weighted), {min = math.cos(math.rad(3))})
    expect("the uniform capsule lies on the floor (|cos of its tilt|)", math.abs(tilt_cos(uniform)), {max = 0.05})
    local p = weighted:position()
    -- Rolling back up moves it sideways by about the cap's radius x 60 degrees.
    expect("the weeble stays where it stood (m from x = 2)", math.abs(p.x - 2), {max = 0.5})
  end,
}
