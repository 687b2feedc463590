-- Convoy: many vehicles (50 by default, --set count=N) driven by Lua
-- autopilots around concentric rings on generated hills; hatchbacks, trucks
-- and buggies in turn. The player drives the lead car (drive.player, with
-- the chase camera on it); --set autopilot=1 puts it on autopilot too (what
-- the headless runs use). The scene behind tools/bench/bench_vehicle.cpp
-- (ms per step and Lua cost per vehicle); --set parked=1 leaves every car
-- parked (no Lua per car), for the benchmark's baseline.
-- Expectations: with autopilots most cars are under way at the end and
-- none has flipped.
--
--   tumble play base:convoy --set count=20
--   tumble run base:convoy --set autopilot=1
local drive = require "tumble.drive"

local cars, pilots, player = {}, {}, nil
local kinds = {"base:hatchback", "base:truck", "base:buggy"}

return {
  title = "Convoy: vehicles on autopilot around the hills",
  duration = 20,
  terrain = {generate = 5, size = 513, height = 14},

  on_start = function(ctx)
    -- The sky (drawn only): --set time_of_day=H, --set weather=cloudy|storm.
    environment.set{time_of_day = param("time_of_day", 17.2), weather = param("weather", "clear"), clouds = 0.4}
    local count = param("count", 50)
    local rings = math.max(1, math.ceil(count / 10))
    for i = 1, count do
      local ring = (i - 1) % rings
      local slot = (i - 1) // rings
      local per_ring = math.ceil(count / rings)
      local radius = 40 + ring * 14
      local a = slot / per_ring * 2 * math.pi
      local x, z = math.cos(a) * radius, math.sin(a) * radius
      local h = vehicle.surface(x, z)
      -- Heading along the ring (counter-clockwise seen from above).
      local car = vehicle.spawn(kinds[(i - 1) % #kinds + 1], {position = {x, h, z}, heading = math.atan(-math.sin(a), math.cos(a))})
      cars[i] = car
      if param("parked", 0) ~= 0 then
        -- no controller: the benchmark's baseline
      elseif i == 1 and param("autopilot", 0) == 0 then
        player = drive.player(car, {ctx = ctx})
        drive.show(car)
      else
        local waypoints = {}
        for k = 1, 16 do
          local b = a + k / 16 * 2 * math.pi
          waypoints[k] = {math.cos(b) * radius, math.sin(b) * radius}
        end
        pilots[#pilots + 1] = drive.autopilot(car, {waypoints = waypoints, speed = 12, loop = true, radius = 8, ctx = ctx})
      end
    end
  end,

  on_update = function(ctx, dt)
    if player then player:update(dt) end
    for i = 1, #pilots do pilots[i]:update(dt) end
  end,

  on_finish = function(ctx)
    local moving, upright = 0, 0
    for _, car in ipairs(cars) do
      if math.abs(car:speed()) > 3 then moving = moving + 1 end
      if car:body():up().y > 0.3 then upright = upright + 1 end
    end
    if #pilots > 0 then expect("cars under way at the end (fraction)", moving / #cars, {min = 0.8}) end
    expect("cars upright (fraction)", upright / #cars, {min = 1})
  end,
}
