-- A car re-tuned while running (Vehicle:tune in on_update): a snapshot
-- holds each vehicle's definition, so a run loaded after the tune drives
-- the tuned car and ends as the run without a split
-- (tests/app/scene_state_test.cpp, SplitRun).
local car

return {
  title = "A car re-tuned after on_start",
  duration = 2,
  on_start = function(ctx)
    world.plane{}
    car = vehicle.spawn("base:hatchback", {position = {0, 0, 0}})
    car:set_controls{throttle = 1, gear = 1}
    ctx.state.chassis = car:body()
  end,
  on_update = function(ctx, dt)
    if ctx.step == 30 then car:tune{engine = {max_rpm = 6300}, tyre = {rolling_resistance = 0.03}} end
  end,
  on_finish = function(ctx)
    expect("the car drove forward (m)", ctx.state.chassis:position().z, {min = 1})
  end,
}
