-- A minimal valid vehicle: every field not given takes its default.
return {
  name = "Kart",
  description = "test kart",
  chassis = {mass = 300, size = {1.2, 0.4, 2.0}},
  axles = {
    {position = {0.55, -0.05, 0.7}, radius = 0.2, steered = true,
     suspension = {travel = 0.1, rest_length = 0.1, frequency = 2.5}},
    {position = {0.55, -0.05, -0.7}, driven = true, handbrake = 600},
  },
}
