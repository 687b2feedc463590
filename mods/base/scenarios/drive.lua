-- Drive: free roam on generated hills among scattered rocks and trees. The
-- player drives (keyboard and gamepad, drive.player: W/S/A/D, R resets the
-- car, C the camera); with --set autopilot=1 the autopilot drives a loop of
-- waypoints over the hills instead (what the headless tests use).
-- Expectations: the car stays upright, keeps its wheels on the terrain
-- (never below it), and nothing in the vehicle goes non-finite; on
-- autopilot it also covers ground.
--
--   tumble play base:drive --set car=base:truck
--   tumble run base:drive --set autopilot=1
local drive = require "tumble.drive"

local car, pilot, player, effects
local start, travelled, lowest_gap, min_up, contact_steps, steps, max_speed = nil, 0, math.huge, 1, 0, 0, 0
local last

local function ground(x, z)
  local h = vehicle.surface(x, z)
  return h
end

-- Scales the tyre curves' friction by grip and each axle's spring rate k by
-- spring_rate (k from the suspension frequency f is m (2 pi f)^2, so f
-- scales by sqrt(spring_rate)). At 1 and 1 the car is left as defined.
local function tune_grip_and_springs(car, grip, spring_rate)
  if grip == 1 and spring_rate == 1 then return end
  local def = car:definition()
  local changes = {tyre = {}, axles = {}}
  for _, curve in ipairs({"longitudinal", "lateral"}) do
    changes.tyre[curve] = {}
    for i, point in ipairs(def.tyre[curve]) do changes.tyre[curve][i] = {point[1], point[2] * grip} end
  end
  for i, axle in ipairs(def.axles) do
    local s = axle.suspension
    changes.axles[i] = {suspension = (s.stiffness or 0) > 0 and {stiffness = s.stiffness * spring_rate}
                                      or {frequency = s.frequency * math.sqrt(spring_rate)}}
  end
  car:tune(changes)
end

return {
  title = "Drive: free roam on generated hills",
  duration = 40,
  terrain = {generate = 5, size = 513, height = 14},  -- gentle 513 x 513 m hills; --set terrain.* overrides
  -- What --set NAME=VALUE may change (tumble sweep sweeps these).
  params = {
    rocks = {default = 40, description = "rocks and trees scattered off the route (a count)"},
    car = {default = "base:hatchback", description = "the vehicle definition, MOD:NAME"},
    autopilot = {default = 0, description = "0: the player drives (drive.player); 1: the autopilot drives the waypoint loop"},
    speed = {default = 16, unit = "m/s", description = "the autopilot's cruising speed"},
    grip = {default = 1, description = "scales the tyre's friction curves (peak and sliding friction), a ratio"},
    spring_rate = {default = 1, description = "scales every axle's suspension spring rate, a ratio"},
    camera = {default = "chase", description = "the view to start in: chase, hood or cockpit (C steps through them)"},
  },

  on_start = function(ctx)
    -- The sky (drawn only): --set time_of_day=H, --set weather=cloudy|storm.
    environment.set{time_of_day = param("time_of_day", 16.5), weather = param("weather", "clear"), clouds = 0.45}
    local h0 = ground(0, 0)
    if not h0 then
      expect("terrain present", false)
      return
    end
    -- Rocks and trees scattered off the route (a ring of radius 60 m is the
    -- route). They collide with their own triangles (collision = "mesh", the
    -- default): a car hits a tree's trunk, not the air under its crown.
    local rng = random.new(ctx.seed)
    local M = "base:assets/models/"
    for i = 1, param("rocks") do
      local a, r = rng:float(0, 2 * math.pi), rng:float(10, 140)
      if math.abs(r - 60) > 12 then
        local x, z = math.cos(a) * r, math.sin(a) * r
        local s = rng:float(0.8, 2.2)
        local g = ground(x, z)
        local heading = rng:float(0, 3)
        if g and i % 3 == 0 then
          world.add_static_model(M .. "tree.obj", {position = {x, g - 0.1, z}, rotation = {0, heading, 0},
                                                   scale = 0.6 + 0.4 * s, friction = 0.8})
        elseif g then
          world.add_static_model(M .. "rock.obj", {position = {x, g - 0.1 * s, z}, rotation = {0, heading, 0},
                                                   scale = {s, s * 0.9, s}, friction = 0.8})
        end
      end
    end
    car = vehicle.spawn(param("car"), {position = {60, ground(60, 0), 0}, heading = 0})
    tune_grip_and_springs(car, param("grip"), param("spring_rate"))
    local waypoints = {}
    for i = 1, 12 do
      local a = i / 12 * 2 * math.pi
      waypoints[i] = {math.cos(a) * 60, math.sin(a) * 60}
    end
    if param("autopilot") ~= 0 then
      pilot = drive.autopilot(car, {waypoints = waypoints, speed = param("speed"), loop = true, radius = 10, ctx = ctx})
    else
      player = drive.player(car, {ctx = ctx})
    end
    effects = drive.effects(car)
    drive.show(car, {camera = param("camera")})
    start = car:position()
    last = start
  end,

  on_update = function(ctx, dt)
    if not (pilot or player) then return end  -- on_start stopped early (its error is in the report)
    if pilot then pilot:update(dt) else player:update(dt) end
    effects:update(dt)
    local p = car:position()
    travelled = travelled + math.sqrt((p.x - last.x) ^ 2 + (p.z - last.z) ^ 2)
    last = p
    local up = car:body():up()
    min_up = math.min(min_up, up.y)
    local t = car:telemetry()
    max_speed = math.max(max_speed, t.speed)
    local touching = 0
    for _, w in ipairs(t.wheels) do
      if w.contact then touching = touching + 1 end
      local g = ground(w.position.x, w.position.z)
      if g then lowest_gap = math.min(lowest_gap, w.position.y - g) end  -- hub above the terrain, m
    end
    steps = steps + 1
    if touching >= 3 then contact_steps = contact_steps + 1 end
    local kmh = t.speed * 3.6
    if math.abs(kmh) < 0.5 then kmh = 0 end  -- a car at rest creeps by mm/s: show 0, not -0
    hud_text(("%s  %3.0f km/h  gear %d  %4.0f rpm"):format(car:name(), kmh, t.gear, t.rpm),
             ("travelled %.0f m"):format(travelled))
  end,

  on_finish = function(ctx)
    if not car then return end
    local p = car:position()
    expect("vehicle state is finite", p.x == p.x and p.y == p.y and math.abs(p.x) < 1e6)
    if pilot then
      expect("distance driven (m)", travelled, {min = 200})
      expect("top speed reached (m/s)", max_speed, {min = 10})
    end
    expect("stayed upright (lowest chassis up.y)", min_up, {min = 0.5})
    expect("wheel hubs never below the terrain (m)", lowest_gap, {min = 0})
    expect("steps with 3+ wheels on the ground (fraction)", contact_steps / math.max(steps, 1), {min = 0.9})
  end,
}
