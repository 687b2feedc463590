-- The base cars drawn with drive.show, standing on flat ground with the
-- brakes on (tests/vehicle/show_test.cpp compares where the chassis models
-- are drawn with where the physics cars stand).
local drive = require("tumble.drive")

local cars = {}

return {
  title = "drive.show: the three base cars at rest",
  duration = 3,
  on_start = function(ctx)
    world.plane{}
    for i, name in ipairs({"hatchback", "truck", "buggy"}) do
      cars[i] = vehicle.spawn("base:" .. name, {position = {(i - 2) * 15, 0, 0}})
      drive.show(cars[i])
    end
  end,
  on_update = function(ctx, dt)
    for _, car in ipairs(cars) do car:set_controls{throttle = 0, brake = 1} end
  end,
}
