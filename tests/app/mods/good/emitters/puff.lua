-- A small white puff, for the tests.
return {
  rate = 50,
  lifetime = {0.5, 1.5},
  speed = {0.5, 1},
  spread = math.rad(30),
  size = {{0, 0.2}, {1, 0.5}},
  alpha = {{0, 0.8}, {1, 0}},
}
