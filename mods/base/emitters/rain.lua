-- Rain over a 30 m x 30 m area: drops start in a thin slab above the scene
-- and fall at close to their terminal speed. Spawn it some 14 m up.
return {
  description = "rain falling over a 30 m square",
  rate = 1800,                        -- drops/s
  lifetime = {1.0, 1.1},              -- s: long enough to reach the ground from 14 m
  max_count = 2500,
  shape = "box", box_size = {30, 0.5, 30},  -- m
  direction = {0.05, -1, 0},
  spread = math.rad(2),
  speed = {9, 10},                    -- m/s, about a drop's terminal speed
  gravity = 1,
  drag = 0.3,                         -- 1/s
  size = 0.06,                        -- m
  color = {0.75, 0.82, 0.95},
  alpha = {{0, 0.7}, {0.9, 0.7}, {1, 0}},
  blend = "alpha",
  space = "world",
}
