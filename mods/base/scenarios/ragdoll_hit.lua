-- A heavy box at speed hits a standing rag-doll: the doll is
-- knocked over and thrown, the joints hold, momentum goes where it should.
--
--   tumble run base:ragdoll_hit --set physics.joint_solver=impulse --set speed=12
--
-- A 300 kg box (0.6 m cube) slides along the ground at `speed` (m/s,
-- default 8) towards a 75 kg rag-doll standing at the origin, hitting it at
-- hip and chest height. The box is frictionless, so until it hits only the
-- doll can slow it: just after the hit the doll has taken momentum (it moves
-- along +x) and the box has slowed, by no more than the doll could take.

-- While playing: drag a part with the mouse, F kicks the part under the
-- cursor, '.' and ',' change the time step (scripts/tumble/interact.lua).
local interact = require "tumble.interact"
local hands

local scenario = {
  title = "Rag-doll hit by a heavy box",
  duration = 5,  -- seconds, when run without --seconds/--steps
  -- Joints solved with the contacts (the impulse solver); --set physics.joint_solver=lagrange tries the other.
  joint_solver = "impulse",
}

local doll, box
local speed
local BOX_MASS = 300  -- kg

function scenario.on_start(ctx)
  hands = interact.new{}
  world.plane{friction = 0.6, color = {0.55, 0.57, 0.6}}
  speed = param("speed", 8)
  doll = spawn_ragdoll{position = {0, 0.005, 0}, height = 1.75, mass = 75}
  box = world.box{size = {0.6, 0.6, 0.6}, position = {-3, 0.9, 0}, velocity = {speed, 0, 0}, mass = BOX_MASS,
                  friction = 0, color = {0.8, 0.3, 0.2}}
  -- The box flies level (gravity would drop it 0.2 m on its way); it is
  -- held up by nothing, so give it the time to arrive: (3 - 0.3) / speed s.
  timer.after(0.5, function()
    local px = 0
    for _, part in pairs(doll) do px = px + part:mass() * part:velocity().x end
    -- In ctx.state, so that a run loaded from a snapshot still has it.
    ctx.state.hit = {dollMomentum = px, boxSpeed = box:velocity().x}
  end)
end

function scenario.on_update(ctx, dt)
  hands:update()
end

function scenario.on_finish(ctx)
  local finite = 1
  for _, part in pairs(doll) do
    local p = part:position()
    if p.x ~= p.x or math.abs(p.y) > 1e6 then finite = 0 end
  end
  local _, worst = joints_error()
  local hitCheck = ctx.state.hit or {}
  expect("every body finite", finite, {min = 1})
  -- Knocked over: the head ends near the ground (m).
  expect("knocked over", doll.head:position().y, {max = 0.6})
  -- Half a second in: the doll moves forward with momentum (kg m/s), and the
  -- box was slowed by the hit but not below what a perfectly plastic hit
  -- with the whole doll leaves, M v / (M + m), less what the ground can
  -- take from the doll through its feet in those 0.5 s (friction 0.6 of its
  -- weight: 0.6 m g 0.5 s = 221 N s, which the doll may pass back to the
  -- box): (M v - 0.6 m g 0.5) / (M + m). The box is frictionless and the
  -- doll is the only thing it touches.
  expect("doll pushed forward", hitCheck.dollMomentum or 0, {min = 0.2 * 75 * speed})
  expect("box slowed", hitCheck.boxSpeed or speed,
         {max = 0.99 * speed, min = (BOX_MASS * speed - 0.6 * 75 * 9.81 * 0.5) / (BOX_MASS + 75)})
  expect("joints hold", worst, {max = param("max_error", 0.05)})
end

return scenario
