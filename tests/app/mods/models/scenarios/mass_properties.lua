-- world.model_mass_properties on the shipped barrier (a 2 x 0.8 x 0.4 m box
-- with its base at y = 0) against the solid box, also scaled; and an open
-- mesh is refused.
return {duration = 0.1, on_start = function()
  local rho = 2400
  local p = world.model_mass_properties("base:assets/models/barrier.obj", {density = rho})
  local m = rho * 2 * 0.8 * 0.4
  expect("mass, kg", p.mass, {min = m * 0.9999, max = m * 1.0001})
  expect("volume, m^3", p.volume, {min = 0.6399, max = 0.6401})
  expect("centre height, m", p.center.y, {min = 0.3999, max = 0.4001})
  expect("I_xx, kg m^2", p.inertia.xx, {min = m * (0.64 + 0.16) / 12 * 0.9999, max = m * (0.64 + 0.16) / 12 * 1.0001})
  expect("I_xy, kg m^2", math.abs(p.inertia.xy), {max = 1e-3})
  -- Scaled by 2 along x: mass doubles, I_yy = m (a^2 + c^2) / 12 with a = 4.
  local s = world.model_mass_properties("base:assets/models/barrier.obj", {density = rho, scale = {2, 1, 1}})
  local iyy = 2 * m * (16 + 0.16) / 12
  expect("scaled mass, kg", s.mass, {min = 2 * m * 0.9999, max = 2 * m * 1.0001})
  expect("scaled I_yy, kg m^2", s.inertia.yy, {min = iyy * 0.9999, max = iyy * 1.0001})
  local ok, err = pcall(world.model_mass_properties, "assets/open_quad.obj")
  expect("an open mesh is refused", not ok and string.find(err, "not one closed surface", 1, true) ~= nil)
end}
