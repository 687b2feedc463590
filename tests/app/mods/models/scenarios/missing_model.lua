-- A model file that does not exist: a script error naming it.
return {duration = 0.1, on_start = function()
  local crate = world.box{position = {0, 1, 0}}
  crate:set_model("base:assets/models/no_such_car.obj")
end}
