-- A ball dropped from 10 m is not at 10 m after a second: this must fail.
local ball
return {
  duration = 1,
  on_start = function() ball = world.sphere{radius = 0.5, position = {0, 10, 0}} end,
  on_finish = function() expect("still at 10 m", ball:position().y, {min = 9.9, max = 10.1}) end,
}
