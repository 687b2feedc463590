-- A ball in zero gravity pushed along x at a tunable speed: after the run
-- it has travelled speed * time.
local ball
return {
  duration = 2,
  on_start = function(ctx)
    world.set_gravity{0, 0, 0}
    ball = world.sphere{radius = 0.5, position = {0, 5, 0}, mass = 1}
  end,
  on_update = function(ctx, dt)
    ball:set_velocity{tune.number("speed", 1, {min = 0, max = 10, unit = "m/s"}), 0, 0}
  end,
  on_finish = function(ctx)
    expect("distance", ball:position().x, {min = 0})
  end,
}
