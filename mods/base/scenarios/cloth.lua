-- Cloth: a flag in the wind and a sheet dropped on a table, as mass-spring
-- grids (structural, shear and bend springs) stepped with implicit Euler
-- (deformable.cloth).
--
--   flag: pinned along a pole, wind `wind` m/s along +z (default 8). Each
--     triangle feels pressure drag 1/2 rho C_d A (n.u)|n.u| n, u the wind
--     relative to the cloth. Expectation: blown downwind (its mean z > 0.3
--     of its length) and never non-finite.
--   sheet: dropped flat onto a static box and the ground, no wind. Backward
--     Euler only removes energy, so its energy never grows from one step to
--     the next (until it touches: a collision moves particles out, which
--     may lift them by up to their overlap); no particle ever below the
--     ground (y - radius >= -1 mm).
--   stiff: a small sheet with structural springs of k/m = 1e6 pinned at two
--     corners, one implicit step per 1/60 s. Expectation: finite, no CG
--     failure, and its springs within 1 % of their rest lengths.
--
--   tumble run base:cloth
--   tumble play base:cloth
--   tumble run base:cloth --set wind=15

local scenario = {
  title = "Cloth: a flag in the wind, a sheet on a table",
  duration = 6,
}

local flag, sheet, stiff
local WIDTH = 1.8          -- m, flag length along the wind
local lastEnergy, worstGain = nil, 0
local touched = false
local lowest = math.huge

function scenario.on_start(ctx)
  local wind = param("wind", 8)
  world.plane{color = {0.55, 0.57, 0.6}}
  world.box{type = "static", size = {0.1, 4, 0.1}, position = {0, 2, 0}, color = {0.4, 0.3, 0.2}}
  world.box{type = "static", size = {1, 0.5, 1}, position = {3, 0.25, 0}, color = {0.45, 0.5, 0.6}}
  -- The flag's first row runs down the pole; its columns run along +z.
  flag = deformable.cloth{origin = {0, 4, 0.06}, u = {0, -1.2, 0}, v = {0, 0, WIDTH}, columns = 10, rows = 14,
                          mass = 0.3, stiffness = 5e3, pins = "top", wind = {0, 0, wind}, color = {0.9, 0.2, 0.2}}
  sheet = deformable.cloth{origin = {2, 1.2, -1}, u = {2, 0, 0}, v = {0, 0, 2}, columns = 14, rows = 14,
                           mass = 0.4, stiffness = 2e3, pins = "none", color = {0.4, 0.7, 1.0}}
  -- 36 particles of 1/360 kg: k/m = 1e6 needs k = 2778 N/m.
  stiff = deformable.cloth{origin = {-3, 3, -0.5}, u = {1, 0, 0}, v = {0, 0, 1}, columns = 6, rows = 6,
                           mass = 0.1, stiffness = 1e6 * 0.1 / 36, pins = "corners", substeps = 1,
                           color = {0.95, 0.8, 0.3}}
  lastEnergy = sheet:energy()
end

function scenario.on_update(ctx, dt)
  local e = sheet:energy()
  local low = sheet:lowest()
  touched = touched or low < 0.6  -- near the table top: may touch it
  if not touched then worstGain = math.max(worstGain, e - lastEnergy) end
  lastEnergy = e
  lowest = math.min(lowest, low)
end

function scenario.on_finish(ctx)
  local z = 0
  for i = 1, flag:count() do z = z + flag:position(i).z end
  z = z / flag:count()
  expect("flag mean z / its length (downwind)", z / WIDTH, {min = 0.3})
  expect("flag stayed finite", flag:stats().nan_events == 0)
  expect("sheet energy gain per step before contact (J)", worstGain, {max = 1e-9})
  expect("sheet lowest point (m)", lowest, {min = -1e-3})
  -- The sheet fell from 1.2 m onto the table (top at 0.5 m): no particle
  -- is higher than the table top plus 5 cm (m).
  local top = -math.huge
  for i = 1, sheet:count() do top = math.max(top, sheet:position(i).y) end
  expect("sheet lies on the table (highest point, m)", top, {max = 0.55})
  local len, rest = stiff:length()
  expect("stiff cloth (k/m = 1e6, one step per frame) stretch / rest", len / rest - 1, {max = 0.01})
  expect("stiff cloth finite, CG converged", stiff:stats().nan_events == 0 and stiff:stats().cg_failures == 0)
end

return scenario
