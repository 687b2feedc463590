-- Mud: two identical cars launched side by side on flat generated land, one
-- along a lane of mud, one along grass. The terrain's material map paints
-- mud (friction 0.3, softness 0.7) in patches on flat low ground and grass
-- (0.6, 0.4) elsewhere (app/terrain_scene.cpp); tyre grip scales with the
-- surface friction and its softness adds rolling drag (docs/vehicles.md
-- "Surfaces"), so the car in the mud spins its wheels and falls behind.
-- The player drives the mud car (drive.player) against the grass car on
-- autopilot; with --set autopilot=1 both drive the same autopilot straight
-- ahead (what the headless tests use).
-- Expectations: the lanes were found; on autopilot also: the mud car's
-- tyres report mud (friction and softness), it covered clearly less ground
-- and its driven wheels slipped more.
--
--   tumble play base:mud --set car=base:truck
--   tumble run base:mud --set autopilot=1
local drive = require "tumble.drive"

local LANE = 28   -- m of the same surface ahead of the start
local mud, grass = {}, {}

-- A start point (x, z) whose next LANE metres along +x all have friction mu.
local function find_lane(mu, avoid)
  for r = 0, 220, 8 do
    for z = -r, r, 8 do
      for _, x in ipairs({-r, r}) do
        local ok = true
        for d = 0, LANE, 4 do
          local h, f = vehicle.surface(x + d, z)
          if not h or math.abs(f - mu) > 1e-3 then ok = false break end
        end
        -- Also a metre either side, so the wheels stay on it.
        for d = 0, LANE, 4 do
          for _, s in ipairs({-1.5, 1.5}) do
            local h, f = vehicle.surface(x + d, z + s)
            if not h or math.abs(f - mu) > 1e-3 then ok = false end
          end
        end
        if ok and (not avoid or math.abs(z - avoid[2]) > 8 or math.abs(x - avoid[1]) > LANE + 10) then
          return {x, z}
        end
      end
    end
  end
end

local autopilot = param("autopilot", 0) ~= 0

local function launch(ctx, entry, start, player)
  local h = vehicle.surface(start[1], start[2])
  entry.car = vehicle.spawn(param("car", "base:hatchback"), {position = {start[1], h, start[2]}, heading = math.pi / 2})
  if player then
    entry.pilot = drive.player(entry.car, {ctx = ctx})
  else
    entry.pilot = drive.autopilot(entry.car,
                                  {waypoints = {{start[1] + 400, start[2]}}, speed = 30, traction = false, ctx = ctx})
  end
  entry.start, entry.slip, entry.friction_min, entry.softness_max = start, 0, math.huge, 0
  entry.driven = {}
  for i, axle in ipairs(entry.car:definition().axles) do
    if axle.driven then entry.driven[#entry.driven + 1] = 2 * i - 1; entry.driven[#entry.driven + 1] = 2 * i end
  end
end

return {
  title = "Mud: the same car on mud and on grass",
  duration = 4,
  params = {
    car = {default = "base:hatchback", description = "the vehicle definition, MOD:NAME (the menu's vehicle picker sets it)"},
    autopilot = {default = 0, description = "0: the player drives the car on mud; 1: both cars drive themselves"},
  },
  terrain = {generate = 21, size = 513, height = 2},  -- nearly flat: low ground with mud patches

  on_start = function(ctx)
    -- The sky (drawn only): --set time_of_day=H, --set weather=cloudy|storm.
    environment.set{time_of_day = param("time_of_day", 11.0), weather = param("weather", "clear"), clouds = 0.6}
    local m = find_lane(0.3)
    local g = m and find_lane(0.6, m)
    expect("a mud lane and a grass lane found", m ~= nil and g ~= nil)
    if not (m and g) then return end
    launch(ctx, mud, m, not autopilot)
    launch(ctx, grass, g, false)
    drive.show(mud.car)
  end,

  on_update = function(ctx, dt)
    for _, e in ipairs({mud, grass}) do
      if e.car then
        e.pilot:update(dt)
        local t = e.car:telemetry()
        for _, i in ipairs(e.driven) do
          local w = t.wheels[i]
          if w.contact then
            e.friction_min = math.min(e.friction_min, w.surface_friction)
            e.softness_max = math.max(e.softness_max, w.surface_softness)
            e.slip = e.slip + math.abs(w.spin * w.radius - t.speed) * dt
          end
        end
      end
    end
    if mud.car then
      hud_text(("mud   %4.1f m/s"):format(mud.car:speed()), ("grass %4.1f m/s"):format(grass.car:speed()))
    end
  end,

  on_finish = function(ctx)
    if not mud.car then return end
    local function dist(e) local p = e.car:position() return math.abs(p.x - e.start[1]) end
    -- Without the autopilot the mud car waits for a player; the grass car
    -- is driven either way and covers ground in 4 s (m; from rest towards
    -- 30 m/s, well over 10 m).
    expect("grass car drove (m)", dist(grass), {min = 10})
    if not autopilot then return end
    expect("mud car's tyres on mud (surface friction)", mud.friction_min, {max = 0.31})
    expect("grass car's tyres on grass (surface friction)", grass.friction_min, {min = 0.59})
    expect("mud car's tyres in soft mud (surface softness)", mud.softness_max, {min = 0.69, max = 0.71})
    expect("mud car behind: distance ratio mud / grass", dist(mud) / dist(grass), {max = 0.85})
    expect("wheelspin in the mud vs on grass (ratio of slip distance)", mud.slip / math.max(grass.slip, 1e-3), {min = 1.2})
  end,
}
