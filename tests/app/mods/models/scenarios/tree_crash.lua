-- A car at full throttle into the base tree model (mesh collision, the
-- default): the chassis box meets the 12-sided trunk's triangles and stops
-- there, upright. With collision = "box" the air under the crown is solid
-- and the car stops 3.3 m short of the axis instead (measured), which the
-- window below refuses.
local car, tree_z, min_up, peak
return {duration = 8, on_start = function()
  world.plane{}
  tree_z = 40
  world.add_static_model("base:assets/models/tree.obj", {position = {0, 0, tree_z}})
  car = vehicle.spawn("base:hatchback", {position = {0, 0, 0}, heading = 0})
  min_up, peak = 1, 0
end, on_update = function()
  car:set_controls{throttle = 1}
  min_up = math.min(min_up, car:body():up().y)
  peak = math.max(peak, car:telemetry().speed)
end, on_finish = function()
  -- The hatchback's chassis box reaches 2.1 m ahead of its centre of mass:
  -- stopped at the trunk (radius 0.17 m), its centre stays well short of it.
  expect("reached speed before the tree (m/s)", peak, {min = 10})
  expect("stopped at the trunk (m before the tree's axis)", tree_z - car:position().z, {min = 1.6, max = 2.4})
  expect("stayed upright", min_up, {min = 0.5})
end}
