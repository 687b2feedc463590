-- A file that is not a model: a script error naming it and what is wrong.
return {duration = 0.1, on_start = function()
  world.add_static_model("assets/broken.obj", {position = {0, 0, 0}})
end}
