-- tumble.drive: vehicle controllers in Lua, run at the fixed rate from a
-- scenario's on_update (the wheel physics runs in C++ in every substep).
--
--   local drive = require "tumble.drive"
--   local car = vehicle.spawn("base:hatchback", {position = {0, 0, 0}})
--   local pilot = drive.autopilot(car, {waypoints = {{0, 100}, {100, 100}}, speed = 20, loop = true})
--   function scenario.on_update(ctx, dt) pilot:update(dt) end
--
-- Controllers:
--   drive.gearbox(car)            automatic gearbox: shifts at the definition's
--                                 shift_up_rpm / shift_down_rpm, never during a shift
--   drive.traction(car, opts)     traction control: cuts throttle while a driven
--                                 wheel's tread runs faster than the ground by more
--                                 than opts.slip (default 0.15) of the speed or 1 m/s
--   drive.autopilot(car, opts)    follows waypoints {x, z} at opts.speed (m/s);
--                                 uses gearbox and traction control; for headless runs
--   drive.player(car, opts)       the player's keyboard and gamepad: switches the
--                                 `vehicle` input context on and reads its actions
--                                 throttle, brake, steer, handbrake, gear_up,
--                                 gear_down, reset (bindings.lua)
--                                 and brings a car that drove off the terrain's edge
--                                 back (drive.rescue)
--   drive.rescue(car, point)      the car at rest, upright, on `point` {x, z}, facing
--                                 the centre of the terrain
--   drive.upright(car, opts)      a car on its roof or stuck back on its wheels where
--                                 it is, facing the same way, at rest, lifted clear
--   drive.effects(car)            tyre dust and exhaust smoke rates from slip and throttle;
--                                 feeds particle emitters when the particles module exists
--   drive.show(car, opts)         the chase camera on the car and its chassis mesh, when the
--                                 camera and model APIs exist (nothing before)
-- Each returns an object with :update(dt).
--
-- Snapshots (run --save-state / --load-state, docs/snapshots.md): give the
-- controllers the scenario's ctx (opts.ctx, in on_start) and what changes
-- while they run (the gearbox's hold timer, the traction factor, the
-- autopilot's waypoint, laps and done, where the player's car last was on
-- the map) is kept in ctx.state.drive, which a snapshot holds, so a run
-- loaded from one drives on exactly as the run it was saved from. Without
-- opts.ctx it is kept in the controller, and a loaded run starts it afresh.

local drive = {}

local function clamp(x, lo, hi) return math.max(lo, math.min(hi, x)) end

-- A controller's changing state: a function returning its table. With a
-- ctx, entry n of ctx.state.drive (n: the controller's place among those
-- made with that ctx, the same again when on_start runs again), looked up
-- at every call because loading a snapshot replaces ctx.state; else a table
-- of its own.
local function state_of(ctx, initial)
  if not ctx then return function() return initial end end
  ctx.state.drive = ctx.state.drive or {}
  local n = #ctx.state.drive + 1
  ctx.state.drive[n] = initial
  return function() return ctx.state.drive[n] end
end

-- Methods from the class, other fields (laps, done, ...) from the state.
local function class()
  local c = {}
  c.__index = function(self, k)
    local m = c[k]
    if m ~= nil then return m end
    local state = rawget(self, "state")
    return state and state()[k]
  end
  return c
end

-- Automatic gearbox --------------------------------------------------------

local Gearbox = class()

-- opts.ctx: see "Snapshots" above.
function drive.gearbox(car, opts)
  local def = car:definition()
  return setmetatable({car = car, up = def.gearbox.shift_up_rpm, down = def.gearbox.shift_down_rpm,
                       gears = #def.gearbox.ratios, state = state_of(opts and opts.ctx, {hold = 0})}, Gearbox)
end

-- Picks the gear for the current rpm; call once per step. `wanted` is the
-- direction the driver wants: 1 forward, -1 reverse. `t` is this step's
-- car:telemetry() when the caller has it already.
function Gearbox:update(dt, wanted, t)
  local car, s = self.car, self.state()
  t = t or car:telemetry()
  local gear = t.gear
  s.hold = math.max(0, s.hold - dt)
  if wanted == -1 then
    if t.speed < 1 then gear = -1 end
  elseif gear < 1 then
    if t.speed > -1 then gear = 1 end
  elseif not t.shifting and s.hold == 0 then
    if t.rpm > self.up and gear < self.gears then
      gear, s.hold = gear + 1, 0.8
    elseif t.rpm < self.down and gear > 1 then
      gear, s.hold = gear - 1, 0.8
    end
  end
  if gear ~= t.gear then car:set_controls{gear = gear} end
  return gear
end

-- Traction control ------------------------------------------------------------

local Traction = class()

function drive.traction(car, opts)
  opts = opts or {}
  local driven = {}
  for i, axle in ipairs(car:definition().axles) do
    if axle.driven then driven[#driven + 1] = 2 * i - 1; driven[#driven + 1] = 2 * i end
  end
  return setmetatable({car = car, slip = opts.slip or 0.15, driven = driven, state = state_of(opts.ctx, {factor = 1})},
                      Traction)
end

-- Returns the throttle to use instead of `throttle`. `t`: this step's
-- car:telemetry() when the caller has it already.
function Traction:filter(dt, throttle, t)
  t = t or self.car:telemetry()
  local spinning = false
  for _, i in ipairs(self.driven) do
    local w = t.wheels[i]
    local excess = math.abs(w.spin * w.radius) - math.abs(t.speed)  -- tread faster than the ground, m/s
    if w.contact and excess > math.max(self.slip * math.abs(t.speed), 1.0) then spinning = true end
  end
  -- Cut while spinning, give back while gripping; never below 30% so the
  -- car still pulls away on a slope.
  local s = self.state()
  if spinning then
    s.factor = math.max(0.3, s.factor - 3 * dt)
  else
    s.factor = math.min(1, s.factor + 1.5 * dt)
  end
  return throttle * s.factor
end

-- Waypoint autopilot ------------------------------------------------------------

local Autopilot = class()

-- opts: waypoints = {{x, z}, ...}, speed = m/s, loop = bool, radius = m
-- (when a waypoint counts as reached, default 6), traction = bool (default
-- true), ctx (see "Snapshots" above). pilot.index, pilot.laps and
-- pilot.done say where it is.
function drive.autopilot(car, opts)
  assert(opts and opts.waypoints and #opts.waypoints > 0, "drive.autopilot: opts.waypoints = {{x, z}, ...} needed")
  return setmetatable({car = car, waypoints = opts.waypoints, speed = opts.speed or 15, loop = opts.loop,
                       radius = opts.radius or 6,
                       state = state_of(opts.ctx, {index = 1, laps = 0, done = false}),
                       gearbox = drive.gearbox(car, opts),
                       traction = opts.traction ~= false and drive.traction(car, opts) or nil}, Autopilot)
end

function Autopilot:update(dt)
  local car, s = self.car, self.state()
  if s.done then
    car:set_controls{throttle = 0, brake = 1, steer = 0}
    return
  end
  local p, f = car:position(), car:forward()
  local wp = self.waypoints[s.index]
  local dx, dz = wp[1] - p.x, wp[2] - p.z
  local dist = math.sqrt(dx * dx + dz * dz)
  if dist < self.radius then
    s.index = s.index + 1
    if s.index > #self.waypoints then
      if self.loop then s.index, s.laps = 1, s.laps + 1 else s.done = true end
    end
    return self:update(dt)
  end
  -- Heading error: positive when the waypoint is to the right (steer +1 = right).
  local fx, fz = f.x, f.z
  local right = dx * -fz + dz * fx
  local ahead = dx * fx + dz * fz
  local err = math.atan(right, ahead)
  local steer = clamp(err * 2.0, -1, 1)
  -- Slow down for sharp turns and for the last waypoint.
  local target = self.speed / (1 + 2.5 * math.abs(err))
  if not self.loop and s.index == #self.waypoints then target = math.min(target, 0.5 * dist + 2) end
  local t = car:telemetry()
  local v = t.speed
  local throttle, brake = clamp((target - v) * 0.4, 0, 1), 0
  if v > target + 2 then throttle, brake = 0, clamp((v - target) * 0.15, 0, 1) end
  if self.traction then throttle = self.traction:filter(dt, throttle, t) end
  car:set_controls{throttle = throttle, brake = brake, steer = steer, handbrake = 0}
  self.gearbox:update(dt, 1, t)
end

-- Player --------------------------------------------------------------------------

local Player = class()

-- The player's controller: switches the `vehicle` input context on (it
-- starts off, so scenarios without a car keep Space and the mouse for the
-- camera) and reads the actions named in bindings.lua. In a build without
-- the input module (no global `input`) update() leaves the controls alone
-- and returns false. opts.automatic (default true): the automatic gearbox;
-- opts.ctx: see "Snapshots" above.
function drive.player(car, opts)
  opts = opts or {}
  if type(input) == "table" then input.set_context("vehicle", true) end
  return setmetatable({car = car, automatic = opts.automatic ~= false, state = state_of(opts.ctx, {}),
                       gearbox = drive.gearbox(car, opts), traction = drive.traction(car, opts)}, Player)
end

function Player:update(dt)
  if type(input) ~= "table" then return false end
  local car = self.car
  local throttle, brake = input.value("throttle"), input.value("brake")
  local controls = {throttle = throttle, brake = brake, steer = input.value("steer"),
                    handbrake = input.value("handbrake")}
  -- Brake at standstill means reverse, as in most driving games. In
  -- reverse the pedals swap: brake drives backwards and throttle brakes
  -- until the car is nearly stopped, when the gearbox takes first gear
  -- again (throttle in reverse gear must never speed the car backwards).
  local reverse = brake > 0.1 and throttle < 0.1 and car:speed() < 0.5
  if reverse or car:controls().gear == -1 then
    controls.throttle, controls.brake = brake, throttle
  end
  controls.throttle = self.traction:filter(dt, controls.throttle)
  car:set_controls(controls)
  if input.pressed("reset") then drive.upright(car) end
  -- Off the edge of the terrain the car would fall for ever: once it is
  -- off the map and 10 m below where it left it, it comes back there.
  local p, s = car:position(), self.state()
  local ground = vehicle.surface(p.x, p.z)
  if ground then
    s.last_on_map = {x = p.x, z = p.z, y = ground}
  elseif s.last_on_map and p.y < s.last_on_map.y - 10 then
    drive.rescue(car, s.last_on_map)
    if type(game) == "table" then game.message("Off the map: back at the edge", 3, "warning") end
  end
  if self.automatic then
    self.gearbox:update(dt, reverse and -1 or 1)
  else
    local g = car:controls().gear
    if input.pressed("gear_up") then car:set_controls{gear = g + 1} end
    if input.pressed("gear_down") then car:set_controls{gear = g - 1} end
  end
  return true
end

-- Puts the car at rest, upright, 0.5 m above the ground at point {x, z},
-- 4 m inside the terrain from there and facing the terrain's centre (the
-- origin), so a car that left the map drives back onto it.
function drive.rescue(car, point)
  local len = math.sqrt(point.x * point.x + point.z * point.z)
  local ux, uz = 0, 0
  if len > 1e-6 then ux, uz = -point.x / len, -point.z / len end
  local x, z = point.x + 4 * ux, point.z + 4 * uz
  local ground = vehicle.surface(x, z) or point.y
  car:reset{position = {x, ground + 0.5, z}, heading = (len > 1e-6) and math.atan(ux, uz) or 0}
end

-- Puts a car that is on its roof or stuck back on its wheels where it is:
-- upright, facing the way it faced (its forward axis seen from above),
-- at rest, with its wheels opts.lift (default 0.5) m above the highest
-- ground under it (the terrain, or any other body a vertical ray from 2 m
-- above its centre meets), so
-- it drops clear of what held it. Returns the ground point used.
function drive.upright(car, opts)
  local lift = (opts and opts.lift) or 0.5
  local p, f = car:position(), car:forward()
  local heading = (f.x * f.x + f.z * f.z > 1e-6) and math.atan(f.x, f.z) or 0
  local ground = vehicle.surface(p.x, p.z)
  local body = car:body()
  for _, hit in ipairs(world.raycast_all({p.x, p.y + 2, p.z}, {0, -1, 0}, 200)) do
    if hit.body ~= body and (not ground or hit.point.y > ground) then ground = hit.point.y end
  end
  ground = ground or p.y
  car:reset{position = {p.x, ground + lift, p.z}, heading = heading}
  return {x = p.x, y = ground, z = p.z}
end

-- Effects ----------------------------------------------------------------------------

local Effects = {}
Effects.__index = Effects

-- Tyre dust per wheel and exhaust smoke, in particles per second:
--   dust  = opts.dust_per_mps (default 40) * slip speed (m/s), on loose
--           ground (surface softness >= 0.3: grass, sand, snow, mud) twice
--           that, 0 without contact
--   smoke = opts.smoke_idle (default 4) + opts.smoke_throttle (default 60)
--           * throttle * rpm / max_rpm
-- drive.effects() spawns "base:dust" at each wheel's contact patch and
-- "base:exhaust" at the back; update() sets their rates (and the dust
-- positions) every step; self.dust[i] and self.smoke hold the rates
-- (scenarios and tests read them). Without a particles module (a build
-- without it) only the rates are computed.
function drive.effects(car, opts)
  opts = opts or {}
  local def = car:definition()
  local self = setmetatable({car = car, dust = {}, smoke = 0, max_rpm = def.engine.max_rpm,
                             rear = -def.chassis.size[3] / 2, dust_per_mps = opts.dust_per_mps or 40,
                             smoke_idle = opts.smoke_idle or 4, smoke_throttle = opts.smoke_throttle or 60}, Effects)
  -- The emitters are made here, when the scenario starts, so that a run
  -- loaded from a snapshot (which makes the scenario again, then puts the
  -- saved emitters back in their slots) finds them behind the same handles.
  if type(particles) == "table" and particles.spawn then
    self.emitters = {exhaust = particles.spawn("base:exhaust", {body = car:body(), offset = {0.3, -0.2, self.rear}},
                                               {rate = 0})}
    for i, w in ipairs(car:telemetry().wheels) do
      local p = w.position
      self.emitters[i] = particles.spawn("base:dust", {position = {p.x, p.y - w.radius, p.z}}, {rate = 0})
    end
  end
  return self
end

function Effects:update(dt)
  local car = self.car
  local t = car:telemetry()
  for i, w in ipairs(t.wheels) do
    local soft = w.surface_softness >= 0.3 and 2 or 1
    self.dust[i] = w.contact and self.dust_per_mps * w.slip_speed * soft or 0
  end
  self.smoke = self.smoke_idle + self.smoke_throttle * car:controls().throttle * t.rpm / self.max_rpm
  if self.emitters then
    -- Dust rises where the tyre meets the ground (world space, moved each
    -- step, so it passes on the wheel's velocity and stays behind the car).
    for i, w in ipairs(t.wheels) do
      local p = w.position
      self.emitters[i]:set_position({p.x, p.y - w.radius, p.z})
      self.emitters[i]:set_rate(self.dust[i])
    end
    self.emitters.exhaust:set_rate(self.smoke)
  end
end

-- Presentation ------------------------------------------------------------------------

-- The shipped models stand on their origin (the ground) with the front
-- along +Z; the body's frame is the centre of mass. At rest each axle's hub
-- hangs its static spring length (rest_length less the sag under the car's
-- weight) below full bump, and the ground is a wheel radius lower: through
-- those points (z, y), one per axle, runs the ground in the body's frame.
-- Returns where the model's origin goes in the body frame (z0, y0, below
-- the box centre) and the ground's slope dy/dz (a least squares fit, tilted
-- when the axles sag differently), so the drawn car sits where the physics
-- car is.
local function model_ground(car, def)
  local com, wheels = def.chassis.com, car:telemetry().wheels
  local n, sz, sy, szz, szy = 0, 0, 0, 0, 0
  for i, axle in ipairs(def.axles) do
    local w = wheels[2 * i - 1]
    local z = axle.position[3] - com[3]
    local y = axle.position[2] - com[2] - w.static_length - w.radius
    n, sz, sy, szz, szy = n + 1, sz + z, sy + y, szz + z * z, szy + z * y
  end
  local spread = szz - sz * sz / n
  local slope = spread > 1e-9 and (szy - sz * sy / n) / spread or 0
  local z0 = -com[3]
  return z0, sy / n + slope * (z0 - sz / n), slope
end

-- Puts the chase camera on the car (camera.set_mode; the camera key then
-- steps through chase, hood and cockpit, at the eyes and with the interior
-- the definition's view gives) and its definition's chassis mesh on the chassis body
-- (Body:set_model), each only when that API exists; returns how many of the
-- two it could do. opts.camera: the mode to start in (default "chase").
function drive.show(car, opts)
  local mode = (opts and opts.camera) or "chase"
  local done = 0
  local def = car:definition()
  -- The display mesh (wheel arches, ...) when the definition has one.
  local mesh = def.chassis.display_mesh
  if mesh == nil or mesh == "" then mesh = def.chassis.mesh end
  local body = car:body()
  local z0, y0, slope = model_ground(car, def)
  if type(camera) == "table" and camera.set_mode then
    -- The definition's view places the eyes in the drawn model's frame
    -- (origin on the ground line under its middle); here they go into the
    -- body frame, as the model is placed below.
    local view, cx = def.view, -def.chassis.com[1]
    local function body_frame(p) return {cx + p[1], y0 + p[2], z0 + p[3]} end
    local opts = {target = body, eye = body_frame(view.cockpit_eye), hood_eye = body_frame(view.hood_eye)}
    local mod = car:name():match("^([^:]+):")
    if view.open then
      camera.set_mode(mode, opts)  -- an open car: the cockpit view keeps the car's own model
    elseif view.interior then
      opts.interior = mod and (mod .. ":" .. view.interior) or view.interior
      camera.set_mode(mode, opts)
    else
      -- The base mod's generic interior, with its two dials on the face of
      -- the dashboard under the instrument hood (in the interior's frame:
      -- origin at the eye; the face is at z 0.58 m). The hood's front edge
      -- (0.22 m below the eye, 0.54 m ahead) hides what lies above the line
      -- from the eye past it: y > -0.2355 m on the face, so the dials' tops
      -- stay under that. Without the base mod, none.
      opts.interior = "base:assets/models/cockpit.obj"
      opts.speed_gauge, opts.rpm_gauge, opts.gauge_radius = {0.075, -0.285, 0.578}, {-0.075, -0.285, 0.578}, 0.045
      if not pcall(camera.set_mode, mode, opts) then
        opts.interior, opts.speed_gauge, opts.rpm_gauge, opts.gauge_radius = nil, nil, nil, nil
        camera.set_mode(mode, opts)
      end
    end
    done = done + 1
  end
  if mesh and body.set_model then
    -- The model's ground on the line through the wheels' contact points (model_ground).
    local com = def.chassis.com
    -- The mesh path is inside the vehicle's mod, which need not be the scenario's.
    local mod = car:name():match("^([^:]+):")
    body:set_model(mod and (mod .. ":" .. mesh) or mesh,
                   {offset = {-com[1], y0, z0}, rotation = {-math.atan(slope), 0, 0}})
    done = done + 1
  end
  return done
end

return drive
