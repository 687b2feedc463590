-- A model whose triangles have no area: mesh collision is refused with a
-- script error naming the file and what is wrong.
return {duration = 0.1, on_start = function()
  world.add_static_model("assets/no_area.obj", {position = {0, 0, 0}})
end}
