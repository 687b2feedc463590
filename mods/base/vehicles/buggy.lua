-- Buggy: light (700 kg), rear-wheel drive with a limited-slip
-- differential and a revvy 150 kW engine on stiff springs (2 Hz). Quick to
-- turn and to slide: lift off or floor it mid-corner and the tail steps
-- out. Grippy tyres with a sharp peak that fall away when sliding.
return {
  name = "Buggy",
  description = "light, rear drive, stiff and twitchy: fast, slides when provoked",
  chassis = {mass = 700, size = {1.6, 0.5, 3.2}, com = {0, -0.05, -0.2}, drag_area = 0.6, mesh = "assets/models/buggy.obj",
             inertia = "mesh"},
  axles = {
    {position = {0.75, -0.1, 1.2}, radius = 0.32, width = 0.22, inertia = 0.7,
     steered = true, brake = 1100,
     suspension = {travel = 0.30, rest_length = 0.21, frequency = 2.0, bump_ratio = 0.35, rebound_ratio = 0.55,
                   anti_roll = 3000}},
    {position = {0.78, -0.1, -1.1}, radius = 0.34, width = 0.28, inertia = 0.8,
     driven = true, brake = 800, handbrake = 1500, differential = "limited_slip", lsd_bias = 2.5,
     suspension = {travel = 0.30, rest_length = 0.21, frequency = 2.1, bump_ratio = 0.35, rebound_ratio = 0.55}},
  },
  tyre = {
    longitudinal = {{0, 0}, {0.07, 1.2}, {0.25, 0.95}, {1, 0.75}},
    lateral = {{0, 0}, {0.12, 1.15}, {0.35, 0.9}, {1.57, 0.7}},
    rolling_resistance = 0.014,
  },
  engine = {torque = {{1500, 150}, {4000, 200}, {6500, 210}, {8000, 180}, {8500, 160}},
            idle_rpm = 1200, max_rpm = 8500, launch_rpm = 3500, inertia = 0.12, braking_torque = 25},
  gearbox = {ratios = {3.0, 2.0, 1.5, 1.2, 1.0}, reverse = 3.0, final_drive = 3.9,
             shift_up_rpm = 8000, shift_down_rpm = 4000, shift_time = 0.15},
  steering = {max_angle = 0.55, speed_sensitivity = 0.015, rate = 3.5},
  sound = {cylinders = 4, volume = 1.2},  -- a light, loud four
  -- An open car: the cockpit view keeps the buggy's own seat and roll cage
  -- (the seat is central, its top at y 0.9 m; the cage's roof 1.45-1.55 m).
  -- No bonnet: the hood camera rides low at the front of the cage, looking
  -- over the front cross tube (z 1.45 m, y 0.55 m).
  view = {hood_eye = {0, 0.85, 0.55}, cockpit_eye = {0, 1.15, -0.35}, open = true},
}
