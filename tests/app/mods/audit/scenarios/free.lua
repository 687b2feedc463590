-- Two 1 kg balls in empty space, no gravity, 10 m apart and moving apart
-- at 1 m/s each: momentum 0 and energy 1 J, for ever.
return {
  title = "Two free balls",
  duration = 2,
  on_start = function(ctx)
    world.set_gravity{0, 0, 0}
    world.sphere{radius = 0.1, position = {-5, 2, 0}, velocity = {-1, 0, 0}, mass = 1}
    world.sphere{radius = 0.1, position = {5, 2, 0}, velocity = {1, 0, 0}, mass = 1}
  end,
}
