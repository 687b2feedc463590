-- Misspelt or wrong options are errors that say what is valid; each call is
-- made under pcall and its message checked, so the run passes only when every
-- mistake is caught with the right words.
local M = "base:assets/models/"
local function fails(name, fn, words)
  local ok, err = pcall(fn)
  expect(name .. " is refused", not ok)
  expect(name .. " says: " .. words, (not ok) and string.find(tostring(err), words, 1, true) ~= nil)
end
return {duration = 0.1, on_start = function()
  local crate = world.box{position = {0, 1, 0}}
  fails("misspelt option", function() crate:set_model(M .. "barrier.obj", {ofset = {0, 1, 0}}) end,
        "unknown field 'ofset' (did you mean: offset?) (valid: offset, rotation, scale)")
  fails("zero scale", function() crate:set_model(M .. "barrier.obj", {scale = 0}) end, "'scale' must be a number > 0")
  fails("not a path", function() crate:set_model(42) end, "expected a model path")
  fails("unknown mod", function() crate:set_model("nomod:assets/x.obj") end, "no mod named \"nomod\"")
  fails("bad collision", function() world.add_static_model(M .. "rock.obj", {collision = "hull"}) end,
        "'collision' must be \"mesh\", \"box\" or \"none\"")
  fails("misspelt collision option", function() world.add_static_model(M .. "rock.obj", {colision = "mesh"}) end,
        "unknown field 'colision' (did you mean: collision")
  fails("unknown camera mode", function() camera.set_mode("helicopter") end, "mode must be \"orbit\"")
  fails("bad interior", function() camera.set_mode("cockpit", {target = crate, interior = M .. "nothing.obj"}) end,
        "option 'interior'")
  fails("huge gauge", function() camera.set_mode("cockpit", {target = crate, gauge_radius = 5}) end,
        "option 'gauge_radius' must be 0.01..0.5 m")
  fails("NaN gauge centre", function() camera.set_mode("cockpit", {target = crate, speed_gauge = {0, 0 / 0, 1}}) end,
        "speed_gauge")
  -- And the good calls work: a model on the crate, then cleared.
  crate:set_model(M .. "barrier.obj", {offset = {0, -0.4, 0}, rotation = {0, 0.5, 0}, scale = {1, 1, 2}})
  expect("clear_model reports the model it removed", crate:clear_model())
  camera.set_mode("hood", {target = crate, eye = {0, 1, 0}})
  expect("camera.mode reports the mode", camera.mode() == "hood")
end}
