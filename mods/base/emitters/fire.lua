-- Flames: short-lived additive particles, white-yellow at the base turning
-- orange then dark red as they rise and shrink.
return {
  description = "flames: additive, yellow to red, rising and shrinking",
  rate = 90,                          -- particles/s
  lifetime = {0.5, 1.0},              -- s
  max_count = 200,
  shape = "cone", radius = 0.45,      -- m
  cone_angle = math.rad(10),
  direction = {0, 1, 0},
  spread = math.rad(6),
  speed = {0.6, 1.4},                 -- m/s
  gravity = 0,
  acceleration = {0, 2.0, 0},         -- m/s^2: hot gas rises faster and faster
  drag = 1.0,                         -- 1/s
  spin = {-2, 2},                     -- rad/s
  size = {{0, 0.6}, {0.5, 0.5}, {1, 0.12}},   -- m
  color = {{0, {0.95, 0.62, 0.22}}, {0.3, {0.9, 0.35, 0.06}}, {1, {0.35, 0.05, 0.02}}},
  alpha = {{0, 0.0}, {0.08, 0.4}, {1, 0}},
  blend = "additive",
  space = "world",
}
