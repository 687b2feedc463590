-- Every field here is wrong in its own way; check must list each with its line.
return {
  rate = "lots",
  lifetime = {2, 1},
  shape = "donut",
  colour = {1, 0, 0},
}
