-- Static models on a terrain: each with a collision body (its mesh, the
-- default) goes into the terrain's tree of static objects
-- (tests/app/scene_models_test.cpp checks the registry); collision = "none"
-- makes no body and nothing to register.
return {
  duration = 0.2,
  terrain = {generate = 3, size = 129},
  on_start = function()
    world.add_static_model("base:assets/models/rock.obj", {position = {20, 0, 30}})
    world.add_static_model("base:assets/models/building.obj", {position = {60, 0, 60}, rotation = {0, 0.7, 0}})
    world.add_static_model("base:assets/models/tree.obj", {position = {40, 0, 40}, collision = "none"})
  end,
}
