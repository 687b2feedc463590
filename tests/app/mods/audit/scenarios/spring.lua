-- A 1 kg ball on a world.spring (k = 40 N/m: 1.0 Hz) to a fixed anchor,
-- no gravity, no damping, pulled 0.5 m from rest and let go. Nothing
-- removes or adds energy: 1/2 k x^2 = 5 J goes back and forth between the
-- spring and the ball.
return {
  title = "Ball on a spring",
  duration = 10,
  on_start = function(ctx)
    world.set_gravity{0, 0, 0}
    local ball = world.sphere{radius = 0.1, position = {0.5, 2, 0}, mass = 1}
    world.spring{a = ball, anchor = {0, 2, 0}, stiffness = 40, rest_length = 0}
  end,
}
