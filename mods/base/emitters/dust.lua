-- Dust kicked up from the ground: brown puffs that billow out, slow down in
-- the air, sink a little and fade. Steady rate for wheels (vehicles drive
-- set_rate from tyre slip); particles.burst("base:dust", n, ...) for a landing.
return {
  description = "brown dust puffs kicked up from the ground",
  rate = 30,                          -- particles/s (set_rate changes it)
  lifetime = {1.2, 2.4},              -- s
  max_count = 600,
  shape = "sphere", radius = 0.25,    -- m
  direction = {0, 1, 0},
  spread = math.rad(70),
  speed = {0.8, 2.2},                 -- m/s
  inherit_velocity = 0.3,
  gravity = 0.15,                     -- x world gravity: fine dust settles slowly
  drag = 2.0,                         -- 1/s: air stops it quickly
  spin = {-0.6, 0.6},                 -- rad/s
  size = {{0, 0.35}, {1, 1.6}},       -- m: puffs grow as they spread
  color = {{0, {0.55, 0.45, 0.32}}, {1, {0.62, 0.55, 0.45}}},
  alpha = {{0, 0}, {0.12, 0.55}, {1, 0}},
  blend = "alpha",
  space = "world",
}
