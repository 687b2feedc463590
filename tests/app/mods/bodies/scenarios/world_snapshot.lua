-- world.snapshot() / world.restore(): try something and undo it, exactly.
-- A stack of boxes and a ball roll and settle for 0.5 s; then a snapshot is
-- taken and the world runs 0.5 s more while every pose is recorded. A kick
-- is tried, then the world is restored: the poses must be the snapshot's,
-- bit for bit, and running the same 0.5 s again must give the recorded
-- poses bit for bit (the contacts' warm starts came back too). A body made
-- after the snapshot is removed by world.restore, a sphere and a convex hull
-- removed since are made again (the hull from its polyhedron in the
-- snapshot), and so is a static model removed since (a triangle mesh, from
-- its tree and triangles in the snapshot): a ray finds it where it was.
local bodies = {}
local wedge  -- a convex hull far from the rest
local barrier  -- a static model (triangle mesh) far from the rest
local snap, first, second = nil, {}, {}
local tried = false

local function poses()
  local out = {}
  for i, b in ipairs(bodies) do
    local p, v = b:position(), b:velocity()
    out[i] = {p.x, p.y, p.z, v.x, v.y, v.z}
  end
  return out
end

local function same(a, b)
  if #a ~= #b then return false end
  for i = 1, #a do
    for k = 1, 6 do
      if a[i][k] ~= b[i][k] then return false end
    end
  end
  return true
end

local kSnapStep, kLength = 30, 30

return {
  title = "world.snapshot and world.restore",
  duration = 2.5,
  on_start = function(ctx)
    world.plane{}
    for i = 0, 4 do bodies[#bodies + 1] = world.box{size = {1, 1, 1}, position = {0, 0.5 + i * 1.0, 0}} end
    bodies[#bodies + 1] = world.sphere{radius = 0.4, position = {3, 0.4, 0}, velocity = {-2, 0, 0}}
    wedge = world.hull{points = {{0,0,0}, {1,0,0}, {0,0,1}, {1,0,1}, {0,1,0}, {0,1,1}}, position = {30, 0.5, 0}}
    barrier = world.add_static_model("base:assets/models/barrier.obj", {position = {-30, 0, 0}})
  end,
  on_update = function(ctx, dt)
    local s = ctx.step
    if s == kSnapStep then
      snap = world.snapshot()
      ctx.state.at_snapshot = poses()
      ctx.state.gravity = world.gravity().y
    elseif s > kSnapStep and s <= kSnapStep + kLength then
      first[s - kSnapStep] = poses()
    end
    if s == kSnapStep + kLength and not tried then
      tried = true
      bodies[1]:apply_impulse{0, 500, 0}
      world.set_gravity{0, -1, 0}
      world.restore(snap)
      expect("restore puts every pose and velocity back exactly", same(poses(), ctx.state.at_snapshot))
      expect("restore puts the gravity back", world.gravity().y == ctx.state.gravity)
      ctx.state.replay_from = s
    end
    if ctx.state.replay_from and s > ctx.state.replay_from and s <= ctx.state.replay_from + kLength then
      -- second pass: one step later than the first recorded the same step
      second[s - ctx.state.replay_from] = poses()
    end
  end,
  on_finish = function(ctx)
    local all = #first == kLength and #second == kLength
    for i = 1, kLength do
      if not (first[i] and second[i] and same(first[i], second[i])) then all = false end
    end
    expect("the same steps after restore give the same poses, bit for bit", all)
    -- Made since: removed again. Removed since: a sphere is made again.
    local extra = world.sphere{radius = 0.1, position = {10, 1, 0}}
    world.remove(bodies[6])
    world.restore(snap)
    expect("a body made since the snapshot is removed by restore", not extra:is_valid())
    expect("a sphere removed since is back", bodies[6]:is_valid() and same(poses(), ctx.state.at_snapshot))
    -- A hull removed since is made again from the snapshot, where it was.
    local wedgeAt = wedge:position()
    world.remove(wedge)
    world.restore(snap)
    local back = wedge:is_valid() and wedge:position()
    expect("a hull removed since is back where it was", back and back.x == wedgeAt.x and back.y == wedgeAt.y and
                                                         back.z == wedgeAt.z)
    -- A static model removed since is made again from its triangles: the
    -- same ray hits it at the same point, on its own body.
    local function hitBarrier()
      local h = world.raycast({-30, 5, 0}, {0, -1, 0}, 10)
      return h and h.body == barrier and h.point.y or nil
    end
    local top = hitBarrier()
    world.remove(barrier)
    local gone = hitBarrier()
    world.restore(snap)
    expect("a static model removed since is back, its triangles where they were",
           barrier:is_valid() and top ~= nil and gone == nil and hitBarrier() == top)
    expect("... and stepping on from it gives the same poses", same(poses(), ctx.state.at_snapshot))
    print(tostring(snap))
  end,
}
