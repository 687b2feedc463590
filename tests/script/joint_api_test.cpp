// The joint API from Lua (bind_joint.cpp): world.joint with a hinge motor,
// Joint:set_motor, a breakable joint, switching formulations while running,
// and bad definitions refused with the field named.
#include <cmath>

#include "script_fixture.h"

namespace tumble::test {

class JointApi : public ScriptTest {};

TEST_F(JointApi, HingeMotorSpinsAWheelAtItsSpeedUnderBothFormulations) {
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

}  // namespace tumble::test
