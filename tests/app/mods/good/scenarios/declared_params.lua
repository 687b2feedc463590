-- A scenario that declares its parameters: a ball dropped from `height`
-- lands after sqrt(2 h / g); --set of an undeclared name is refused before
-- the run, param() without a default returns the declared one.
local ball, landed_at
return {
  duration = 1.5,
  params = {
    height = {default = 5, unit = "m", description = "drop height of the ball's bottom"},
    label = {default = "ball", description = "a name, to show string parameters"},
    bounce = {default = false, description = "a boolean, to show boolean parameters"},
  },
  on_start = function(ctx)
    world.plane{}
    ball = world.sphere{radius = 0.5, position = {0, param("height") + 0.5, 0}, mass = 1, restitution = 0}
  end,
  on_update = function(ctx, dt)
    if not landed_at and ball:position().y < 0.52 then landed_at = ctx.time end
  end,
  on_finish = function(ctx)
    local h = param("height")
    expect("landing time matches sqrt(2 h / g) (s)", landed_at or -1,
           {min = math.sqrt(2 * h / 9.81) - 0.04, max = math.sqrt(2 * h / 9.81) + 0.04})
    expect("label is a string", type(param("label")) == "string")
    expect("bounce is a boolean", type(param("bounce")) == "boolean")
  end,
}
