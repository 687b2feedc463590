-- A vehicle file with a misspelt field: `tumble check` and vehicle.spawn
-- must name the file and the field path.
return {
  name = "Broken",
  chassis = {mass = 900},
  axles = {
    {position = {0.7, -0.1, 1.2}, steered = true, driven = true, suspension = {frequncy = 1.5}},
    {position = {0.7, -0.1, -1.2}},
  },
}
