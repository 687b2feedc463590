-- Static models: collision = "mesh" (the default) collides with the model's
-- own triangles, "box" with one static box around its bounds, "none" not at
-- all. Checked through the bodies and balls rolled at them.
local M = "base:assets/models/"
local rock, none, wall, tree, under, trunk
return {duration = 1, on_start = function()
  world.plane{}
  -- The barrier model is 2 x 0.8 x 0.4 m with its base at y = 0.
  wall = world.add_static_model(M .. "barrier.obj", {position = {0, 0, 5}, scale = 2,
                                                     rotation = {0, math.pi / 2, 0}, collision = "box"})
  none = world.add_static_model(M .. "tree.obj", {position = {4, 0, 0}, collision = "none"})
  -- A ball rolling into the wall stops there.
  rock = world.sphere{radius = 0.3, position = {0, 0.3, 0}, velocity = {0, 0, 6}, friction = 0.0}
  -- The tree model: a trunk 0.18 m in radius at the ground, its crown from
  -- 1.2 m up and 1.3 m wide. With mesh collision a ball rolling 0.8 m beside
  -- the trunk passes under the crown; one rolling at the trunk stops at it.
  tree = world.add_static_model(M .. "tree.obj", {position = {-6, 0, 6}})
  under = world.sphere{radius = 0.3, position = {-6 + 0.8, 0.3, 3}, velocity = {0, 0, 6}, friction = 0.0}
  trunk = world.sphere{radius = 0.3, position = {-6, 0.3, 3}, velocity = {0, 0, 6}, friction = 0.0}
end, on_finish = function()
  expect("no body for collision = none", none == nil)
  local p = wall:position()
  expect("wall box centre height (0.8 m scaled by 2, halved)", p.y, {min = 0.799, max = 0.801})
  expect("ball stopped by the wall", rock:position().z, {max = 5 - 0.4 + 0.05})
  expect("mesh body sits at the model's origin", tree:position().z, {min = 5.999, max = 6.001})
  expect("ball beside the trunk rolled on under the crown (m)", under:position().z, {min = 8})
  -- 12-sided trunk of radius 0.169 m at 0.3 m up: its faces are 0.163 m from the axis.
  expect("ball at the trunk stopped at the bark (m)", trunk:position().z, {min = 6 - 0.17 - 0.3 - 0.02, max = 6 - 0.16 - 0.3 + 0.01})
  expect("bodies: plane, wall, tree, three balls", world.body_count(), {min = 6, max = 6})
end}
