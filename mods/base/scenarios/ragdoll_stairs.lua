-- A rag-doll tumbling down a staircase of static boxes: it gets
-- to the bottom in one piece and comes to rest there.
--
--   tumble run base:ragdoll_stairs --set physics.joint_solver=impulse
--   tumble play base:ragdoll_stairs --set steps=12
--
-- Steps of 0.3 m rise and 0.45 m tread go down along +x from the top
-- landing; the doll stands on the landing's edge leaning forward and is
-- given a push (2.5 m/s) down the stairs.

local RISE, TREAD, WIDTH = 0.3, 0.45, 2.0  -- m

-- While playing: drag a part with the mouse, F kicks the part under the
-- cursor, '.' and ',' change the time step (scripts/tumble/interact.lua).
local interact = require "tumble.interact"
local hands

local scenario = {
  title = "Rag-doll down the stairs",
  duration = 10,  -- seconds, when run without --seconds/--steps
  -- Joints solved with the contacts (the impulse solver); --set physics.joint_solver=lagrange tries the other.
  joint_solver = "impulse",
}

local doll
local steps

function scenario.on_start(ctx)
  hands = interact.new{}
  world.plane{friction = 0.6, color = {0.55, 0.57, 0.6}}
  steps = math.floor(param("steps", 8))
  local height = steps * RISE
  -- Step i (1 = top) is a box from the ground up to its tread, at x = i * TREAD.
  for i = 1, steps do
    local top = height - (i - 1) * RISE
    world.box{type = "static", size = {TREAD, top, WIDTH}, position = {(i - 0.5) * TREAD, top / 2, 0},
              friction = 0.6, color = {0.7, 0.62 - 0.02 * i, 0.5}}
  end
  -- The landing at the top, behind step 1.
  world.box{type = "static", size = {1.5, height, WIDTH}, position = {-0.75, height / 2, 0}, friction = 0.6,
            color = {0.7, 0.64, 0.5}}
  -- Standing on the landing's edge, facing +x (the model faces +z: a
  -- quarter turn about y), leaning 0.3 rad forward (about -z).
  doll = spawn_ragdoll{position = {-0.25, height + 0.01, 0}, height = 1.75, mass = 75, rotation = {0, math.pi / 2, 0}}
  for _, part in pairs(doll) do
    local v = part:velocity()
    part:set_velocity({2.5, v.y, v.z})
  end
end

function scenario.on_update(ctx, dt)
  hands:update()
end

function scenario.on_finish(ctx)
  local fastest, finite = 0, 1
  for _, part in pairs(doll) do
    local p = part:position()
    if p.x ~= p.x or p.y ~= p.y or math.abs(p.y) > 1e6 then finite = 0 end
    fastest = math.max(fastest, part:speed())
  end
  local _, worst = joints_error()
  local pelvis = doll.pelvis:position()
  expect("every body finite", finite, {min = 1})
  -- It went down: the pelvis ends below the middle of the stairs (m).
  expect("tumbled down", pelvis.y, {max = steps * RISE / 2})
  expect("went forward", pelvis.x, {min = steps * TREAD / 2})
  -- Joints hold (m): largest anchor separation of the whole run.
  expect("joints hold", worst, {max = param("max_error", 0.05)})
  expect("all parts at rest", fastest, {max = 0.05})
end

return scenario
