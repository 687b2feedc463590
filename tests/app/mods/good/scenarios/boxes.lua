-- Two bright red boxes resting on a plane, in front of the default camera.
return {
  duration = 0.5,
  on_start = function()
    world.plane{color = {0.5, 0.5, 0.5}}
    world.box{size = {2, 2, 2}, position = {-1.5, 1, 0}, color = {1, 0, 0}}
    world.box{size = {2, 2, 2}, position = {1.5, 1, 0}, color = {1, 0, 0}}
  end,
}
