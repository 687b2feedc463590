-- Ground planes drawn with each texture world.plane takes, one plane per
-- height (y = its index in `names`), plus one without a texture at y = 20,
-- for scene_models_test.cpp; and the texture values it refuses, each under
-- pcall with its message checked.
local names = {"checker", "grass", "rock", "sand", "mud", "snow", "gravel", "dirt", "moss"}
local function fails(what, def, words)
  local ok, err = pcall(world.plane, def)
  expect(what .. " is refused", not ok)
  expect(what .. " says: " .. words, (not ok) and string.find(tostring(err), words, 1, true) ~= nil)
end
return {duration = 0.1, on_start = function()
  for i, name in ipairs(names) do world.plane{point = {0, i, 0}, texture = name} end
  world.plane{point = {0, 20, 0}}
  fails("an unknown texture", {texture = "lava"},
        "world.plane: field 'texture' must be \"checker\", \"grass\", \"rock\", \"sand\", \"mud\", \"snow\", \"gravel\", \"dirt\" or \"moss\", got \"lava\"")
  fails("a number", {texture = 3}, "got number")
  fails("a long name", {texture = string.rep("x", 100000)}, "got \"xxxxxxxxxx")
  fails("a misspelt field", {textur = "grass"}, "unknown field 'textur' (did you mean: texture?)")
end}
