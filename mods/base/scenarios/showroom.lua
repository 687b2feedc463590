-- Showroom: the project's own models on bodies and as static scenery among
-- rocks, trees, barriers, a building and a checkpoint arch, followed by the
-- chase camera. The player drives a car (drive.player; --set car=MOD:NAME,
-- the hatchback by default) between them.
-- With --set autopilot=1 nobody drives: a hatchback-shaped box (collision
-- stays a box; the picture is the model) slides towards the barriers
-- instead; static models get static box collision bodies, so it stops
-- against them (what the headless tests check).
--
--   tumble play base:showroom            (C cycles orbit, follow, chase, hood, cockpit)
--   tumble play base:showroom --set ground=checker   (the lab floor instead of grass)
--   tumble run base:showroom --set autopilot=1 --screenshot shot.png

local drive = require "tumble.drive"

local M = "base:assets/models/"
local car, player
local settle_y0  -- the car body's height at the start (player mode), m
local sliding = param("autopilot", 0) ~= 0

return {
  title = "Showroom: models on bodies, static scenery, chase camera",
  duration = 5,
  on_start = function(ctx)
    -- The sky (drawn only): --set time_of_day=H, --set weather=cloudy|storm.
    environment.set{time_of_day = param("time_of_day", 15.0), weather = param("weather", "clear"), clouds = 0.3}
    -- The ground: --set ground=checker (the lab floor) or any world.plane texture.
    world.plane{texture = param("ground", "grass")}
    if sliding then
      -- The car: a 1.6 x 1.2 x 4.1 m box whose centre is 0.87 m above the model's origin.
      car = world.box{size = {1.6, 1.2, 4.1}, position = {0, 0.9, -6}, velocity = {0, 0, 12}, mass = 1100,
                      friction = 0.3}
      car:set_model(M .. "hatchback.obj", {offset = {0, -0.87, 0}})
    else
      car = vehicle.spawn(param("car", "base:hatchback"), {position = {0, 0, -6}, heading = 0})
      player = drive.player(car, {ctx = ctx})
      settle_y0 = car:body():position().y
    end
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
    local mode = param("camera", "chase")
    if sliding then
      -- Eyes in the car body's frame (its centre is 0.87 m above the model's
      -- origin): the driver's seat for the cockpit, above the bonnet for hood.
      local eye = mode == "hood" and {0, 0.2, 1.6} or {0.35, 0.3, -0.1}
      camera.set_mode(mode, {target = car, eye = eye, interior = M .. "cockpit.obj"})
    else
      drive.show(car, {camera = mode})  -- the camera, the model, the cockpit's eye and interior
    end
  end,
  on_update = function(ctx, dt)
    if player then player:update(dt) end
  end,
  on_finish = function(ctx)
    if not sliding then
      expect("car still upright", car:body():up().y, {min = 0.5})
      -- Spawned with its wheels on the ground and nobody driving, the car
      -- finds the height where its springs carry its weight (measured: its
      -- body rises 1 cm); a world that never steps leaves it where it was.
      expect("car settled onto its springs (height change, m)", math.abs(settle_y0 - car:body():position().y), {min = 0.001})
      return
    end
    -- The barriers' static boxes stopped the car before z = 8 - 0.2 - 2.05.
    -- Without them it would slide 12^2 / (2 * 0.3 * 9.81) = 24 m, to z = 18.
    expect("car stopped by the barriers", car:position().z, {min = 5.0, max = 5.8})
    expect("car still upright", car:up().y, {min = 0.9})
  end,
}
