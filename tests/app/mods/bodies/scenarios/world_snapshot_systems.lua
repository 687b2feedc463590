-- world.snapshot() / world.restore() with joints, a rope, particles and a
-- vehicle: a swinging chain of hinged boxes, a rope with its end pinned to
-- the chain's last link, a smoke emitter riding on the first link, and a
-- car accelerating in first gear. After
-- 0.5 s a snapshot is taken and the scene runs 0.5 s more while the links,
-- the rope's particles and the emitter's live particles are recorded. Then
-- the scene is disturbed in every system (a link kicked, a joint removed, a
-- new joint, a motor, a second emitter, the rope unpinned, the car shifted
-- into reverse with the brakes on and re-tuned, a truck spawned), and
-- restored: the next 0.5 s must repeat the recorded ones bit for bit (joint
-- warm starts, the rope's last solve, the emitters' random streams, the
-- car's definition, engine, gear and wheel spins came back), the removed
-- joint is back and the new joint, emitter and truck are gone.
-- A restore refused part-way (a rope removed since the snapshot) leaves
-- the scene as it was before the call.
local links, hinges = {}, {}
local rope, smoke, car
local snap
local first, second = {}, {}
local kSnapStep, kLength = 30, 30

local function state()
  local out = {}
  for _, b in ipairs(links) do
    local p, v = b:position(), b:velocity()
    for _, x in ipairs({p.x, p.y, p.z, v.x, v.y, v.z}) do out[#out + 1] = x end
  end
  for i = 1, rope:count() do
    local p = rope:position(i)
    for _, x in ipairs({p.x, p.y, p.z}) do out[#out + 1] = x end
  end
  out[#out + 1] = smoke:count()
  out[#out + 1] = particles.count()
  local t, p = car:telemetry(), car:position()
  for _, x in ipairs({p.x, p.y, p.z, t.rpm, t.gear, t.wheels[1].spin, t.wheels[3].spin}) do out[#out + 1] = x end
  return out
end

local function same(a, b)
  if not a or not b or #a ~= #b then return false end
  for i = 1, #a do
    if a[i] ~= b[i] then return false end
  end
  return true
end

return {
  title = "world.snapshot and world.restore with joints, a rope and particles",
  duration = 2.5,
  joint_solver = "impulse",
  on_start = function(ctx)
    world.plane{}
    local prev = nil
    for i = 1, 5 do
      local b = world.box{size = {0.6, 0.2, 0.2}, position = {0.6 * i - 0.3, 4, 0}, mass = 1}
      hinges[i] = world.joint{type = "hinge", a = b, b = prev, anchor = {0.6 * (i - 1), 4, 0}, axis = {0, 0, 1}}
      links[i] = b
      prev = b
    end
    rope = deformable.rope{from = {3.0, 4, 0}, to = {3.0, 2, 0}, segments = 12, mass = 0.3, pin_start = false}
    rope:pin(1, links[5])  -- carried at the point of the last link where the rope starts
    smoke = particles.spawn("base:smoke", {body = links[1], offset = {0, 0.2, 0}})
    car = vehicle.spawn("base:hatchback", {position = {0, 0, 10}})
    car:set_controls{throttle = 0.6, gear = 1}
  end,
  on_update = function(ctx, dt)
    local s = ctx.step
    if s == kSnapStep then
      snap = world.snapshot()
    elseif s > kSnapStep and s <= kSnapStep + kLength then
      first[s - kSnapStep] = state()
    end
    if s == kSnapStep + kLength and not ctx.state.replay_from then
      links[3]:apply_impulse{0, 5, 3}
      hinges[2]:remove()
      local extra = world.joint{type = "ball", a = links[1], b = links[5], anchor = links[5]:position()}
      hinges[4]:set_motor(5, 50)
      local sparks = particles.spawn("base:smoke", {position = {1, 1, 1}})
      rope:unpin(1)
      car:set_controls{throttle = 0, brake = 1, gear = -1}
      car:tune{steering = {rate = 1.2}, engine = {max_rpm = 6500}}
      local truck = vehicle.spawn("base:truck", {position = {12, 0, 10}})
      world.restore(snap)
      expect("restore removes a vehicle spawned since", not truck:is_valid())
      expect("restore undoes a tune", car:definition().steering.rate == 2.5 and car:definition().engine.max_rpm == 6800)
      expect("restore brings a removed joint back", hinges[2]:is_valid())
      expect("restore removes a joint made since", not extra:is_valid())
      expect("restore removes an emitter made since", not sparks:alive())
      expect("the emitter made before is still there", smoke:alive())
      expect("the car's controls are back", car:controls().gear == 1 and math.abs(car:controls().throttle - 0.6) < 1e-6)
      ctx.state.replay_from = s
    end
    if ctx.state.replay_from and s > ctx.state.replay_from and s <= ctx.state.replay_from + kLength then
      second[s - ctx.state.replay_from] = state()
    end
  end,
  on_finish = function(ctx)
    local all = #first == kLength and #second == kLength
    for i = 1, kLength do
      if not same(first[i], second[i]) then all = false end
    end
    expect("the same steps after restore give the same bodies, rope and particles, bit for bit", all)
    expect("the chain swung: the last link moved", first[1] and first[kLength] and first[1][1] ~= first[kLength][1])
    expect("the car drove: its wheels spun up", first[1] and first[kLength] and first[kLength][#first[1]] > first[1][#first[1]])
    -- A refused restore changes nothing: the rope is gone since the snapshot.
    local before = state()
    rope:remove()
    local ok, err = pcall(world.restore, snap)
    expect("a rope removed since the snapshot makes restore refuse", not ok)
    expect("the message names the part", tostring(err):find("ropes_and_cloth") ~= nil)
    local after = {}
    for _, b in ipairs(links) do
      local p, v = b:position(), b:velocity()
      for _, x in ipairs({p.x, p.y, p.z, v.x, v.y, v.z}) do after[#after + 1] = x end
    end
    local bodiesBefore = {table.unpack(before, 1, #after)}
    expect("a refused restore leaves every body as it was", same(bodiesBefore, after))
    expect("... and every joint", hinges[2]:is_valid() and hinges[5]:is_valid())
    -- Refused part-way after removing a static model placed since: the
    -- model comes back with the rest of the state before the call.
    local placed = world.add_static_model("base:assets/models/barrier.obj", {position = {20, 0, 0}})
    local ok2, err2 = pcall(world.restore, snap)
    expect("a refused restore puts back a static model placed since", not ok2 and
           tostring(err2):find("ropes_and_cloth") ~= nil and placed:is_valid())
    print(tostring(snap))
  end,
}
