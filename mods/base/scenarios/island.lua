-- Island: spheres and boxes tumble down the ridge of a generated island
-- (plasma faded to a sea at the border, a ridge across it, a ditch) and come to rest.
-- Expectations: every body rests on the terrain (its centre is between 0
-- and its bounding radius + 0.15 m above the terrain height under it, as
-- world.raycast finds it), nothing fell through, nearly all have stopped.
--
--   tumble run base:island
--   tumble play base:island --set terrain.height=60
--
-- The terrain is declared in the table below (the settings are described in
-- runtime/app/terrain_scene.h); --set terrain.KEY=VALUE overrides any of them.

local terrain_drop = require "lib.terrain_drop"

return terrain_drop.scenario{
  title = "Island: bodies tumble off a ridge into a ditch",
  duration = 12,  -- seconds, when run without --seconds/--steps
  terrain = {generate = 3, style = "island"},  -- generated with ridges and a ditch; --set terrain.* overrides
  -- The drop zone: over the ditch, which runs from (-154, 225) to (184, 20) m
  -- on the default 1025 m island, so bodies tumble down its sides.
  center = function() return param("x", 15), param("z", 123) end,
}
