-- A ball dropped from `height` onto the ground: it should land after
-- sqrt(2 h / g). Short and cheap, for the sweep tests: heights above
-- 4.9 m fail the "lands within 1 s" expectation, explode = true raises a
-- script error, so a sweep sees each outcome.
local ball, landed_at
return {
  duration = 1.5,
  params = {
    height = {default = 2, unit = "m", description = "drop height of the ball's bottom"},
    explode = {default = false, description = "raise a script error in on_start (a failing run)"},
  },
  on_start = function(ctx)
    if param("explode") then error("asked to fail with explode = true") end
    world.plane{}
    -- The seed moves the ball sideways, so each seed is a different run.
    local x = random.new(ctx.seed):float(-1, 1)
    ball = world.sphere{radius = 0.25, position = {x, param("height") + 0.25, 0}, mass = 1, restitution = 0}
  end,
  on_update = function(ctx, dt)
    if not landed_at and ball:position().y < 0.26 then landed_at = ctx.time end
  end,
  on_finish = function(ctx)
    local h = param("height")
    expect("landing time matches sqrt(2 h / g) (s)", landed_at or 99,
           {min = math.sqrt(2 * h / 9.81) - 0.05, max = math.sqrt(2 * h / 9.81) + 0.05})
    expect("lands within 1 s", landed_at or 99, {max = 1})
  end,
}
