-- Smoke from a fire or an exhaust: grey puffs that rise, widen and thin out.
return {
  description = "grey smoke that rises, widens and thins out",
  rate = 18,                          -- particles/s
  lifetime = {3.0, 5.0},              -- s
  max_count = 200,
  shape = "cone", radius = 0.3,       -- m
  cone_angle = math.rad(12),
  direction = {0, 1, 0},
  spread = math.rad(8),
  speed = {0.6, 1.1},                 -- m/s
  inherit_velocity = 0.5,
  gravity = 0,
  acceleration = {0.25, 0.35, 0},     -- m/s^2: buoyancy, and a light breeze along +x
  drag = 0.4,                         -- 1/s
  spin = {-0.4, 0.4},                 -- rad/s
  size = {{0, 0.5}, {1, 2.8}},        -- m
  color = {{0, {0.32, 0.31, 0.30}}, {1, {0.62, 0.62, 0.64}}},
  alpha = {{0, 0}, {0.1, 0.5}, {0.6, 0.3}, {1, 0}},
  blend = "alpha",
  space = "world",
}
