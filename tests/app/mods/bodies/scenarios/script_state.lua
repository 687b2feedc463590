-- The Lua state a snapshot keeps (docs/snapshots.md), in one scenario whose
-- physics depends on all of it: a timer made in on_start kicks a ball with
-- a random impulse from the scenario's generator, on_update pushes the
-- boxes with math.random and a counter kept in ctx.state, and on_contact
-- counts hits in ctx.state. A run split by --save-state / --load-state must
-- end in the state hash of the run without a split (scene_state_test.cpp):
-- it does only if the timer's schedule, both generators and ctx.state are
-- restored exactly. A trigger box made in on_start lifts each box whose
-- centre enters it: a loaded run re-lifts the boxes already inside unless
-- the trigger's occupants are restored too. With --set late_timer=1 a timer
-- is also made after on_start, which a snapshot cannot hold: saving is
-- refused, naming where its function is defined; --set late_trigger=1 does
-- the same with a trigger volume, and --set late_ode=1 makes an ode.system
-- after on_start, which refuses the load.
local ball, boxes, late = nil, {}, nil

return {
  title = "Timers, random numbers and ctx.state across a snapshot",
  duration = 3,
  params = {late_timer = {default = 0, description = "1: also make a timer after on_start (saving is then refused)"},
            late_trigger = {default = 0, description = "1: also make a trigger after on_start (saving is then refused)"},
            late_ode = {default = 0, description = "1: also make an ode.system after on_start (loading is then refused)"}},
  on_start = function(ctx)
    world.plane{}
    ball = world.sphere{radius = 0.3, position = {0, 0.3, 0}}
    for i = 1, 3 do boxes[i] = world.box{size = {0.5, 0.5, 0.5}, position = {2 * i, 0.25, 0}} end
    ctx.state.pushes, ctx.state.hits, ctx.state.log = 0, 0, {}
    timer.every(0.37, function()
      ball:apply_impulse{random.float(-1, 1), random.float(0, 2), random.float(-1, 1)}
    end)
    ctx.state.entered = 0
    trigger.box{center = {4, 0.25, 0}, size = {6, 1, 6}, on_enter = function(body)
      ctx.state.entered = ctx.state.entered + 1
      body:apply_impulse{0, 0.3, 0}
    end}
  end,
  on_update = function(ctx, dt)
    if ctx.step % 7 == 0 then
      ctx.state.pushes = ctx.state.pushes + 1
      local b = boxes[ctx.state.pushes % #boxes + 1]
      b:apply_impulse{math.random() - 0.5, 0.5 * math.random(), math.random() - 0.5}
      ctx.state.log[#ctx.state.log + 1] = {step = ctx.step, x = b:position().x}
    end
    if param("late_timer") == 1 and ctx.step == 10 then
      timer.after(5, function() ball:apply_impulse{0, 1, 0} end)
    end
    if param("late_ode") == 1 and ctx.step == 10 then
      late = ode.system{state = {1, 0}, derivative = function(t, y) return {y[2], -y[1]} end}
    end
    if late then late:step(dt) end
    if param("late_trigger") == 1 and ctx.step == 10 then
      trigger.box{center = {0, 0, 0}, size = {1, 1, 1}, on_enter = function(body) end}
    end
  end,
  on_contact = function(ctx, a, b)
    ctx.state.hits = ctx.state.hits + 1
  end,
  on_finish = function(ctx)
    expect("the boxes were pushed", ctx.state.pushes, {min = 25})
    expect("bodies touched", ctx.state.hits, {min = 1})
    expect("boxes entered the trigger", ctx.state.entered, {min = 2})
    expect("the log has every push", #ctx.state.log == ctx.state.pushes)
  end,
}
