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
  size = {{0, 0.09}, {1, 0.04}},      -- m
  color = {{0, {3.0, 2.4, 1.2}}, {0.5, {2.0, 0.9, 0.2}}, {1, {0.9, 0.25, 0.05}}},
  alpha = {{0, 1}, {1, 0}},
  blend = "additive",
  space = "world",
}
