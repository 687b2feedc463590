-- Crash test: a car at 15 m/s (54 km/h) into a rag-doll standing before a
-- wall of boxes. The chassis is an ordinary rigid body, so the impact is solved by
-- the contact solver like any other: the rag-doll goes tumbling, the wall
-- scatters, the car is slowed. The autopilot holds the car straight up to
-- the impact, then the car coasts. The rag-doll's joints are impulses solved
-- with the contacts (joint_solver = "impulse"): measured (error.joint_error_max_m),
-- they hold the hit to 1.9 cm at 15 m/s, 3.3 cm at 20 and 3.2 cm at 30,
-- where the Lagrange solver opens 5.8, 5.1 and 9.9 cm.
-- Expectations: the car was at speed when it hit, the rag-doll was thrown
-- (its pelvis moved metres and fast), boxes scattered, the car slowed, and
-- nothing went non-finite.
--
--   tumble run base:crash_test
--   tumble play base:crash_test --set car=base:truck --set speed=20
local drive = require "tumble.drive"

local car, pilot, boxes = nil, nil, {}
local wall_z, doll_z = 40, 37
-- The rag-doll (spawned as the car comes near) and what is measured are
-- kept in ctx.state, so that a run loaded from a snapshot goes on with them.

return {
  title = "Crash test: a car, a rag-doll and a wall of boxes",
  duration = 6,
  joint_solver = "impulse",

  on_start = function(ctx)
    world.plane{friction = 0.9}
    for row = 0, 3 do
      for col = -3, 3 do
        boxes[#boxes + 1] = world.box{size = {0.7, 0.5, 0.5}, position = {col * 0.72 + (row % 2) * 0.36, 0.25 + row * 0.5, wall_z},
                                      mass = 40, friction = 0.6, color = {0.75, 0.6, 0.4}}
      end
    end
    car = vehicle.spawn(param("car", "base:hatchback"), {position = {0, 0, 0}, heading = 0})
    local speed = param("speed", 15)
    car:body():set_velocity({0, 0, speed})
    pilot = drive.autopilot(car, {waypoints = {{0, 200}}, speed = speed, traction = false, ctx = ctx})
    drive.show(car)
    ctx.state.impact_speed, ctx.state.doll_speed_max, ctx.state.speed_after = 0, 0, math.huge
  end,

  on_update = function(ctx, dt)
    local m = ctx.state
    local p = car:position()
    if p.z < doll_z - 3 then pilot:update(dt) else car:set_controls{throttle = 0, brake = 0, steer = 0} end
    if not m.doll and p.z > doll_z - 14 then
      m.doll = spawn_ragdoll{position = {0, 0, doll_z}, rotation = {0, math.pi, 0}}
      local q = m.doll.pelvis:position()
      m.doll_start = {x = q.x, z = q.z}
    end
    if m.doll then
      m.doll_speed_max = math.max(m.doll_speed_max, m.doll.pelvis:speed())
      if p.z < doll_z - 3 then m.impact_speed = car:speed() end
    end
    if ctx.time > 4 then m.speed_after = math.min(m.speed_after, math.abs(car:speed())) end
  end,

  on_finish = function(ctx)
    local m = ctx.state
    local impact_speed = m.impact_speed
    expect("car at speed before the impact (m/s)", impact_speed, {min = 0.8 * param("speed", 15)})
    expect("rag-doll created", m.doll ~= nil)
    if m.doll then
      local q = m.doll.pelvis:position()
      local moved = math.sqrt((q.x - m.doll_start.x) ^ 2 + (q.z - m.doll_start.z) ^ 2)
      expect("rag-doll thrown (pelvis moved, m)", moved, {min = 2})
      expect("rag-doll hit hard (pelvis speed max, m/s)", m.doll_speed_max, {min = 5, max = 60})
    end
    -- A box is scattered when it left its place in the wall (0.5 m along
    -- z) and is still a box on the ground: finite, its centre no lower than
    -- its half height (0.25 m) less 2 cm. Boxes that went non-finite or
    -- sank through the ground are counted apart and fail their own check.
    local scattered, lost = 0, 0
    for i, b in ipairs(boxes) do
      local p = b:position()
      local sound = p.x == p.x and p.y == p.y and p.z == p.z and p.y >= 0.25 - 0.02
      if not sound then
        lost = lost + 1
      elseif math.abs(p.z - wall_z) > 0.5 then
        scattered = scattered + 1
      end
    end
    expect("boxes knocked out of the wall", scattered, {min = 5})
    expect("boxes non-finite or below the ground", lost, {max = 0})
    expect("car slowed by the crash (m/s, after 4 s)", m.speed_after, {max = impact_speed * 0.8})
    local p = car:position()
    expect("car state finite", p.x == p.x and p.y == p.y and p.z == p.z and p.y > -1)
  end,
}
