-- A car (--set car=MOD:NAME, the hatchback by default) drawn as a player
-- sees it (drive.show: its display mesh on the chassis), rolling forward on
-- a plane, for the look tests (tests/app/look_car_test.cpp): its wheels
-- show below the body and turn with the simulated wheels.
local drive = require "tumble.drive"
local car
return {
  duration = 2,
  on_start = function()
    environment.set{sun = {0.5, 0.8, 0.3}, fog = false, clouds = 0}
    world.plane{color = {0.5, 0.5, 0.5}}
    car = vehicle.spawn(param("car", "base:hatchback"), {position = {0, 0, 0}, heading = 0})
    drive.show(car)
  end,
  on_update = function()
    car:set_controls{throttle = param("throttle", 0.6), steer = param("steer", 0)}
  end,
}
