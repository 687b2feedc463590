-- Many placements of a few model files (the drive scenario's scenery, in
-- bulk): `trees` trees and `rocks` rocks on a grid 4 m apart, each at one of
-- `sizes` scales. Placements of the same file at the same scale share one
-- collision shape (tests/app/scene_models_test.cpp; the run report's
-- mesh_collision.shapes_built). A ball dropped on the first rock lands on it.
local M = "base:assets/models/"
local ball
return {duration = 1, on_start = function()
  world.plane{}
  local trees, rocks, sizes = param("trees", 20), param("rocks", 20), param("sizes", 2)
  local n = 0
  local function place(file, i)
    n = n + 1
    local x, z = (n % 20) * 4, (n // 20) * 4
    return world.add_static_model(M .. file, {position = {x, 0, z}, rotation = {0, 0.3 * n, 0},
                                              scale = 1 + 0.25 * ((i - 1) % sizes)})
  end
  for i = 1, trees do place("tree.obj", i) end
  local first
  for i = 1, rocks do
    local body = place("rock.obj", i)
    first = first or body
  end
  if first then
    local p = first:position()
    ball = world.sphere{radius = 0.2, position = {p.x, 3, p.z}}
  end
end, on_finish = function()
  if ball then expect("the ball rests on the first rock, not the ground (m)", ball:position().y, {min = 0.5}) end
end}
