-- Rain over a 30 m x 30 m area: drops start in a thin slab above the scene
-- and fall at close to their terminal speed. Spawn it some 14 m up.
return {
  description = "rain falling over a 30 m square",
  rate = 1800,                        -- drops/s
  lifetime = {1.0, 1.05},             -- s: from 14 m up they end at the ground (0.1 m below .. 1.6 m above)
  max_count = 2500,
  shape = "box", box_size = {30, 0.5, 30},  -- m
  direction = {0.05, -1, 0},
  spread = math.rad(2),
  speed = {9.5, 10},                  -- m/s, about a drop's terminal speed
  gravity = 1,
  drag = 0.3,                         -- 1/s
  size = 0.035,                       -- m: the streak's width
  stretch = 0.05,                     -- s: drawn as a streak of speed x 0.05 s, about 0.5 m
  color = {0.52, 0.58, 0.70},
  alpha = {{0, 0.55}, {0.9, 0.55}, {1, 0}},
  blend = "alpha",
  space = "world",
}
