-- A car re-tuned while running (Vehicle:tune in on_update): a snapshot
-- holds the vehicles' running state, not their definitions, so loading one
-- saved after the tune is refused, naming the vehicle and Vehicle:tune
-- (tests/app/scene_state_test.cpp).
local car

return {
  title = "A car re-tuned after on_start",
  duration = 2,
  on_start = function(ctx)
    world.plane{}
    car = vehicle.spawn("base:hatchback", {position = {0, 0, 0}})
  end,
  on_update = function(ctx, dt)
    if ctx.step == 30 then car:tune{engine = {max_rpm = 7000}} end
  end,
}
