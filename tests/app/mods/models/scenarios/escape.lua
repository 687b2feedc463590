-- A path that leaves the mod's folder is refused.
return {duration = 0.1, on_start = function()
  local crate = world.box{position = {0, 1, 0}}
  crate:set_model("../../../../../etc/hostname")
end}
