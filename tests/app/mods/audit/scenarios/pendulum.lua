-- A 1 kg box on a ball joint 1 m below a world anchor, released at 60
-- degrees: an ideal joint does no work, so its energy can only fall.
return {
  title = "Jointed pendulum",
  duration = 6,
  joint_solver = "impulse",
  on_start = function(ctx)
    local a = math.rad(60)
    local bob = world.box{size = {0.1, 0.1, 0.1}, position = {math.sin(a), 3 - math.cos(a), 0}, mass = 1}
    world.joint{type = "ball", a = bob, anchor = {0, 3, 0}}
  end,
}
