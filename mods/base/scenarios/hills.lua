-- Hills: spheres and boxes roll and slide down a generated 1025 x 1025 m
-- plasma terrain among static rocks, and come to rest on its surface.
-- Expectations: every body rests on the terrain (its centre is between 0
-- and its bounding radius + 0.15 m above the terrain height under it, as
-- world.raycast finds it), nothing fell through, nearly all have stopped.
--
--   tumble run base:hills
--   tumble play base:hills --set terrain.generate=11 --set terrain.roughness=0.6
--
-- The terrain is declared in the table below (the settings are described in
-- runtime/app/terrain_scene.h); --set terrain.KEY=VALUE overrides any of them.

local terrain_drop = require "lib.terrain_drop"

return terrain_drop.scenario{
  title = "Hills: spheres and boxes settle on a generated terrain",
  duration = 12,  -- seconds, when run without --seconds/--steps
  terrain = {generate = 7, size = 1025},  -- a generated 1025 x 1025 m plasma terrain; --set terrain.* overrides
  center = function() return 0, 0 end,
}
