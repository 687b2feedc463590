-- A 2 kg block at rest on a static ramp at 20 degrees with friction 0.8
-- (tan 20 = 0.36 < 0.8: it stays). Gravity and the ramp's contact
-- impulses cancel at every step; the block's momentum stays 0.
return {
  title = "Block resting on a static ramp",
  duration = 10,
  on_start = function(ctx)
    local a = math.rad(20)
    local q = {w = math.cos(a / 2), x = 0, y = 0, z = math.sin(a / 2)}
    world.box{type = "static", size = {6, 0.4, 2}, position = {0, 0, 0}, orientation = q, friction = 0.8}
    -- On the ramp's top face, 0.2 m + 0.25 m along its normal from its centre.
    local n = {-math.sin(a), math.cos(a)}
    world.box{size = {0.5, 0.5, 0.5}, position = {0.45 * n[1], 0.45 * n[2], 0}, orientation = q, mass = 2,
              friction = 0.8}
  end,
}
