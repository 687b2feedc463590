-- A hanging chain of N links: released at 60 degrees from the
-- vertical it swings without coming apart and without gaining energy.
--
--   tumble run base:chain --set links=100 --set physics.joint_solver=impulse
--   tumble run base:chain --set grow=5     -- adds 5 links while it swings
--
-- Links are 0.25 m boxes of 0.5 kg joined by ball joints at their ends; the
-- top one hangs from a world anchor at y = 1 + N * 0.25 m. Ball joints have
-- no friction and the chain touches nothing, so gravity is the only work
-- done: the energy may only fall (the solvers' damping), never rise.
-- scenario.actions.more_links / fewer_links add or remove the bottom link
-- while it runs (for input bindings; `grow` calls more_links on a timer).

local L = 0.25     -- link length, m
local MASS = 0.5   -- kg
local ANGLE = math.rad(60)

-- While playing: ']' / '[' add or remove the bottom link, drag a link with
-- the mouse, F kicks it, '.' and ',' change the time step (the "interact"
-- actions in mods/base/bindings.lua; scripts/tumble/interact.lua).
local interact = require "tumble.interact"
local hands

local scenario = {
  title = "Chain: N links swinging from a world anchor",
  duration = 6,  -- seconds, when run without --seconds/--steps
  -- Joints solved with the contacts (the impulse solver); --set physics.joint_solver=lagrange tries the other.
  joint_solver = "impulse",
  actions = {},
}

local links, joints = {}, {}
local top, dir
local e0, emax = 0, 0
local added = 0  -- work done on the chain by adding links (their energy), J
local grab, target  -- --set grab=1
local swing_min_x = math.huge  -- the bottom link's least x (m); it starts at x > 0

local function linkEnergy(b)
  local p = b:position()
  return b:kinetic_energy() + MASS * 9.81 * p.y
end

local function chainEnergy()
  local e = 0
  for _, b in ipairs(links) do e = e + linkEnergy(b) end
  return e
end

-- Adds a link below the last one, along the last link's direction, at rest.
function scenario.actions.more_links()
  local n = #links
  local anchor
  if n == 0 then
    anchor = top
  else
    local last = links[n]:position()
    local up = links[n]:up()  -- the link's own +y, pointing to its top joint
    anchor = {x = last.x - up.x * L / 2, y = last.y - up.y * L / 2, z = last.z - up.z * L / 2}
  end
  local d = n == 0 and dir or links[n]:up()
  local sign = n == 0 and 1 or -1
  local center = {anchor.x + sign * d.x * L / 2, anchor.y + sign * d.y * L / 2, anchor.z + sign * d.z * L / 2}
  -- Same orientation as the link above (the first: rotated by ANGLE about z,
  -- so that its +y, its top, points back up the chain).
  local link = world.box{size = {0.1, L, 0.1}, position = center, mass = MASS,
                         orientation = n == 0 and {w = math.cos(ANGLE / 2), x = 0, y = 0, z = math.sin(ANGLE / 2)}
                                                or links[n]:orientation(),
                         color = {0.8, 0.55 + 0.3 * (n % 2), 0.2}}
  joints[n + 1] = world.joint{type = "ball", a = link, b = links[n], anchor = {anchor.x, anchor.y, anchor.z}}
  links[n + 1] = link
  if n > 0 then added = added + linkEnergy(link) end
end

-- Removes the bottom link (its joint goes with it).
function scenario.actions.fewer_links()
  local n = #links
  if n <= 1 then return end
  added = added - linkEnergy(links[n])
  world.remove(links[n])
  links[n], joints[n] = nil, nil
end

function scenario.on_start(ctx)
  hands = interact.new{}
  local n = math.floor(param("links", 10))
  top = {x = 0, y = 1 + n * L, z = 0}
  -- Released at ANGLE from the vertical, in the x-y plane.
  dir = {x = math.sin(ANGLE), y = -math.cos(ANGLE), z = 0}
  for _ = 1, n do scenario.actions.more_links() end
  e0 = chainEnergy()
  emax = e0
  local grow = math.floor(param("grow", 0))
  for i = 1, grow do timer.after(0.5 * i, scenario.actions.more_links) end
  -- --set grab=1: drag the bottom link's lower end to a point the chain can
  -- reach (what the mouse does in play), released never.
  if param("grab", 0) ~= 0 then
    local len = n * L
    target = {top.x + 0.6 * len, top.y - 0.6 * len, 0}
    grab = world.grab(links[n], {0, -L / 2, 0}, {top.x, top.y - len, 0})
    timer.after(0.5, function() grab:set_target(target) end)
  end
  -- --set dt=H: change the step to H seconds after 1 s (while running).
  if param("dt", 0) > 0 then timer.after(1, function() world.set_dt(param("dt", 0)) end) end
end

function scenario.on_update(ctx, dt)
  hands:update()
  if input.pressed("more_links") then scenario.actions.more_links() end
  if input.pressed("fewer_links") and scenario.actions.fewer_links then scenario.actions.fewer_links() end
  emax = math.max(emax, chainEnergy() - added)
  swing_min_x = math.min(swing_min_x, links[#links]:position().x)
end

function scenario.on_finish(ctx)
  local _, worst = joints_error()
  local finite = 1
  for _, b in ipairs(links) do
    local p = b:position()
    if p.x ~= p.x or math.abs(p.y) > 1e6 then finite = 0 end
  end
  local scale = #links * MASS * 9.81 * #links * L  -- m g L of the whole chain, J
  expect("every link finite", finite, {min = 1})
  if grab then
    -- The grabbed point (the bottom link's lower end) is at the target (m),
    -- give or take the grab spring's stretch under the chain's pull (its
    -- stiffness follows the link's mass: 316 N/m for 0.5 kg at 4 Hz).
    local p, up = links[#links]:position(), links[#links]:up()
    local e = {p.x - up.x * L / 2 - target[1], p.y - up.y * L / 2 - target[2], p.z - up.z * L / 2 - target[3]}
    expect("grabbed end at the target", math.sqrt(e[1] ^ 2 + e[2] ^ 2 + e[3] ^ 2), {max = 0.1})
  end
  if param("dt", 0) > 0 then expect("step changed while running", world.dt(), {min = param("dt", 0) * 0.999, max = param("dt", 0) * 1.001}) end
  expect("links", #links, {min = math.floor(param("links", 10)) + math.floor(param("grow", 0))})
  -- Joints hold (m): the largest anchor separation seen in the whole run.
  expect("joints hold", worst, {max = param("max_error", 0.05)})
  -- No energy from nowhere: the largest gain over the start, relative to m g L.
  if not grab then expect("energy does not grow", (emax - e0) / scale, {max = 0.002}) end
  -- It swings (m): released at 60 degrees on the +x side, the bottom link
  -- passes under the anchor to the -x side in the first swing (it starts at
  -- x = 0.87 of the chain's length; a chain that does not move stays there).
  if not grab then expect("bottom link swung past the vertical (least x - anchor x)", swing_min_x - top.x, {max = 0}) end
end

return scenario
