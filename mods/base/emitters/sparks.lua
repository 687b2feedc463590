-- Sparks from an impact: one burst of bright additive specks that fly out,
-- fall under gravity and cool from white-yellow to orange. The emitter stops
-- by itself (duration) and is gone when its last spark dies.
return {
  description = "a burst of bright sparks that fall and cool",
  rate = 0,
  bursts = {{time = 0, count = 40}},
  duration = 0.05,                    -- s
  lifetime = {0.4, 0.9},              -- s
  max_count = 400,
  shape = "point",
  direction = {0, 1, 0},
  spread = math.rad(75),
  speed = {3, 7},                     -- m/s
  gravity = 1,
  drag = 0.8,                         -- 1/s
  size = {{0, 0.07}, {1, 0.035}},     -- m: width
  stretch = 0.03,                     -- s: short streaks along the flight
  color = {{0, {1.0, 0.9, 0.5}}, {0.4, {1.0, 0.55, 0.15}}, {1, {0.8, 0.2, 0.05}}},
  alpha = {{0, 1}, {1, 0}},
  blend = "additive",
  space = "world",
}
