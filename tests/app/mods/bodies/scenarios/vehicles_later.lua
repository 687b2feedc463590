-- Vehicles spawned, re-tuned and removed after on_start
-- (tests/app/scene_state_test.cpp, SplitRun): a snapshot holds every
-- vehicle's definition, so a run loaded after these moments makes the cars
-- again around their chassis and ends as the run without a split.
--   0.25 s  a hatchback is spawned and drives off in first gear
--   0.40 s  a buggy is spawned, re-tuned (a lower rev limit, stiffer
--           springs) and driven in reverse
--   0.50 s  a second hatchback is spawned, and removed at 0.70 s
-- Their chassis bodies are kept in ctx.state: the expectations check that
-- both cars drove, which fails if the world does not step.
local later

return {
  title = "Vehicles spawned, re-tuned and removed after on_start",
  duration = 2,
  on_start = function(ctx)
    world.plane{}
  end,
  on_update = function(ctx, dt)
    if ctx.step == 15 then
      local car = vehicle.spawn("base:hatchback", {position = {0, 0, 0}})
      car:set_controls{throttle = 0.7, gear = 1}
      ctx.state.hatchback = car:body()
      ctx.state.hatchback_start = car:body():position().z
    elseif ctx.step == 24 then
      local buggy = vehicle.spawn("base:buggy", {position = {8, 0, 0}, heading = 0.3})
      buggy:tune{engine = {max_rpm = 8400}, axles = {[1] = {suspension = {frequency = 2.2}}}}
      buggy:set_controls{throttle = 0.5, gear = -1}
      ctx.state.buggy = buggy:body()
      ctx.state.buggy_start = buggy:body():position()
    elseif ctx.step == 30 then
      later = vehicle.spawn("base:hatchback", {position = {-8, 0, 0}})
      later:set_controls{throttle = 1, gear = 1}
    elseif ctx.step == 42 and later then
      later:remove()
    end
  end,
  on_finish = function(ctx)
    local z = ctx.state.hatchback and ctx.state.hatchback:position().z or 0
    expect("the hatchback drove forward (m)", z - (ctx.state.hatchback_start or 0), {min = 1})
    local b, b0 = ctx.state.buggy and ctx.state.buggy:position(), ctx.state.buggy_start
    local moved = (b and b0) and math.sqrt((b.x - b0.x) ^ 2 + (b.z - b0.z) ^ 2) or 0
    expect("the buggy reversed (m)", moved, {min = 0.3})
  end,
}
