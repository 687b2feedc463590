-- Every bad call below must fail with a message naming the field, and leave
-- the objects usable. Each check is an expectation (exit 0 when all hold).

local function fails_with(name, pattern, f, ...)
  local ok, err = pcall(f, ...)
  expect(name, (not ok) and tostring(err):find(pattern, 1, true) ~= nil)
  if ok or not tostring(err):find(pattern, 1, true) then print(name .. ": got " .. tostring(err)) end
end

return {
  duration = 0.1,
  on_start = function(ctx)
    -- ode.system
    fails_with("ode: state required", "state", ode.system, {derivative = function() end})
    fails_with("ode: derivative required", "derivative", ode.system, {state = {1}})
    fails_with("ode: unknown method lists valid ones", "sdirk2", ode.system,
               {state = {1}, method = "rk5", derivative = function(t, y) return {0} end})
    fails_with("ode: verlet needs an even state", "even", ode.system,
               {state = {1, 2, 3}, method = "verlet", derivative = function(t, y) return y end})
    fails_with("ode: unknown field", "valid:", ode.system, {state = {1}, derivative = function() end, colour = 1})
    local calls = 0
    local sys = ode.system{state = {1, 0}, derivative = function(t, y)
      calls = calls + 1
      if calls > 4 then error("boom in the derivative") end
      return {y[2], -y[1]}
    end}
    sys:step(0.1)  -- 4 calls (rk4)
    local before = sys:state()
    fails_with("ode: a Lua error in the derivative reaches the caller", "boom in the derivative", sys.step, sys, 0.1)
    local after = sys:state()
    expect("ode: a failed step leaves the state", before[1] == after[1] and before[2] == after[2])
    local short = ode.system{state = {1, 0}, derivative = function(t, y) return {y[2]} end}
    fails_with("ode: a short derivative names the entry", "entry 2", short.step, short, 0.1)
    local nan = ode.system{state = {1}, derivative = function(t, y) return {0 / 0} end}
    fails_with("ode: a NaN derivative is refused", "finite", nan.step, nan, 0.1)
    fails_with("ode: dt must be > 0", "dt", sys.step, sys, -1)
    expect("ode: methods lists eight", #ode.methods() == 8)

    -- deformable
    fails_with("rope: from required", "from", deformable.rope, {to = {1, 0, 0}})
    fails_with("rope: stiffness > 0", "stiffness", deformable.rope, {from = {0, 1, 0}, to = {1, 1, 0}, stiffness = -1})
    fails_with("rope: unknown field", "valid:", deformable.rope, {from = {0, 1, 0}, to = {1, 1, 0}, lenght = 2})
    fails_with("cloth: pins", "pins", deformable.cloth, {origin = {0, 1, 0}, pins = "left"})
    fails_with("cloth: columns", "columns", deformable.cloth, {origin = {0, 1, 0}, columns = 1})
    local rope = deformable.rope{from = {0, 1, 0}, to = {1, 1, 0}, segments = 4}
    fails_with("rope: particle index range", "1..5", rope.position, rope, 6)
    expect("rope: 5 particles", rope:count() == 5)
    rope:remove()
    fails_with("rope: removed", "removed", rope.count, rope)

    -- world.spring
    local ball = world.sphere{radius = 0.1, position = {0, 2, 0}}
    fails_with("spring: stiffness required", "stiffness", world.spring, {a = ball, anchor = {0, 3, 0}})
    fails_with("spring: b or anchor", "anchor", world.spring, {a = ball, stiffness = 10})
    fails_with("spring: a must be a body", "'a'", world.spring, {a = 3, anchor = {0, 3, 0}, stiffness = 10})
    local id = world.spring{a = ball, anchor = {0, 3, 0}, stiffness = 10}
    expect("spring: removed once", world.remove_spring(id) and not world.remove_spring(id))
    -- Found by the scenario fuzzer: -1e308 was converted to an integer (undefined).
    for _, bad in ipairs({-1e308, 1e308, 0.5, math.huge, 0 / 0}) do
      fails_with("spring: id " .. tostring(bad) .. " is refused", "expected a spring id", world.remove_spring, bad)
    end
    fails_with("spring: a string id is refused", "got string", world.remove_spring, tostring(id))
  end,
}
