-- Exhaust: thin blue-grey puffs from a car's tailpipe. The vehicle effects
-- (scripts/tumble/drive.lua) attach it to the chassis and set its rate from
-- throttle and rpm every step; its direction is in the body's frame, so the
-- puffs leave backwards (-Z is the back of the shipped cars).
return {
  description = "thin blue-grey exhaust puffs, blown backwards and up",
  rate = 4,                            -- particles/s at idle (drive.lua overrides it)
  lifetime = {0.8, 1.6},               -- s
  max_count = 120,
  shape = "point",
  direction = {0, 0.15, -1},
  spread = math.rad(12),
  speed = {1.5, 2.5},                  -- m/s
  inherit_velocity = 0.8,
  gravity = 0,
  acceleration = {0, 0.4, 0},          -- m/s^2: warm gas rises
  drag = 1.5,                          -- 1/s
  spin = {-1, 1},                      -- rad/s
  size = {{0, 0.08}, {1, 0.7}},        -- m
  color = {{0, {0.35, 0.36, 0.40}}, {1, {0.6, 0.6, 0.62}}},
  alpha = {{0, 0}, {0.1, 0.35}, {1, 0}},
  blend = "alpha",
  space = "world",
}
