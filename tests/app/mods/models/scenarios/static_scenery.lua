-- Static models get static box bodies around their (scaled, rotated) bounds;
-- collision = "none" makes none. Checked through the bodies' sizes.
local rock, none, wall
return {duration = 0.5, on_start = function()
  world.plane{}
  -- The barrier model is 2 x 0.8 x 0.4 m with its base at y = 0.
  wall = world.add_static_model("base:assets/models/barrier.obj", {position = {0, 0, 5}, scale = 2,
                                                                   rotation = {0, math.pi / 2, 0}})
  none = world.add_static_model("base:assets/models/tree.obj", {position = {4, 0, 0}, collision = "none"})
  -- A ball rolling into the wall stops there.
  rock = world.sphere{radius = 0.3, position = {0, 0.3, 0}, velocity = {0, 0, 6}, friction = 0.0}
end, on_finish = function()
  expect("no body for collision = none", none == nil)
  local p = wall:position()
  expect("wall box centre height (0.8 m scaled by 2, halved)", p.y, {min = 0.799, max = 0.801})
  expect("ball stopped by the wall", rock:position().z, {max = 5 - 0.4 + 0.05})
  expect("static bodies", world.body_count(), {min = 3, max = 3})
end}
