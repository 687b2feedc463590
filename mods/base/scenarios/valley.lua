-- Valley: the terrain is shaped here in Lua with the terrain generators and
-- filters: rolling plasma hills, a jagged ridge along the north, a
-- river ditch winding through the middle, a hill raised with a plasma bump,
-- then smoothed. Spheres and boxes are dropped on the river's sloping bank
-- among static rocks. Same expectations as hills: every body rests on the
-- terrain, nothing fell through, nearly all have stopped.
--
--   tumble run base:valley
--   tumble play base:valley --set terrain.height=80
--   tumble run base:valley --set seed_offset=5     (another valley)
--
-- Heights are fractions of terrain.height (metres from value 0 to 1) and
-- positions fractions of the map, so the same build works at any size.
-- See HeightMap in docs/lua-api.md for every method.

local terrain_drop = require "lib.terrain_drop"

local s = param("seed_offset", 0)

return terrain_drop.scenario{
  title = "Valley: a terrain shaped in Lua, bodies settle on the river bank",
  duration = 12,  -- seconds, when run without --seconds/--steps
  terrain = {
    size = 513, spacing = 1, height = 50,  -- 513 x 513 samples, 1 m apart, 50 m of relief
    build = function(map)
      map:plasma{seed = 21 + s, roughness = 0.45}
      map:ridge{from = {0.05, 0.15}, to = {0.95, 0.2}, height = 0.35, width = 0.08, jaggedness = 0.3, seed = 22 + s}
      map:ridge{from = {0.0, 0.55}, to = {1.0, 0.45}, height = -0.3, width = 0.04, jaggedness = 0.2, seed = 23 + s}
      map:bump{x = 0.6, z = 0.65, width = 0.3, depth = 0.3, amplitude = 0.25, seed = 24 + s}
      map:smooth(2)
    end,
  },
  -- The drop zone: on the river's north bank, 20 m from the middle of the ditch.
  center = function() return param("x", 0), param("z", param("bank", -20)) end,
}
