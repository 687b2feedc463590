-- What is seen, set after on_start (tests/app/scene_state_test.cpp,
-- SnapshotPresentation): at 0.5 s a red ball and a box drawn as a barrier
-- model are made, a building is placed without collision, the camera
-- follows the ball and the sky turns to a cloudy evening; at 0.6 s a second
-- box drawn as a model is removed (its model stays attached to the dead
-- body, not drawn). A run loaded from a snapshot taken after that must look
-- as the run without a split: the snapshot holds colours, models, the
-- camera and the sky.
return {
  title = "A ball, a model, a camera and a sky set after on_start",
  duration = 2,
  on_start = function(ctx)
    world.plane{}
    for i = 0, 2 do world.box{size = {1, 1, 1}, position = {0, 0.5 + i, 0}} end
  end,
  on_update = function(ctx, dt)
    if ctx.step == 30 then
      ctx.state.ball = world.sphere{radius = 0.5, position = {-4, 0.5, 1}, velocity = {3, 0, 0}, mass = 2,
                                    color = {0.9, 0.1, 0.1}}
      local crate = world.box{size = {2, 1, 0.5}, position = {3, 0.5, -1}, color = {0.1, 0.2, 0.9}}
      crate:set_model("base:assets/models/barrier.obj")
      world.add_static_model("base:assets/models/building.obj", {position = {-3, 0, -8}, collision = "none"})
      camera.set_mode("follow", {target = ctx.state.ball, distance = 9})
      environment.set{time_of_day = 18.5, weather = "cloudy"}
      ctx.state.doomed = world.box{size = {1, 1, 1}, position = {-2, 0.5, -3}}
      ctx.state.doomed:set_model("base:assets/models/rock.obj")
    elseif ctx.step == 36 then
      world.remove(ctx.state.doomed)
    end
  end,
  on_finish = function(ctx)
    local p = ctx.state.ball and ctx.state.ball:position()
    expect("the ball rolled", p and p.x or -100, {min = -3.9})
  end,
}
