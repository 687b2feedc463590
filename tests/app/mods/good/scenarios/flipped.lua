-- A hatchback dropped in a roll onto flat ground, with the player at the
-- wheel (drive.player): it comes to rest on its roof, where the reset key
-- (R: drive.upright) must put it back on its wheels. For the play tests
-- (tests/app/play_events_test.cpp).
local drive = require "tumble.drive"

local car, player

return {
  title = "A car that lands on its roof",
  duration = 10,
  on_start = function(ctx)
    world.plane{friction = 0.8}
    car = vehicle.spawn("base:hatchback", {position = {0, 0, 0}, heading = 0})
    local p = car:position()
    car:body():set_position({p.x, p.y + param("drop", 3), p.z})
    -- About the forward axis: half a turn during the fall.
    car:body():set_angular_velocity({0, 0, param("roll", 4)})
    player = drive.player(car)
    drive.show(car)
  end,
  on_update = function(ctx, dt)
    player:update(dt)
  end,
}
