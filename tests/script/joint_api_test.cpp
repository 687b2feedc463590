// The joint API from Lua (bind_joint.cpp): world.joint with a hinge motor,
// Joint:set_motor, a breakable joint, switching joint solvers while running,
// and bad definitions refused with the field named.
#include <cmath>

#include "script_fixture.h"

namespace tumble::test {

class JointApi : public ScriptTest {};

TEST_F(JointApi, HingeMotorSpinsAWheelAtItsSpeedUnderBothSolvers) {
  for (const char* solver : {"lagrange", "impulse"}) {
    auto host = load(std::string(R"(
      local wheel, hinge
      return {
        joint_solver = ")") + solver + R"(",
        on_start = function()
          world.set_gravity({0, 0, 0})
          wheel = world.box{size = {0.6, 0.6, 0.1}, position = {0, 1, 0}, mass = 3}
          -- b = the world: the hinge angle is the world's frame relative to
          -- the wheel, so motor speed -3 spins the wheel at +3 rad/s about z.
          hinge = world.joint{type = "hinge", a = wheel, anchor = {0, 1, 0}, axis = {0, 0, 1},
                              motor_speed = -3, max_motor_torque = 20}
          timer.after(1, function() hinge:set_motor(0, 20) end)
        end,
        on_update = function(ctx)
          if ctx.time > 0.9 and ctx.time < 0.95 then expect("spinning", wheel:angular_velocity().z, {min = 2.9, max = 3.1}) end
        end,
        on_finish = function()
          expect("stopped by the motor", math.abs(wheel:angular_velocity().z), {max = 0.05})
          expect("no wobble", math.abs(wheel:angular_velocity().x) + math.abs(wheel:angular_velocity().y), {max = 1e-3})
          expect("solver", world.joint_solver() == ")" + solver + R"(")
        end,
      })",
                     {}, std::string("motor_") + solver);
    ASSERT_TRUE(host);
    run(*host, 90);
    EXPECT_TRUE(host->errors().empty()) << host->errors().front().summary();
    for (const auto& e : host->expectations()) EXPECT_TRUE(e.ok) << solver << ": " << e.name << " = " << e.value;
  }
}

TEST_F(JointApi, BreakableJointLetsGoAndSwitchingSolversKeepsTheRest) {
  auto host = load(R"(
    local held, lost, jh, jl
    return {
      on_start = function()
        held = world.box{size = {0.2, 0.2, 0.2}, position = {0, 1.9, 0}, mass = 10}
        lost = world.box{size = {0.2, 0.2, 0.2}, position = {3, 1.9, 0}, mass = 10}
        jh = world.joint{a = held, anchor = {0, 2, 0}, break_force = 150}
        jl = world.joint{a = lost, anchor = {3, 2, 0}, break_force = 80}
        timer.after(0.5, function() world.set_joint_solver("impulse") end)
      end,
      on_finish = function()
        expect("strong joint holds", jh:is_valid())
        expect("weak joint broke", not jl:is_valid())
        expect("held box hangs", held:position().y, {min = 1.85})
        expect("lost box fell", lost:position().y, {max = 0})
        local f = jh:force()
        expect("holds the weight, N", f, {min = 90, max = 106})
      end,
    })");
  ASSERT_TRUE(host);
  run(*host, 60);
  EXPECT_TRUE(host->errors().empty()) << host->errors().front().summary();
  for (const auto& e : host->expectations()) EXPECT_TRUE(e.ok) << e.name << " = " << e.value;
}

TEST_F(JointApi, BadDefinitionsNameTheField) {
  auto host = load(R"(
    return {
      on_start = function()
        local b = world.box{size = {1, 1, 1}, position = {0, 2, 0}, mass = 1}
        local ok, err = pcall(world.joint, {type = "weld", a = b, anchor = {0, 3, 0}})
        expect("type named", not ok and err:find("'type'") ~= nil)
        ok, err = pcall(world.joint, {a = b, anchor = {0, 3, 0}, stifness = 3})
        expect("unknown field named", not ok and err:find("stifness") ~= nil)
        ok, err = pcall(world.joint, {type = "hinge", a = b, anchor = {0, 3, 0}, lower_angle = 1, upper_angle = -1})
        expect("limits named", not ok and err:find("lower_angle") ~= nil)
        ok, err = pcall(world.set_dt, 3)
        expect("dt range named", not ok and err:find("dt") ~= nil)
      end,
    })");
  ASSERT_TRUE(host);
  run(*host, 1);
  for (const auto& e : host->expectations()) EXPECT_TRUE(e.ok) << e.name;
  EXPECT_EQ(host->expectations().size(), 4u);
}

// A rag-doll described part by part from Lua: a box "body" with two capsule
// "legs" on hinges limited to [-0.3, 0.3] rad, dropped tilted on the ground
// under both joint solvers. The joints hold (anchor error), the legs stay
// within their limits (angle between body and leg axes about the hinge),
// and the doll comes to rest; masses and placement follow the description
// and the scale (lengths x s, masses x s^3).
TEST_F(JointApi, ADescribedRagdollHoldsItsJointsAndLimitsAndScales) {
  for (const char* solver : {"lagrange", "impulse"}) {
    auto host = load(std::string(R"(
      local doll, small, worstLimit = nil, nil, 0
      local function describe(scale, x)
        return {position = {x, 1.2, 0}, rotation = {0.4, 0, 0.3}, scale = scale, parts = {
          {name = "body", shape = "box", size = {0.6, 0.3, 0.3}, mass = 8, position = {0, 0.55, 0}},
          {name = "leg_l", shape = "capsule", radius = 0.06, length = 0.3, mass = 2, position = {-0.2, 0.2, 0}},
          {name = "leg_r", shape = "capsule", radius = 0.06, length = 0.3, mass = 2, position = {0.2, 0.2, 0}}},
          joints = {
            {type = "hinge", child = "leg_l", parent = "body", anchor = {-0.2, 0.4, 0}, axis = {1, 0, 0},
             lower_angle = -0.3, upper_angle = 0.3},
            {type = "hinge", child = "leg_r", parent = "body", anchor = {0.2, 0.4, 0}, axis = {1, 0, 0},
             lower_angle = -0.3, upper_angle = 0.3}}}
      end
      -- Angle of a leg's axis (local Y) from the body's, measured about the hinge axis (body's X).
      local function legAngle(leg)
        local by, bz, ly = doll.body:axis("y"), doll.body:axis("z"), leg:axis("y")
        local c = by.x * ly.x + by.y * ly.y + by.z * ly.z
        local s = bz.x * ly.x + bz.y * ly.y + bz.z * ly.z
        return math.atan(s, c)
      end
      return {
        joint_solver = ")") + solver + R"(",
        on_start = function()
          world.plane{}
          doll = spawn_ragdoll(describe(1, 0))
          small = spawn_ragdoll(describe(0.5, 3))
          expect("body mass, kg", doll.body:mass(), {min = 7.999, max = 8.001})
          expect("scaled mass, kg", small.leg_r:mass(), {min = 0.2499, max = 0.2501})
          local p = small.body:position()
          local d = math.sqrt((p.x - 3) ^ 2 + (p.y - 1.2) ^ 2 + p.z ^ 2)
          expect("scaled placement: 0.55 m x 0.5 from the origin, m", d, {min = 0.2749, max = 0.2751})
        end,
        on_update = function()
          for _, leg in ipairs({doll.leg_l, doll.leg_r}) do worstLimit = math.max(worstLimit, math.abs(legAngle(leg))) end
        end,
        on_finish = function()
          local _, worst = joints_error()
          expect("joints held, m", worst, {max = 0.01})
          expect("hinge limits held, rad", worstLimit, {max = 0.3 + 0.05})
          local fastest = 0
          for _, d in ipairs({doll, small}) do
            for _, part in pairs(d) do fastest = math.max(fastest, part:speed()) end
          end
          expect("at rest, m/s", fastest, {max = 0.01})
        end,
      })",
                     {}, std::string("described_ragdoll_") + solver);
    ASSERT_TRUE(host);
    run(*host, 300);
    EXPECT_TRUE(host->errors().empty()) << host->errors().front().summary();
    EXPECT_EQ(host->expectations().size(), 6u) << "on_start and on_finish both ran";
    for (const auto& e : host->expectations()) EXPECT_TRUE(e.ok) << solver << ": " << e.name << " = " << e.value;
  }
}

TEST_F(JointApi, ARagdollDescriptionsMistakesNameTheField) {
  auto host = load(R"(
    local box = {name = "a", shape = "box", size = {0.2, 0.2, 0.2}, mass = 1, position = {0, 1, 0}}
    local function try(def) local ok, err = pcall(spawn_ragdoll, def); return not ok and err or "" end
    return {
      on_start = function()
        local e = try{parts = {box, {name = "b", shape = "capsule", radius = 0.05, mass = 1, position = {0, 0.5, 0}}},
                      joints = {{child = "c", parent = "a", anchor = {0, 0.8, 0}}}}
        expect("unknown part named with the parts", e:find("joints%[1%]") ~= nil and e:find("'c'") ~= nil and e:find("a, b") ~= nil)
        e = try{parts = {{name = "a", shape = "box", size = {0.2, 0.2, 0.2}, position = {0, 1, 0}}}, joints = {}}
        expect("missing mass named", e:find("parts%[1%]") ~= nil and e:find("'mass'") ~= nil)
        e = try{parts = {{name = "a", shape = "sphere", mass = 1, position = {0, 1, 0}}}, joints = {}}
        expect("bad shape named", e:find("'shape'") ~= nil)
        e = try{height = 1.8, parts = {box}, joints = {}}
        expect("height with parts refused", e:find("'height'") ~= nil)
        e = try{parts = {box, box}, joints = {}}
        expect("duplicate name refused", e:find("names two parts") ~= nil)
        e = try{scale = 0, parts = {box}, joints = {}}
        expect("scale named", e:find("'scale'") ~= nil)
        e = try{parts = {box}, joints = {}, sise = 1}
        expect("misspelt field named", e:find("sise") ~= nil)
      end,
    })");
  ASSERT_TRUE(host);
  run(*host, 1);
  EXPECT_TRUE(host->errors().empty()) << host->errors().front().summary();
  ASSERT_FALSE(host->expectations().empty());
  for (const auto& e : host->expectations()) EXPECT_TRUE(e.ok) << e.name;
}

}  // namespace tumble::test

