-- Playing with bodies by hand, as in the rag-doll paper's demo: drag a part
-- with the mouse (a spring from the grabbed point to the cursor), kick the
-- body under the cursor with a key, and change the time step while it runs.
-- Everything goes through the input actions of the "interact" context
-- (mods/base/bindings.lua: grab = left mouse, impulse = F, dt_up / dt_down =
-- . and ,), so players can rebind them; nothing happens headless (no
-- pointer). A scenario makes one in on_start and updates it in on_update:
--
--   local interact = require "tumble.interact"
--   local hands
--   on_start = function() hands = interact.new{kick = 6} end,
--   on_update = function(ctx, dt) hands:update() end,
--
-- Options: kick (m/s of speed the impulse gives the body, default 5),
-- reach (m, default 200), hertz (grab spring, default 4), dt_factor
-- (default 1.25), dt_min / dt_max (s, default 1/480 and 1/15).

local interact = {}
local Hands = {}
Hands.__index = Hands

-- v rotated by the inverse of unit quaternion q ({w, x, y, z}).
local function unrotate(q, v)
  local w, x, y, z = q.w, -q.x, -q.y, -q.z
  -- t = 2 (q.xyz x v); v' = v + w t + q.xyz x t
  local tx = 2 * (y * v.z - z * v.y)
  local ty = 2 * (z * v.x - x * v.z)
  local tz = 2 * (x * v.y - y * v.x)
  return {x = v.x + w * tx + (y * tz - z * ty),
          y = v.y + w * ty + (z * tx - x * tz),
          z = v.z + w * tz + (x * ty - y * tx)}
end

function interact.new(opts)
  opts = opts or {}
  input.set_context("interact", true)
  return setmetatable({kick = opts.kick or 5, reach = opts.reach or 200, hertz = opts.hertz or 4,
                       dt_factor = opts.dt_factor or 1.25, dt_min = opts.dt_min or 1 / 480,
                       dt_max = opts.dt_max or 1 / 15}, Hands)
end

-- Call once per on_update. Returns the body held, if any.
function Hands:update()
  if input.pressed("dt_up") then world.set_dt(math.min(world.dt() * self.dt_factor, self.dt_max)) end
  if input.pressed("dt_down") then world.set_dt(math.max(world.dt() / self.dt_factor, self.dt_min)) end
  local o, d = input.pointer_ray()
  if not o then return nil end
  if self.grab and (not input.down("grab") or not self.body:is_valid()) then
    if self.grab:is_valid() then self.grab:release() end
    self.grab, self.body = nil, nil
  end
  if input.pressed("grab") and not self.grab then
    local hit = world.raycast(o, d, self.reach)
    if hit and hit.body:is_valid() and hit.body:mass() > 0 then
      local p, c = hit.point, hit.body:position()
      local rel = unrotate(hit.body:orientation(), {x = p.x - c.x, y = p.y - c.y, z = p.z - c.z})
      self.body, self.distance = hit.body, hit.distance
      self.grab = world.grab(hit.body, {rel.x, rel.y, rel.z}, {p.x, p.y, p.z}, self.hertz)
    end
  end
  if self.grab then
    -- The cursor's point at the distance it was grabbed at.
    self.grab:set_target({o.x + d.x * self.distance, o.y + d.y * self.distance, o.z + d.z * self.distance})
  end
  if input.pressed("impulse") then
    local hit = world.raycast(o, d, self.reach)
    if hit and hit.body:is_valid() and hit.body:mass() > 0 then
      local j = hit.body:mass() * self.kick
      hit.body:apply_impulse({d.x * j, d.y * j, d.z * j}, {hit.point.x, hit.point.y, hit.point.z})
    end
  end
  return self.body
end

return interact
