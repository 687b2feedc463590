// Hulls, compounds and shape queries from Lua: what a modder sees, bad
// arguments included. Each test is a small scenario against a real world.
#include "script_fixture.h"

namespace tumble::test {

class ShapeApi : public ScriptTest {};

TEST_F(ShapeApi, BadHullAndCompoundArgumentsAreRefusedWithTheReason) {
  auto host = load(R"(
    local function refused(fn, def, needle)
      local ok, err = pcall(fn, def)
      return (not ok) and tostring(err):find(needle, 1, true) ~= nil, tostring(err)
    end
    local cube = {{0,0,0}, {1,0,0}, {0,1,0}, {0,0,1}, {1,1,1}}
    return {on_start = function()
      local ok, msg = refused(world.hull, {points = {{0,0,0}, {1,0,0}, {0,1,0}}}, "at least 4 points")
      expect("too few points: " .. msg, ok)
      ok, msg = refused(world.hull, {points = {{0,0,0}, {1,0,0}, {0,0,1}, {1,0,1}}}, "coplanar")
      expect("coplanar points: " .. msg, ok)
      ok, msg = refused(world.hull, {points = {{0,0,0}, {1,0,0}, {0,1,0}, {0,0,0/0}}}, "point 4")
      expect("NaN coordinate names the point: " .. msg, ok)
      ok, msg = refused(world.hull, {points = cube, mass = 0}, "'mass' must be > 0")
      expect("zero mass: " .. msg, ok)
      ok, msg = refused(world.hull, {}, "points")
      expect("no points: " .. msg, ok)
      ok, msg = refused(world.compound, {children = {}}, "at least one child")
      expect("no children: " .. msg, ok)
      ok, msg = refused(world.compound, {children = {{shape = "box"}, {shape = "cone"}}}, "child 2")
      expect("unknown child shape names the child: " .. msg, ok)
      ok, msg = refused(world.compound, {children = {{shape = "sphere", radius = -1}}}, "radius")
      expect("negative radius: " .. msg, ok)
      ok, msg = refused(world.compound, {children = {{shape = "box", colour = {1, 0, 0}}}}, "unknown field 'colour'")
      expect("typo in a child: " .. msg, ok)
      ok, msg = refused(world.shape_cast, {shape = "sphere", radius = 1}, "direction")
      expect("shape_cast without a direction: " .. msg, ok)
      ok, msg = refused(world.overlap, {shape = "plane"}, "shape")
      expect("overlap with a plane: " .. msg, ok)
      expect("nothing was created", world.body_count(), {min = 0, max = 0})
    end})");
  run(*host, 1);
  expectAllHeld(*host);
}

TEST_F(ShapeApi, HullBodySitsAtItsCentroidAndRestsOnTheGround) {
  auto host = load(R"(
    local hull
    return {
      on_start = function()
        world.plane{}
        -- Unit cube with its corner at the frame origin, placed at (0, 2, 0):
        -- its centroid (the body position) is at (0.5, 2.5, 0.5).
        local pts = {}
        for i = 0, 7 do pts[#pts + 1] = {i % 2, math.floor(i / 2) % 2, math.floor(i / 4)} end
        hull = world.hull{points = pts, position = {0, 2, 0}, density = 500}
        local p = hull:position()
        expect("centroid x, m", p.x, {min = 0.4999, max = 0.5001})
        expect("centroid y, m", p.y, {min = 2.4999, max = 2.5001})
        expect("mass = density x volume, kg", hull:mass(), {min = 499.9, max = 500.1})
        -- Cube inertia m a^2 / 6 about every axis.
        expect("inertia, kg m^2", hull:inertia().y, {min = 500 / 6 - 0.01, max = 500 / 6 + 0.01})
      end,
      on_finish = function()
        expect("rests with its centre 0.5 m up, m", hull:position().y, {min = 0.49, max = 0.51})
      end,
    })");
  run(*host, 180);
  expectAllHeld(*host);
}

TEST_F(ShapeApi, CompoundQueriesAndCasts) {
  auto host = load(R"(
    local t
    return {on_start = function()
      world.plane{}
      t = world.compound{children = {
            {shape = "box", size = {2, 0.2, 0.2}},
            {shape = "sphere", radius = 0.3, position = {0, 0, 1}},
            {shape = "hull", points = {{-0.2, 0, -0.2}, {0.2, 0, -0.2}, {0, 0, 0.2}, {0, 0.4, 0}}, position = {1, 0.1, 0}},
          }, position = {0, 3, 0}, type = "static"}
      -- The overlap query finds the compound through its sphere child only.
      expect("overlap at the sphere child", #world.overlap{shape = "sphere", radius = 0.1, position = {0, 3, 1.35}}, {min = 1, max = 1})
      expect("no overlap beside it", #world.overlap{shape = "sphere", radius = 0.1, position = {0, 3, 1.45}}, {min = 0, max = 0})
      -- A sphere cast up from the ground under the bar's end stops under the bar (y = 2.9).
      local hit = world.shape_cast{shape = "sphere", radius = 0.25, position = {-0.8, 0.5, 0}, direction = {0, 1, 0}, max_distance = 10}
      expect("cast hits the compound", hit ~= nil and hit.body == t)
      expect("cast distance, m", hit and hit.distance or -1, {min = 2.9 - 0.25 - 0.5 - 0.003, max = 2.9 - 0.25 - 0.5 + 0.001})
      expect("normal points back down", hit and hit.normal.y or 0, {max = -0.99})
      -- Cast down onto the ground from beside the compound: the plane body.
      local down = world.shape_cast{shape = "box", size = {0.4, 0.4, 0.4}, position = {3, 2, 0}, direction = {0, -1, 0}}
      expect("box cast onto the ground, m", down and down.distance or -1, {min = 1.797, max = 1.801})
      expect("a miss returns nil", world.shape_cast{shape = "sphere", radius = 0.2, position = {5, 1, 0}, direction = {1, 0, 0}, max_distance = 3} == nil)
    end})");
  run(*host, 1);
  expectAllHeld(*host);
}

}  // namespace tumble::test
