-- The base cars' feel, side by side: each holds 11 m/s for 12 s on flat
-- ground, then steers 0.3 for 4 s. Measured per car: the steady yaw rate
-- and lateral acceleration (mean over the last second), the time the yaw
-- rate takes to reach 90 % of it, and the peak roll. docs/vehicles.md
-- describes the feel these numbers show: the truck leans most and turns
-- slowest, the buggy rotates quickest and leans least.
--
--   tumble --mods tests/vehicle/mods run vtest:step_steer --report r.json
local drive = require("tumble.drive")

local names = {"hatchback", "truck", "buggy"}
local cars = {}

return {
  title = "Step steer: hatchback, truck and buggy",
  duration = 16,
  on_start = function(ctx)
    world.plane{}
    for i, name in ipairs(names) do
      local car = vehicle.spawn("base:" .. name, {position = {(i - 2) * 40, 0, 0}})
      cars[name] = {car = car, gearbox = drive.gearbox(car), hist = {}, roll = 0}
    end
  end,
  on_update = function(ctx, dt)
    local t = ctx.time
    for _, c in pairs(cars) do
      local v = c.car:speed()
      c.gearbox:update(dt)
      c.car:set_controls{throttle = math.max(0, math.min(1, (11 - v) * 0.3)), steer = t >= 12 and 0.3 or 0}
      if t >= 12 then
        local b = c.car:body()
        local w, vel, up = b:angular_velocity(), b:velocity(), b:axis("y")
        local yaw = math.abs(w.y)
        c.hist[#c.hist + 1] = {t - 12, yaw, yaw * math.sqrt(vel.x ^ 2 + vel.z ^ 2)}
        c.roll = math.max(c.roll, math.deg(math.acos(math.min(1, up.y))))
      end
    end
  end,
  on_finish = function(ctx)
    for _, name in ipairs(names) do
      local c = cars[name]
      local n, yaw, lat = 0, 0, 0
      for _, h in ipairs(c.hist) do
        if h[1] >= 3 then n, yaw, lat = n + 1, yaw + h[2], lat + h[3] end
      end
      c.yaw, c.lat, c.rise = yaw / n, lat / n, -1
      for _, h in ipairs(c.hist) do
        if h[2] >= 0.9 * c.yaw then c.rise = h[1]; break end
      end
      expect(name .. " steady lateral acceleration (m/s^2)", c.lat, {min = 1, max = 1.1 * 9.81})
      expect(name .. " yaw rate rise to 90 % (s)", c.rise, {min = 0.01, max = 2})
      expect(name .. " peak roll (deg)", c.roll, {min = 0.1, max = 15})
    end
    local h, t, b = cars.hatchback, cars.truck, cars.buggy
    expect("the truck leans more than the hatchback (roll ratio)", t.roll / h.roll, {min = 1.5})
    expect("the buggy leans least (roll ratio to the hatchback)", b.roll / h.roll, {max = 0.8})
    expect("the buggy's yaw builds quickest (rise time ratio to the truck)", b.rise / t.rise, {max = 0.6})
    expect("the heavy truck corners with the least lateral acceleration (ratio to the hatchback)", t.lat / h.lat, {max = 0.85})
  end,
}
