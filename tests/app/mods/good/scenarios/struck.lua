-- A box dropped 1 m onto the ground plane; its sound material is a
-- parameter (audio_cli_test.cpp renders it with --audio-out and compares
-- how metal, wood and rubber ring).
return {
  duration = 4,
  params = {sound = {default = "metal", description = "the box's Material.sound"}},
  on_start = function()
    world.plane{}
    local box = world.box{size = {0.5, 0.5, 0.5}, mass = 20, position = {0, 1.25, -3}}
    box:set_material{sound = param("sound")}
  end,
}
