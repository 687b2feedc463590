-- A negative mass from Lua: refused with a clear error naming the field.
return {
  duration = 0.1,
  on_start = function()
    world.box{size = {1, 1, 1}, mass = -3}
  end,
}
