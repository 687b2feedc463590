-- Static models: collision = "mesh" (the default) collides with the model's
-- own triangles, "box" with one static box around its bounds, "none" not at
-- all. Checked through the bodies and balls rolled at them.
local M = "base:assets/models/"
local rock, none, wall, tree, under, trunk, post
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
  -- A barrier turned a quarter round (its 2 m length along z, 0.4 m
  -- thickness along x) and stretched to 1.6 m tall: rays meet its mesh
  -- where the placed box's faces are.
  post = world.add_static_model(M .. "barrier.obj", {position = {6, 0, -4}, rotation = {0, math.pi / 2, 0},
                                                     scale = {1, 2, 1}})
end, on_finish = function()
  expect("no body for collision = none", none == nil)
  local p = wall:position()
  expect("wall box centre height (0.8 m scaled by 2, halved)", p.y, {min = 0.799, max = 0.801})
  expect("ball stopped by the wall", rock:position().z, {max = 5 - 0.4 + 0.05})
  expect("mesh body sits at the model's origin", tree:position().z, {min = 5.999, max = 6.001})
  expect("ball beside the trunk rolled on under the crown (m)", under:position().z, {min = 8})
  -- 12-sided trunk of radius 0.169 m at 0.3 m up: its faces are 0.163 m from the axis.
  expect("ball at the trunk stopped at the bark (m)", trunk:position().z, {min = 6 - 0.17 - 0.3 - 0.02, max = 6 - 0.16 - 0.3 + 0.01})
  local hit = world.raycast({10, 1.5, -4.6}, {-1, 0, 0})
  expect("ray meets the turned barrier's face at x = 6.2 (m)", hit and hit.point.x or 0, {min = 6.199, max = 6.201})
  expect("ray hits the barrier's mesh body", hit ~= nil and hit.body == post)
  expect("its normal faces the ray", hit and hit.normal.x or 0, {min = 0.9999})
  local over = world.raycast({10, 1.65, -4.6}, {-1, 0, 0}, 20)
  expect("a ray over its 1.6 m top misses it", over == nil or over.body ~= post)
  local down = world.raycast({6.1, 5, -3.5}, {0, -1, 0})
  expect("a ray down meets its top at 1.6 m", down and down.point.y or 0, {min = 1.599, max = 1.601})
  expect("bodies: plane, wall, tree, barrier, three balls", world.body_count(), {min = 7, max = 7})
end}
