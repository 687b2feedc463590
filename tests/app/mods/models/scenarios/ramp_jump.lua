-- The base mod's jump ramp (base:assets/models/ramp.obj, mesh collision):
-- 6 m long rising along +Z to a 0.9 m lip that drops straight down. A car
-- at full throttle from 25 m before it climbs the deck, leaves the lip in
-- the air and lands upright beyond it.
--
-- Airborne: the rear wheels leave the lip a wheelbase after the front ones
-- (2.55 m at >= 8 m/s: <= 0.32 s); by then the front wheels have fallen at
-- most g t^2 / 2 = 0.5 m of the lip's 0.9 m, so for a while no wheel
-- touches anything.
local car, rest, top, min_up, lip_speed, airborne, air_time
local RAMP_Z = 30  -- the ramp's centre; its lip is at z = 33
return {duration = 7, on_start = function()
  world.plane{}
  world.add_static_model("base:assets/models/ramp.obj", {position = {0, 0, RAMP_Z}})
  car = vehicle.spawn("base:hatchback", {position = {0, 0, 2}, heading = 0})
  top, min_up, air_time = -math.huge, 1, 0
end, on_update = function(ctx, dt)
  car:set_controls{throttle = 1}
  local p = car:position()
  if ctx.time < 0.5 then rest = p.y end
  top = math.max(top, p.y)
  min_up = math.min(min_up, car:body():up().y)
  if not lip_speed and p.z >= RAMP_Z + 3 then lip_speed = car:speed() end
  local touching = 0
  for _, w in ipairs(car:telemetry().wheels) do
    if w.contact then touching = touching + 1 end
  end
  if ctx.time > 0.5 and touching == 0 then air_time = air_time + dt end
end, on_finish = function()
  expect("at the lip at speed (m/s)", lip_speed or 0, {min = 8})
  expect("chassis rose by the lip's height (m)", top - rest, {min = 0.75})
  expect("all four wheels in the air (s)", air_time, {min = 0.1})
  expect("landed beyond the ramp (m)", car:position().z, {min = RAMP_Z + 3 + 5})
  expect("back on the ground (m)", car:position().y - rest, {min = -0.05, max = 0.05})
  expect("stayed upright", min_up, {min = 0.7})
end}
