// world.cylinder from Lua: what a modder sees - the body's mass and inertia,
// rolling, the shape in compounds and queries, and bad definitions refused
// with the field named.
#include "script_fixture.h"

namespace tumble::test {

class CylinderApi : public ScriptTest {};

TEST_F(CylinderApi, BadDefinitionsAreRefusedNamingTheField) {
  auto host = load(R"(
    local function refused(fn, def, needle)
      local ok, err = pcall(fn, def)
      return (not ok) and tostring(err):find(needle, 1, true) ~= nil, tostring(err)
    end
    return {on_start = function()
      local ok, msg = refused(world.cylinder, {radius = 0}, "radius")
      expect("zero radius: " .. msg, ok)
      ok, msg = refused(world.cylinder, {radius = 0/0}, "radius")
      expect("NaN radius: " .. msg, ok)
      ok, msg = refused(world.cylinder, {height = -1}, "half_height")
      expect("negative height: " .. msg, ok)
      ok, msg = refused(world.cylinder, {radius = "big"}, "radius")
      expect("radius not a number: " .. msg, ok)
      ok, msg = refused(world.cylinder, {radius = 0.3, heigth = 1}, "unknown field 'heigth'")
      expect("typo: " .. msg, ok)
      ok, msg = refused(world.cylinder, {mass = -2}, "mass")
      expect("negative mass: " .. msg, ok)
      ok, msg = refused(world.cylinder, {center_of_mass = {0, 0, 2}, height = 1}, "center_of_mass")
      expect("centre of mass outside: " .. msg, ok)
      ok, msg = refused(world.compound, {children = {{shape = "cylinder", radius = -1}}}, "radius")
      expect("bad child: " .. msg, ok)
      expect("nothing was created", world.body_count(), {min = 0, max = 0})
    end})");
  run(*host, 1);
  expectAllHeld(*host);
}

TEST_F(CylinderApi, MassInertiaAndRollingDownASlope) {
  // A 2 kg cylinder of radius 0.25 m and height 0.6 m: I_axis = m r^2 / 2,
  // I_across = m (3 r^2 + h^2) / 12; on a 20 degree slope it rolls at
  // g sin / (1 + 1/2).
  auto host = load(R"(
    local c, v0
    local theta = math.rad(20)
    return {
      on_start = function()
        world.box{size = {120, 2, 20}, rotation = {0, 0, -theta}, type = "static", friction = 1}
        local down = {math.cos(theta), -math.sin(theta)}
        local up = {math.sin(theta), math.cos(theta)}
        c = world.cylinder{radius = 0.25, height = 0.6, mass = 2, friction = 1,
                           rotation = {math.pi / 2, 0, 0},  -- axis along z, across the slope
                           position = {-20 * down[1] + 1.25 * up[1], -20 * down[2] + 1.25 * up[2], 0}}
        expect("mass, kg", c:mass(), {min = 1.9999, max = 2.0001})
        local I = c:inertia()
        expect("inertia about the axis, kg m^2", I.y, {min = 0.0625 - 1e-5, max = 0.0625 + 1e-5})
        expect("inertia across, kg m^2", I.x, {min = 2 * (3 * 0.0625 + 0.36) / 12 - 1e-5, max = 2 * (3 * 0.0625 + 0.36) / 12 + 1e-5})
      end,
      on_update = function(ctx, dt)
        if ctx.time >= 0.25 and not v0 then v0 = c:velocity() end
      end,
      on_finish = function(ctx)
        local v = c:velocity()
        local speed0 = math.sqrt(v0.x ^ 2 + v0.y ^ 2)
        local speed = math.sqrt(v.x ^ 2 + v.y ^ 2)
        local a = (speed - speed0) / (ctx.time - 0.25)
        local expected = 9.80665 * math.sin(theta) / 1.5
        expect("acceleration, m/s^2", a, {min = expected * 0.99, max = expected * 1.01})
      end,
    })");
  run(*host, 135);
  expectAllHeld(*host);
}

TEST_F(CylinderApi, CompoundChildrenAndQueries) {
  auto host = load(R"(
    return {on_start = function()
      world.plane{}
      local axle = world.compound{children = {
          {shape = "cylinder", radius = 0.4, height = 0.2, position = {0, 0, -0.5}, rotation = {math.pi / 2, 0, 0}},
          {shape = "cylinder", radius = 0.4, half_height = 0.1, position = {0, 0, 0.5}, rotation = {math.pi / 2, 0, 0}},
          {shape = "box", size = {0.1, 0.1, 1}},
        }, position = {0, 2, 0}}
      expect("compound made", axle ~= nil)
      local drum = world.cylinder{radius = 0.5, height = 2, position = {5, 1, 0}, type = "static"}
      local hits = world.overlap{shape = "cylinder", radius = 0.2, height = 0.2, position = {5, 2.05, 0}}
      expect("overlap finds the drum", #hits, {min = 1, max = 1})
      local hit = world.shape_cast{shape = "sphere", radius = 0.1, position = {2, 1, 0}, direction = {1, 0, 0}, max_distance = 10}
      expect("sphere cast stops at the drum's side, m", hit and hit.distance or -1, {min = 2.39, max = 2.41})
    end})");
  run(*host, 1);
  expectAllHeld(*host);
}

}  // namespace tumble::test
