-- A puff emitter on a falling ball: the report lists the particle system.
return {
  duration = 2,
  on_start = function()
    world.plane{}
    local ball = world.sphere{radius = 0.3, position = {0, 2, 0}}
    particles.spawn("good:puff", {body = ball})
  end,
}
