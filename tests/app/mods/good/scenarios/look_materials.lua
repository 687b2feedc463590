-- Ropes, cloth and a rag-doll for the look tests (tests/app/look_snapshot_test.cpp):
-- a rope pinned at both ends along X at y = 1.5, z = 3; a cloth hanging in
-- the plane z = -2 around x = -6 (pinned along its top edge); a rag-doll
-- lying at x = 6 with a green shirt. The sun stands towards +Z, 30 degrees up.
return {
  duration = 0.5,
  on_start = function()
    environment.set{sun = {0, 0.5, 0.866}, fog = false, clouds = 0}
    world.plane{color = {0.5, 0.5, 0.5}}
    deformable.rope{from = {-1, 1.5, 3}, to = {1, 1.5, 3}, segments = 10, pin_start = true, pin_end = true,
                    color = {0.9, 0.6, 0.2}}
    deformable.cloth{origin = {-7, 3, -2}, u = {2, 0, 0}, v = {0, -1.5, 0}, columns = 8, rows = 6, pins = "top",
                     color = {0.8, 0.15, 0.1}}
    spawn_ragdoll{position = {6, 0.2, 0}, rotation = {math.pi / 2, 0, 0}, colors = {shirt = {0.1, 0.6, 0.2}}}
  end,
}
