-- Showroom: the project's own models on bodies and as static scenery. A
-- hatchback-shaped box (collision stays a box; the picture is the model)
-- slides down a ramp between rocks, trees, barriers, a building and a
-- checkpoint arch, followed by the chase camera. Static models get static
-- box collision bodies, so the car stops against the barrier.
--
--   tumble play base:showroom            (C cycles orbit, follow, chase, hood, cockpit)
--   tumble run base:showroom --screenshot shot.png

local M = "base:assets/models/"
local car

return {
  title = "Showroom: models on bodies, static scenery, chase camera",
  duration = 5,
  on_start = function(ctx)
    world.plane{color = {0.42, 0.48, 0.38}}
    -- The car: a 1.6 x 1.2 x 4.1 m box whose centre is 0.87 m above the model's origin.
    car = world.box{size = {1.6, 1.2, 4.1}, position = {0, 0.9, -6}, velocity = {0, 0, 12}, mass = 1100,
                    friction = 0.3}
    car:set_model(M .. "hatchback.obj", {offset = {0, -0.87, 0}})
    for _, x in ipairs({-1, 1}) do
      world.add_static_model(M .. "barrier.obj", {position = {x * 1.1, 0, 8}})
    end
    for i, p in ipairs({{-7, -4}, {6, -2}, {-6, 5}, {8, 9}, {-9, 12}}) do
      world.add_static_model(M .. "rock.obj", {position = {p[1], 0, p[2]}, rotation = {0, i, 0}, scale = 0.8 + 0.15 * i})
    end
    for i, p in ipairs({{-5, -9}, {5, -8}, {-11, 2}, {10, 3}, {-4, 14}, {6, 15}}) do
      world.add_static_model(M .. "tree.obj", {position = {p[1], 0, p[2]}, collision = "none", scale = 0.9 + 0.1 * (i % 3)})
    end
    world.add_static_model(M .. "building.obj", {position = {-14, 0, 20}})
    world.add_static_model(M .. "checkpoint_arch.obj", {position = {0, 0, 2}, collision = "none"})
    -- Eyes in the car body's frame (its centre is 0.87 m above the model's
    -- origin): the driver's seat for the cockpit, above the bonnet for hood.
    local mode = param("camera", "chase")
    local eye = mode == "hood" and {0, 0.2, 1.6} or {0.35, 0.3, -0.1}
    camera.set_mode(mode, {target = car, eye = eye, interior = M .. "cockpit.obj"})
  end,
  on_finish = function(ctx)
    -- The barriers' static boxes stopped the car before z = 8 - 0.2 - 2.05.
    -- Without them it would slide 12^2 / (2 * 0.3 * 9.81) = 24 m, to z = 18.
    expect("car stopped by the barriers", car:position().z, {min = 5.0, max = 5.8})
    expect("car still upright", car:up().y, {min = 0.9})
  end,
}
