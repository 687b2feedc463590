-- No moving bodies: only a rope and an effect whose parameters come from
-- --set. The report's state hash must still tell runs apart (and agree for
-- the same inputs).
return {
  duration = 1,
  on_start = function()
    world.plane{}
    deformable.rope{from = {0, 3, 0}, to = {2, 3, 0}, segments = 8, mass = 0.8, stiffness = param("k", 2000)}
    particles.spawn("good:puff", {position = {0, 1, 0}}, {rate = param("rate", 20)})
  end,
}
