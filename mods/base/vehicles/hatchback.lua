-- Hatchback: a front-wheel-drive family car. Soft, comfortable springs
-- (1.5 Hz), a gentle 95 kW engine, front-heavy: it understeers
-- predictably and forgives mistakes. Units: docs/vehicles.md.
return {
  name = "Hatchback",
  description = "front drive, soft and forgiving: understeers gently, brakes straight",
  chassis = {mass = 1150, size = {1.7, 0.6, 3.9}, com = {0, 0, 0.15}, drag_area = 0.68, mesh = "assets/models/hatchback.obj", inertia = "mesh",
             display_mesh = "assets/models/hatchback_shaped.obj"},
  axles = {
    {position = {0.74, -0.15, 1.25}, radius = 0.30, width = 0.19, inertia = 0.9,
     steered = true, driven = true, brake = 1600,
     suspension = {travel = 0.22, rest_length = 0.22, frequency = 1.5, bump_ratio = 0.3, rebound_ratio = 0.5,
                   anti_roll = 9000}},
    {position = {0.74, -0.15, -1.30}, brake = 900, handbrake = 1800,
     suspension = {travel = 0.22, rest_length = 0.23, frequency = 1.6, bump_ratio = 0.3, rebound_ratio = 0.5,
                   anti_roll = 4000}},
  },
  tyre = {
    longitudinal = {{0, 0}, {0.08, 1.05}, {0.3, 0.9}, {1, 0.75}},
    lateral = {{0, 0}, {0.14, 1.0}, {0.4, 0.85}, {1.57, 0.75}},
    rolling_resistance = 0.012,
  },
  engine = {torque = {{1000, 110}, {2500, 140}, {4500, 150}, {6000, 135}, {6800, 110}},
            idle_rpm = 850, max_rpm = 6800, launch_rpm = 2200, inertia = 0.15, braking_torque = 30},
  gearbox = {ratios = {3.45, 1.95, 1.32, 1.03, 0.82}, reverse = 3.3, final_drive = 4.05,
             shift_up_rpm = 6200, shift_down_rpm = 2500, shift_time = 0.25},
  steering = {max_angle = 0.6, speed_sensitivity = 0.02, rate = 2.5},
  sound = {cylinders = 4, volume = 0.9},
  -- Eyes in the drawn model's frame: the hood camera just above the back of
  -- the bonnet (the windscreen's foot is at z 1.25 m, y 0.92 m), the
  -- driver on the left behind the dashboard.
  view = {hood_eye = {0, 1.02, 1.15}, cockpit_eye = {0.35, 1.17, -0.1}},
}
