-- Time trial: drive through six checkpoint gates in order and back to the
-- start; the timer runs from the first step, the HUD's lap widget shows the
-- time, the next gate and the best time (hud.set_lap), the minimap the gates
-- (hud.set_gates), and a new best is saved (save.write: JSON in
-- the user's data folder, written atomically). The player drives
-- (drive.player); --set autopilot=1 hands the lap to the autopilot (what the
-- headless runs use).
-- Expectations: every gate passed in order, the lap within a sane time,
-- the best time read back equals the one written.
--
--   tumble play base:time_trial --set car=base:buggy
--   tumble run base:time_trial --set autopilot=1
local drive = require "tumble.drive"

-- Gates on a 240 x 120 m loop, start/finish last.
local gates = {{40, 0}, {110, 25}, {120, 90}, {60, 120}, {-10, 95}, {-20, 30}, {0, 0}}
local car, pilot, player
local best  -- the best lap on record (the save file), s
-- The lap's progress (next_gate, lap_time, finished, saved_best) is kept in
-- ctx.state, so that a run loaded from a snapshot goes on with it.

local function post(x, z, color)
  world.box{type = "static", size = {0.3, 1.5, 0.3}, position = {x, 0.75, z}, color = color}
end

return {
  title = "Time trial: six gates, beat your best",
  duration = 60,
  params = {
    car = {default = "base:hatchback", description = "the vehicle definition, MOD:NAME (the menu's vehicle picker sets it)"},
    autopilot = {default = 0, description = "0: the player drives; 1: the autopilot drives through the gates"},
    speed = {default = 22, unit = "m/s", description = "the autopilot's cruising speed"},
  },

  on_start = function(ctx)
    -- The sky (drawn only): --set time_of_day=H, --set weather=cloudy|storm.
    environment.set{time_of_day = param("time_of_day", 13.5), weather = param("weather", "clear"), clouds = 0.35}
    world.plane{friction = 1, color = {0.35, 0.36, 0.38}}
    best = (save.read("time_trial") or {}).best_s
    local lap = ctx.state
    lap.next_gate, lap.lap_time, lap.finished = 1, 0, false
    for i, g in ipairs(gates) do
      local color = i == #gates and {0.9, 0.9, 0.9} or {0.95, 0.6, 0.1}
      -- Posts 6 m either side, across the line from the previous gate to the next.
      local a, b = gates[i - 1] or {0, -12}, gates[i + 1] or {0, 12}
      local dx, dz = b[1] - a[1], b[2] - a[2]
      local len = math.sqrt(dx * dx + dz * dz)
      local px, pz = -dz / len * 6, dx / len * 6
      post(g[1] - px, g[2] - pz, color)
      post(g[1] + px, g[2] + pz, color)
      -- The trigger spans the whole opening between the posts (a car that
      -- passes between them passes the gate), and at least 9 m each way.
      local sx, sz = math.max(2 * math.abs(px), 9), math.max(2 * math.abs(pz), 9)
      trigger.box{center = {g[1], 1, g[2]}, size = {sx, 3, sz}, on_enter = function(body)
        local lap = ctx.state
        if lap.finished or not car or body ~= car:body() or i ~= lap.next_gate then return end
        lap.next_gate = lap.next_gate + 1
        if lap.next_gate > #gates then
          lap.finished = true
          game.message(("Lap %.2f s"):format(lap.lap_time), 5)
          if not best or lap.lap_time < best then
            best = lap.lap_time
            save.write("time_trial", {best_s = lap.lap_time, car = car:name()})
            lap.saved_best = lap.lap_time
          end
          game.win(("lap %.2f s"):format(lap.lap_time))
        end
      end}
    end
    hud.set_gates(gates)
    car = vehicle.spawn(param("car", "base:hatchback"), {position = {0, 0, -12}, heading = 0})
    drive.show(car)
    if param("autopilot", 0) ~= 0 then
      pilot = drive.autopilot(car, {waypoints = gates, speed = param("speed", 22), loop = false, radius = 4, ctx = ctx})
    else
      player = drive.player(car, {ctx = ctx})
    end
  end,

  on_update = function(ctx, dt)
    local lap = ctx.state
    if not lap.finished then lap.lap_time = lap.lap_time + dt end
    if pilot then pilot:update(dt) else player:update(dt) end
    -- Speed, rpm and gear are on the HUD already; the lap is the scenario's.
    hud.set_lap{time = lap.lap_time, best = best, gate = math.min(lap.next_gate, #gates), gates = #gates,
                finished = lap.finished}
  end,

  on_finish = function(ctx)
    local lap = ctx.state
    expect("gates passed in order", lap.next_gate - 1, {min = #gates, max = #gates})
    expect("lap finished", lap.finished)
    if lap.finished then
      -- About 520 m of track: faster than 10 m/s on average would be a
      -- shortcut, slower than 4 m/s a car that crawls.
      expect("lap time (s)", lap.lap_time, {min = 520 / 40, max = 520 / 4})
      local stored = (save.read("time_trial") or {}).best_s
      expect("best time saved and read back", stored ~= nil and stored <= lap.lap_time + 1e-9)
      if lap.saved_best then expect("saved value round-trips", stored == lap.saved_best) end
    end
  end,
}
