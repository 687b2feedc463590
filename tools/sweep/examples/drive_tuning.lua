-- A designer's sweep: the base car's tyre grip against its spring rate on
-- the drive scenario's hills, three seeds each (the rocks move with the
-- seed). 5 x 4 x 3 = 60 runs of 20 s.
--   tools/tumble sweep tools/sweep/examples/drive_tuning.lua --run
--   tools/tumble sweep collect sweep-drive_tuning
return {
  name = "drive_tuning",
  scenarios = {"base:drive"},
  seconds = 20,
  grid = {grip = {0.6, 0.8, 1, 1.2, 1.4}, spring_rate = {0.75, 1, 1.5, 2}},
  set = {autopilot = 1},  -- headless: the autopilot drives (the player drives by default)
  seeds = {1, 2, 3},
  collect = {"wall_seconds.total", "error.energy_rel_drift_max", "error.penetration_max_m",
             "expectations.distance driven (m)", "expectations.stayed upright (lowest chassis up.y)"},
  error_metric = "error.penetration_max_m",
}
