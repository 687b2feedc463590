-- Ropes: mass-spring chains stepped with implicit Euler (deformable.rope).
--
--   orange, hanging: pinned at the top, starting straight down. At rest
--     spring j (counted from the pin) carries the N - j particles below it,
--     so the rope stretches by m g / k * N (N + 1) / 2 in total (N springs,
--     N + 1 particles of mass m). Expectation: the measured stretch within
--     2 % of that once it has settled.
--   blue, swinging: pinned at one end, released horizontal. Backward Euler
--     only removes energy, so kinetic + potential + spring energy must never
--     grow from one step to the next.
--   red, stiff: k / m = 1e6 with ONE implicit step per 1/60 s (omega h =
--     16.7, where every explicit method explodes). Expectation: no
--     non-finite state, and the rope stays within 1 mm of its rest length
--     plus its static stretch.
--   green, dropped: falls across a static box onto the ground. Expectation:
--     no particle ever below the ground (y - radius >= -1 mm).
--
--   tumble run base:rope
--   tumble play base:rope

local scenario = {
  title = "Ropes: implicit mass-spring chains",
  duration = 8,
}

local G = 9.81
local hanging, swinging, stiff, dropped
local N = 20               -- segments of the hanging rope
local MASS = 2.1           -- kg: 0.1 kg per particle
local K = 2000             -- N/m per segment
local lastEnergy, worstGain = nil, 0
local lowest = math.huge

function scenario.on_start(ctx)
  local gv = world.gravity()
  G = math.sqrt(gv.x ^ 2 + gv.y ^ 2 + gv.z ^ 2)
  world.plane{color = {0.55, 0.57, 0.6}}
  world.box{type = "static", size = {1, 1, 1}, position = {3, 0.5, 2}, color = {0.45, 0.5, 0.6}}
  -- A gallows: a post behind the hanging rope and an arm over its pin.
  world.box{type = "static", size = {0.2, 6.2, 0.2}, position = {-2, 3.1, -0.4}, color = {0.4, 0.3, 0.2}}
  world.box{type = "static", size = {0.15, 0.15, 0.9}, position = {-2, 6.12, -0.05}, color = {0.4, 0.3, 0.2}}
  hanging = deformable.rope{from = {-2, 6, 0.3}, to = {-2, 4, 0.3}, segments = N, mass = MASS, stiffness = K,
                            bend = 0, damping = 5, air_drag = 0.2, color = {0.95, 0.6, 0.2}}
  swinging = deformable.rope{from = {-1.8, 5.5, -0.5}, to = {1.2, 5.5, -0.5}, segments = 30, mass = 0.6,
                             stiffness = 5e3, color = {0.3, 0.6, 1.0}}
  stiff = deformable.rope{from = {0, 6, 1}, to = {2.5, 6, 1}, segments = 10, mass = 1.1, stiffness = 1e5,
                          damping = 0, air_drag = 0, substeps = 1, color = {0.9, 0.25, 0.2}}
  dropped = deformable.rope{from = {1.5, 2, 2}, to = {4.5, 2, 2}, segments = 40, mass = 0.8, stiffness = 1e4,
                            pin_start = false, color = {0.3, 0.8, 0.35}}
  lastEnergy = swinging:energy()
end

function scenario.on_update(ctx, dt)
  local e = swinging:energy()
  worstGain = math.max(worstGain, e - lastEnergy)
  lastEnergy = e
  lowest = math.min(lowest, dropped:lowest())
  local len, rest = hanging:length()
  hud_text(string.format("hanging rope stretch %.4f m (theory %.4f m)", len - rest,
                         MASS / (N + 1) * G / K * N * (N + 1) / 2))
end

function scenario.on_finish(ctx)
  local m = MASS / (N + 1)
  local theory = m * G / K * N * (N + 1) / 2
  local len, rest = hanging:length()
  expect("hanging stretch / static equilibrium", (len - rest) / theory, {min = 0.98, max = 1.02})
  expect("swinging rope energy gain per step (J)", worstGain, {max = 1e-9})
  local slen, srest = stiff:length()
  local sag = 1.1 / 11 * G / 1e5 * 10 * 11 / 2
  expect("stiff rope (k/m = 1e6, one step per frame) stretch (m)", slen - srest, {max = sag + 1e-3})
  expect("stiff rope stayed finite", stiff:stats().nan_events == 0)
  expect("dropped rope lowest point (m)", lowest, {min = -1e-3})
end

return scenario
