-- The chase camera needs a body to follow.
return {duration = 0.1, on_start = function()
  camera.set_mode("chase", {stiffness = 3})
end}
