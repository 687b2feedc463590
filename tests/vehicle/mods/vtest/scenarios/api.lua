-- The Lua vehicle API as a user sees it: spawning, bad input with clear
-- errors, controls, telemetry, tuning while running, reset, remove, saves.
local drive = require "tumble.drive"
local car, effects, gain_before, v30
local function fails_with(pattern, fn, ...)
  local ok, err = pcall(fn, ...)
  return not ok and tostring(err):find(pattern, 1, true) ~= nil, err
end

return {
  duration = 3,
  on_start = function(ctx)
    local ground = world.plane{friction = 1}
    -- Softness (rolling drag) of a body's surface: hard until set, checked input.
    expect("bad softness refused with what is valid", (fails_with("finite number >= 0", vehicle.set_softness, ground, -1)))
    vehicle.set_softness(ground, 0.05)
    expect("misspelt field named with its path", (fails_with("axles[1].suspension: unknown field 'frequncy' (did you mean: frequency?)",
      vehicle.spawn, "vtest:broken")))
    expect("unknown vehicle lists the mod's vehicles", (fails_with("this mod has: broken, kart", vehicle.spawn, "vtest:nope")))
    expect("unknown mod is named", (fails_with("no mod named \"nomod\"", vehicle.spawn, "nomod:car")))
    car = vehicle.spawn("vtest:kart", {position = {0, 0, 0}})
    expect("unknown control is an error", (fails_with("unknown field 'throtle'", car.set_controls, car, {throtle = 1})))
    expect("bad tune value names the field", (fails_with("engine.max_rpm", car.tune, car, {engine = {max_rpm = -5}})))
    expect("mesh path may not leave the mod", (fails_with("leaves the mod's folder", car.tune, car, {chassis = {mesh = "../x.glb"}})))
    -- The cameras' view: eyes checked, the interior kept inside the mod, an open car without an interior.
    expect("a NaN camera eye names the field", (fails_with("view.hood_eye", car.tune, car, {view = {hood_eye = {0, 0 / 0, 1}}})))
    expect("a camera eye off the car is refused", (fails_with("view.cockpit_eye must be finite and on the car", car.tune, car,
      {view = {cockpit_eye = {0, 40, 0}}})))
    expect("interior path may not leave the mod", (fails_with("leaves the mod's folder", car.tune, car, {view = {interior = "../x.obj"}})))
    expect("an open car has no interior", (fails_with("view.interior: an open car", car.tune, car,
      {view = {open = true, interior = "x.obj"}})))
    local def = vehicle.definition("base:hatchback")
    expect("definition gives the cameras' view", def.view.hood_eye[3] > 0 and def.view.open == false)
    expect("definition has every field", math.abs(def.axles[2].suspension.frequency - 1.6) < 1e-6 and def.engine.max_rpm == 6800)
    -- Part throttle: the kart pulls without wheelspin (a spinning tyre keeps
    -- pushing at sliding friction whatever the engine does).
    car:set_controls{throttle = 0.15}
    effects = drive.effects(car)
    -- The player controller drives from the input actions (none pressed here).
    expect("player controller reads the actions", drive.player(car):update(1 / 60) == true)
    -- Another mod's car wears its own mesh (the path is inside base, not vtest).
    local parked = vehicle.spawn("base:truck", {position = {60, 0, 0}})
    expect("drive.show dresses a car from another mod", drive.show(parked), {min = 1, max = 2})
    camera.set_mode("orbit")
    car:set_controls{throttle = 0.15}
  end,
  on_update = function(ctx, dt)
    effects:update(dt)
    if ctx.step == 30 then v30 = car:speed() end
    if ctx.step == 45 then
      expect("exhaust smoke rises with throttle (particles/s)", effects.smoke, {min = 5})
    end
    if ctx.step == 60 then
      gain_before = car:speed() - v30
      local t = car:telemetry()
      expect("moving forward after 1 s of throttle (m/s)", t.speed, {min = 1.5})
      expect("four wheels report contact", #t.wheels == 4 and t.wheels[1].contact and t.wheels[4].contact)
      expect("tyres report the ground's softness and friction", math.abs(t.wheels[1].surface_softness - 0.05) < 1e-6 and t.wheels[1].surface_friction == 1)
      -- Rear drive, open differential on even ground: the rear wheels get
      -- the same drive torque, the undriven front wheels none.
      expect("driven rear wheels get drive torque (N m)", t.wheels[3].drive_torque, {min = 1})
      expect("open differential: equal torque left and right (N m)", math.abs(t.wheels[3].drive_torque - t.wheels[4].drive_torque), {max = 1e-3})
      expect("undriven front wheels get no drive torque", t.wheels[1].drive_torque == 0 and t.wheels[2].drive_torque == 0)
      expect("loads carry the weight (N)", t.wheels[1].load + t.wheels[2].load + t.wheels[3].load + t.wheels[4].load,
             {min = 300 * 9.81 * 0.8, max = 300 * 9.81 * 1.2})
      -- Tuning while running: a tenth of the torque.
      car:tune{engine = {torque = {{1000, 12}, {4000, 16}, {6500, 12}}}}
      expect("tuned value visible", car:definition().engine.torque[2][2] == 16)
    end
    if ctx.step == 90 then
      -- The same half second with a tenth of the torque gains much less speed.
      expect("tuned car accelerates less (speed gain ratio after/before)", (car:speed() - (v30 + gain_before)) / gain_before,
             {max = 0.5})
    end
    if ctx.step == 120 then
      car:reset()
      expect("reset puts the car back at rest (m/s)", math.abs(car:speed()), {max = 1e-6})
      local p = car:position()
      expect("reset puts the car back at its spawn point (m)", math.abs(p.x) + math.abs(p.z), {max = 0.5})
    end
  end,
  on_finish = function(ctx)
    save.write("api_test", {best_s = 12.5, laps = {1, 2, 3}, name = "kart", ok = true})
    local back = save.read("api_test")
    expect("save round-trips", back.best_s == 12.5 and back.laps[3] == 3 and back.name == "kart" and back.ok == true)
    expect("bad save name refused", (fails_with("must be 1 to 64 letters", save.write, "../escape", {})))
    car:remove()
    expect("removed vehicle is invalid", not car:is_valid())
    expect("removed vehicle refuses use", (fails_with("was removed", car.speed, car)))
  end,
}
