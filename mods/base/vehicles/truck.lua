-- Off-road truck: heavy (2200 kg), four-wheel drive with limited-slip
-- differentials, long soft travel (0.4 m at 1.1 Hz), a low-revving diesel
-- with lots of torque and short gearing. Slow to turn and to stop, rolls in
-- corners, but climbs and crosses mud where the others dig in.
return {
  name = "Off-road truck",
  description = "4x4 diesel on long soft springs: slow, heavy, climbs and crosses mud",
  chassis = {mass = 2200, size = {1.9, 0.9, 4.6}, com = {0, -0.05, 0.1}, drag_area = 1.6, friction = 0.5, mesh = "assets/models/truck.obj",
             inertia = "mesh", display_mesh = "assets/models/truck_shaped.obj"},
  axles = {
    {position = {0.82, -0.3, 1.55}, radius = 0.42, width = 0.28, inertia = 2.5,
     steered = true, driven = true, brake = 3000, differential = "limited_slip", lsd_bias = 3,
     suspension = {travel = 0.40, rest_length = 0.42, frequency = 1.1, bump_ratio = 0.25, rebound_ratio = 0.45,
                   anti_roll = 6000}},
    {position = {0.82, -0.3, -1.55}, driven = true, brake = 2200, handbrake = 4000,
     differential = "limited_slip", lsd_bias = 3,
     suspension = {travel = 0.40, rest_length = 0.44, frequency = 1.2, bump_ratio = 0.25, rebound_ratio = 0.45,
                   anti_roll = 4000}},
  },
  tyre = {
    longitudinal = {{0, 0}, {0.12, 1.0}, {0.4, 0.9}, {1, 0.85}},
    lateral = {{0, 0}, {0.18, 0.95}, {0.5, 0.85}, {1.57, 0.8}},
    rolling_resistance = 0.018, soft_ground_drag = 0.03,
  },
  engine = {torque = {{800, 300}, {1500, 420}, {2500, 400}, {3500, 300}, {4000, 250}},
            idle_rpm = 700, max_rpm = 4000, launch_rpm = 1400, inertia = 0.5, braking_torque = 80},
  gearbox = {ratios = {4.2, 2.5, 1.6, 1.2, 0.95}, reverse = 4.0, final_drive = 4.1,
             shift_up_rpm = 3500, shift_down_rpm = 1400, shift_time = 0.4},
  steering = {max_angle = 0.55, speed_sensitivity = 0.03, rate = 1.8},
  sound = {cylinders = 6, volume = 1.1},  -- a straight-six diesel: low, steady note
  -- Eyes in the drawn model's frame: the hood camera over the back of the
  -- bonnet (the windscreen's foot is at z 1.6 m, y 1.5 m), the driver high
  -- in the cab (floor 0.98 m, roof 2.25 m), the dashboard under the glass.
  view = {hood_eye = {0, 1.64, 1.75}, cockpit_eye = {0.4, 1.85, 0.7}},
}
