-- A car drives over a ramp model with mesh collision (the default): its
-- wheel rays hit the ramp's triangles, so the chassis climbs the 0.6 m ramp
-- and comes down the other side. (A box around the ramp would be a 0.6 m
-- step that stops the car.)
local car, rest, top, min_up
return {duration = 8, on_start = function()
  world.plane{}
  world.add_static_model("assets/ramp.obj", {position = {0, 0, 10}})
  car = vehicle.spawn("base:hatchback", {position = {0, 0, 0}, heading = 0})
  top, min_up = -math.huge, 1
end, on_update = function(ctx, dt)
  car:set_controls{throttle = 0.5}
  local p = car:position()
  if ctx.time < 0.5 then rest = p.y end
  top = math.max(top, p.y)
  min_up = math.min(min_up, car:body():up().y)
end, on_finish = function()
  expect("drove past the ramp (m)", car:position().z, {min = 22})
  expect("chassis rose by the ramp's height (m)", top - rest, {min = 0.45, max = 0.8})
  expect("back down on the ground (m)", car:position().y - rest, {min = -0.05, max = 0.05})
  expect("stayed upright", min_up, {min = 0.8})
end}
