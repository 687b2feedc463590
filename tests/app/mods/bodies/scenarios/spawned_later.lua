-- Bodies spawned after on_start (tests/app/scene_state_test.cpp): a ball is
-- shot at a stack every half second, its handle kept in ctx.state. A
-- snapshot holds each ball's size, so a run loaded after the shots makes
-- them again and ends as the run without a split. With --set hull=1 a
-- wedge (a convex hull) is dropped at 0.75 s and a hammer (a compound of a
-- box and a hull) at 0.9 s: a snapshot holds their polyhedra and children,
-- so a run loaded after that makes them again too. With --set mesh=1 a
-- static model (a barrier, a triangle mesh) is placed across the balls'
-- path at 0.75 s: the later balls hit it, and a snapshot holds its tree
-- and triangles, so a run loaded after that makes it again too.
return {
  title = "Balls shot at a stack after on_start",
  duration = 3,
  params = {
    hull = {default = 0, description = "1: also drop a convex-hull wedge at 0.75 s and a compound hammer at 0.9 s"},
    mesh = {default = 0, description = "1: also place a static model across the balls' path at 0.75 s"},
  },
  on_start = function(ctx)
    world.plane{}
    for i = 0, 3 do world.box{size = {1, 1, 1}, position = {0, 0.5 + i, 0}} end
    ctx.state.balls = {}
  end,
  on_update = function(ctx, dt)
    if ctx.step % 30 == 0 and ctx.step > 0 then
      local n = #ctx.state.balls + 1
      ctx.state.balls[n] = world.sphere{radius = 0.2, position = {-6, 0.5 + 0.4 * (n % 4), 0}, velocity = {12, 2, 0},
                                        mass = 2}
    end
    if param("hull") == 1 and ctx.step == 45 then
      world.hull{points = {{0,0,0}, {1,0,0}, {0,0,1}, {1,0,1}, {0,1,0}, {0,1,1}}, position = {3, 2, 0}}
    end
    if param("hull") == 1 and ctx.step == 54 then
      world.compound{children = {
          {shape = "box", size = {0.2, 1.2, 0.2}},
          {shape = "hull", points = {{-0.3,0,-0.2}, {0.3,0,-0.2}, {-0.3,0,0.2}, {0.3,0,0.2}, {0,0.4,0}}, position = {0, 0.6, 0}},
        }, position = {1.5, 3, 0.5}, angular_velocity = {0, 2, 5}}
    end
    if param("mesh") == 1 and ctx.step == 45 then
      world.add_static_model("base:assets/models/barrier.obj", {position = {-3, 0, 0}, rotation = {0, math.pi / 2, 0}})
    end
  end,
  on_finish = function(ctx)
    local moved = 0
    for _, b in ipairs(ctx.state.balls) do
      local p = b:position()
      if p.x == p.x and p.x > -5 then moved = moved + 1 end
    end
    expect("every ball flew", moved, {min = #ctx.state.balls, max = #ctx.state.balls})
    expect("balls were shot", #ctx.state.balls, {min = 5})
  end,
}
