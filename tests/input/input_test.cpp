// The input system as a player and a script see it: keys become action
// values, key pairs make an axis, modifiers do their maths, a higher context
// takes a shared key, edges are never lost between fixed steps, injected
// values drive headless runs.
#include <cmath>

#include "input_fixture.h"

namespace tumble::test {

using input::ActionType;
using input::InputSystem;

namespace {

input::BindingSet vehicleSet() {
  input::BindingSet s;
  s.contexts = {{"vehicle", 10, true}};
  s.actions = {actionDef("throttle", ActionType::Button, "vehicle", {"key:W", "pad_axis:righttrigger"}),
               actionDef("steer", ActionType::Axis, "vehicle", {"keys:A/D", "pad_axis:leftx;dead_zone=0.2"}),
               actionDef("reset", ActionType::Button, "vehicle", {"key:ctrl+R"})};
  return s;
}

}  // namespace

TEST(InputKeys, AKeyDrivesAButtonThroughDownPressedAndReleased) {
  InputSystem in(vehicleSet());
  const int throttle = in.find("throttle");
  ASSERT_GE(throttle, 0);
  in.step();
  EXPECT_EQ(in.value(throttle), 0);
  EXPECT_FALSE(in.down(throttle));

  in.handleEvent(keyEvent(SDL_SCANCODE_W, true));
  in.step();
  EXPECT_EQ(in.value(throttle), 1);
  EXPECT_TRUE(in.down(throttle));
  EXPECT_TRUE(in.pressed(throttle));
  in.handleEvent(keyEvent(SDL_SCANCODE_W, true, /*repeat*/ true));  // auto-repeat is not a new press
  in.step();
  EXPECT_TRUE(in.down(throttle));
  EXPECT_FALSE(in.pressed(throttle));

  in.handleEvent(keyEvent(SDL_SCANCODE_W, false));
  in.step();
  EXPECT_EQ(in.value(throttle), 0);
  EXPECT_TRUE(in.released(throttle));
  in.step();
  EXPECT_FALSE(in.released(throttle));
}

TEST(InputKeys, AKeyPairMakesAnAxisFromMinusOneToOne) {
  InputSystem in(vehicleSet());
  const int steer = in.find("steer");
  in.handleEvent(keyEvent(SDL_SCANCODE_A, true));
  in.step();
  EXPECT_EQ(in.value(steer), -1);
  in.handleEvent(keyEvent(SDL_SCANCODE_D, true));
  in.step();
  EXPECT_EQ(in.value(steer), 0) << "both keys cancel";
  in.handleEvent(keyEvent(SDL_SCANCODE_A, false));
  in.step();
  EXPECT_EQ(in.value(steer), 1);
}

TEST(InputKeys, AModifierBindingNeedsItsModifierHeld) {
  InputSystem in(vehicleSet());
  const int reset = in.find("reset");
  in.handleEvent(keyEvent(SDL_SCANCODE_R, true));
  in.step();
  EXPECT_FALSE(in.down(reset)) << "R alone is not ctrl+R";
  in.handleEvent(keyEvent(SDL_SCANCODE_R, false));
  in.handleEvent(keyEvent(SDL_SCANCODE_LCTRL, true));
  in.handleEvent(keyEvent(SDL_SCANCODE_R, true));
  in.step();
  EXPECT_TRUE(in.pressed(reset));
}

TEST(InputModifiers, DeadZoneCurveInvertAndScaleFollowTheirFormulas) {
  input::Modifiers dz;
  dz.deadZone = 0.2;
  EXPECT_EQ(input::applyModifiers(0.1, dz), 0.0);
  EXPECT_EQ(input::applyModifiers(-0.2, dz), 0.0);
  // The rest of the travel is stretched back to 0..1: (0.6 - 0.2) / 0.8 = 0.5.
  EXPECT_NEAR(input::applyModifiers(0.6, dz), 0.5, 1e-12);
  EXPECT_NEAR(input::applyModifiers(-1.0, dz), -1.0, 1e-12);

  input::Modifiers curve;
  curve.curve = 2;
  EXPECT_NEAR(input::applyModifiers(0.5, curve), 0.25, 1e-12);
  EXPECT_NEAR(input::applyModifiers(-0.5, curve), -0.25, 1e-12) << "the sign survives the curve";

  input::Modifiers all;
  all.deadZone = 0.2;
  all.curve = 2;
  all.invert = true;
  all.scale = 3;
  // dead zone: 0.5, curve: 0.25, invert: -0.25, scale: -0.75
  EXPECT_NEAR(input::applyModifiers(0.6, all), -0.75, 1e-12);
}

TEST(InputModifiers, AStickBelowItsDeadZoneReadsZeroAndFullTravelReadsOne) {
  InputSystem in(vehicleSet());
  const int steer = in.find("steer");
  in.handleEvent(padAxisEvent(SDL_CONTROLLER_AXIS_LEFTX, 6000));  // 0.18 of travel < 0.2
  in.step();
  EXPECT_EQ(in.value(steer), 0);
  in.handleEvent(padAxisEvent(SDL_CONTROLLER_AXIS_LEFTX, 19660));  // 0.6 -> (0.6 - 0.2) / 0.8
  in.step();
  EXPECT_NEAR(in.value(steer), 0.5, 1e-3);
  in.handleEvent(padAxisEvent(SDL_CONTROLLER_AXIS_LEFTX, -32768));
  in.step();
  EXPECT_NEAR(in.value(steer), -1, 1e-6);
}

TEST(InputModifiers, ATriggerGivesItsTravelAndIsDownPastHalf) {
  InputSystem in(vehicleSet());
  const int throttle = in.find("throttle");
  in.handleEvent(padAxisEvent(SDL_CONTROLLER_AXIS_TRIGGERRIGHT, 9830));  // 0.3
  in.step();
  EXPECT_NEAR(in.value(throttle), 0.3, 1e-3);
  EXPECT_FALSE(in.down(throttle));
  in.handleEvent(padAxisEvent(SDL_CONTROLLER_AXIS_TRIGGERRIGHT, 26214));  // 0.8
  in.step();
  EXPECT_NEAR(in.value(throttle), 0.8, 1e-3);
  EXPECT_TRUE(in.pressed(throttle));
}

TEST(InputContexts, TheHigherPriorityContextTakesASharedKey) {
  input::BindingSet s;
  s.contexts = {{"menu", 50, true}, {"vehicle", 10, true}, {"camera", 10, true}};
  s.actions = {actionDef("menu_confirm", ActionType::Button, "menu", {"key:Return"}),
               actionDef("horn", ActionType::Button, "vehicle", {"key:Return", "key:H"}),
               actionDef("zoom", ActionType::Button, "camera", {"key:Return"})};
  InputSystem in(s);
  const int confirm = in.find("menu_confirm"), horn = in.find("horn"), zoom = in.find("zoom");
  EXPECT_TRUE(in.handleEvent(keyEvent(SDL_SCANCODE_RETURN, true))) << "a bound key is consumed";
  in.step();
  EXPECT_TRUE(in.down(confirm));
  EXPECT_FALSE(in.down(horn)) << "the menu (priority 50) consumed Return";
  EXPECT_FALSE(in.down(zoom));

  ASSERT_TRUE(in.setContextEnabled("menu", false));
  in.step();
  EXPECT_FALSE(in.down(confirm)) << "a context switched off reads 0";
  EXPECT_TRUE(in.down(horn)) << "with the menu off, Return reaches the vehicle";
  EXPECT_TRUE(in.down(zoom)) << "equal priorities both see the key";

  in.handleEvent(keyEvent(SDL_SCANCODE_H, true));
  ASSERT_TRUE(in.setContextEnabled("menu", true));
  in.step();
  EXPECT_TRUE(in.down(horn)) << "H is not shared, so the vehicle keeps it";
  EXPECT_FALSE(in.setContextEnabled("vehicel", true)) << "unknown context";
  EXPECT_NE(in.setContextEnabled("vehicel", true).error().find("vehicle"), std::string::npos);
}

TEST(InputDevices, GamepadButtonsDriveActionsAndAPadThatLeavesReleasesThem) {
  input::BindingSet s;
  s.contexts = {{"vehicle", 10, true}};
  s.actions = {actionDef("handbrake", ActionType::Button, "vehicle", {"key:Space", "pad:a"}),
               actionDef("steer", ActionType::Axis, "vehicle", {"pad_axis:leftx"})};
  InputSystem in(s);
  in.handleEvent(padButtonEvent(SDL_CONTROLLER_BUTTON_A, true));
  in.handleEvent(padAxisEvent(SDL_CONTROLLER_AXIS_LEFTX, 32767));
  in.step();
  EXPECT_TRUE(in.pressed(0));
  EXPECT_NEAR(in.value(1), 1.0, 1e-6);
  SDL_Event gone{};
  gone.type = SDL_CONTROLLERDEVICEREMOVED;
  gone.cdevice.which = 12345;
  in.handleEvent(gone);
  in.step();
  EXPECT_TRUE(in.released(0)) << "nothing stays held by a pad that was unplugged";
  EXPECT_EQ(in.value(1), 0);
}

TEST(InputDevices, TheWheelCountsNotchesPerStepAndAMouseButtonIsAButton) {
  input::BindingSet s;
  s.contexts = {{"interact", 5, false}, {"camera", 0, true}};
  s.actions = {actionDef("grab", ActionType::Button, "interact", {"mouse:left"}),
               actionDef("zoom", ActionType::Axis, "camera", {"wheel:y"})};
  InputSystem in(s);
  EXPECT_FALSE(in.handleEvent(mouseButtonEvent(SDL_BUTTON_LEFT, true))) << "interact is off: the camera keeps the button";
  in.handleEvent(mouseButtonEvent(SDL_BUTTON_LEFT, false));
  ASSERT_TRUE(in.setContextEnabled("interact", true));
  EXPECT_TRUE(in.handleEvent(mouseButtonEvent(SDL_BUTTON_LEFT, true)));
  SDL_Event wheel{};
  wheel.type = SDL_MOUSEWHEEL;
  wheel.wheel.preciseY = 1;
  wheel.wheel.direction = SDL_MOUSEWHEEL_NORMAL;
  in.handleEvent(wheel);
  in.handleEvent(wheel);
  in.step();
  EXPECT_TRUE(in.pressed(0));
  EXPECT_EQ(in.value(1), 2);
  in.step();
  EXPECT_TRUE(in.down(0));
  EXPECT_EQ(in.value(1), 0);
}

TEST(InputDevices, PressesTheHudTakesAreIgnoredButReleasesAlwaysCount) {
  InputSystem in(vehicleSet());
  const int throttle = in.find("throttle");
  in.handleEvent(keyEvent(SDL_SCANCODE_W, true), /*uiWants*/ true);  // typing in a HUD field
  in.step();
  EXPECT_FALSE(in.down(throttle));
  in.handleEvent(keyEvent(SDL_SCANCODE_W, true));
  in.step();
  in.handleEvent(keyEvent(SDL_SCANCODE_W, false), true);  // focus moved to the HUD while held
  in.step();
  EXPECT_TRUE(in.released(throttle)) << "no stuck key";
}

TEST(InputContexts, UnboundKeysAreLeftForTheCamera) {
  InputSystem in(vehicleSet());
  EXPECT_FALSE(in.handleEvent(keyEvent(SDL_SCANCODE_N, true)));
  EXPECT_FALSE(in.handleEvent(mouseMotionEvent(4, 0))) << "motion always reaches the orbit camera";
}

TEST(InputEdges, ATapInsideOneFrameIsPressedOnceAndReleasedNextStep) {
  InputSystem in(vehicleSet());
  const int throttle = in.find("throttle");
  in.step();
  // Press and release between two fixed steps (a 60 Hz step, a fast tap).
  in.handleEvent(keyEvent(SDL_SCANCODE_W, true));
  in.handleEvent(keyEvent(SDL_SCANCODE_W, false));
  in.step();
  EXPECT_TRUE(in.pressed(throttle));
  EXPECT_TRUE(in.down(throttle));
  EXPECT_EQ(in.value(throttle), 1);
  in.step();
  EXPECT_FALSE(in.pressed(throttle));
  EXPECT_TRUE(in.released(throttle));
  EXPECT_FALSE(in.down(throttle));
}

TEST(InputEdges, SeveralStepsInOneFrameSeeOnePress) {
  InputSystem in(vehicleSet());
  const int throttle = in.find("throttle");
  in.handleEvent(keyEvent(SDL_SCANCODE_W, true));
  int presses = 0, downs = 0;
  for (int i = 0; i < 4; ++i) {  // a slow frame: the accumulator runs 4 steps
    in.step();
    presses += in.pressed(throttle);
    downs += in.down(throttle);
  }
  EXPECT_EQ(presses, 1);
  EXPECT_EQ(downs, 4);
}

TEST(InputEdges, ReleaseAndPressWhileHeldCountsAsBothEdges) {
  InputSystem in(vehicleSet());
  const int throttle = in.find("throttle");
  in.handleEvent(keyEvent(SDL_SCANCODE_W, true));
  in.step();
  in.handleEvent(keyEvent(SDL_SCANCODE_W, false));
  in.handleEvent(keyEvent(SDL_SCANCODE_W, true));
  in.step();
  EXPECT_TRUE(in.down(throttle));
  EXPECT_TRUE(in.released(throttle));
  EXPECT_TRUE(in.pressed(throttle)) << "the second press is not lost";
}

TEST(InputEdges, FramePressesReachTheAppEvenWithoutSteps) {
  // Pause must unpause: while paused no fixed step runs.
  InputSystem in(vehicleSet());
  in.handleEvent(keyEvent(SDL_SCANCODE_W, true));
  in.handleEvent(keyEvent(SDL_SCANCODE_W, false));
  in.handleEvent(keyEvent(SDL_SCANCODE_W, true));
  auto presses = in.takeFramePresses();
  ASSERT_EQ(presses.size(), 1u);
  EXPECT_EQ(presses[0], in.find("throttle"));
  EXPECT_TRUE(in.takeFramePresses().empty());
}

TEST(InputEdges, MouseMotionIsThePixelsMovedDuringTheStep) {
  input::BindingSet s;
  s.contexts = {{"look", 0, true}};
  s.actions = {actionDef("look_x", ActionType::Axis, "look", {"mouse_axis:x;scale=0.01"})};
  InputSystem in(s);
  in.handleEvent(mouseMotionEvent(30, 5));
  in.handleEvent(mouseMotionEvent(20, 5));
  in.step();
  EXPECT_NEAR(in.value(0), 0.5, 1e-12);  // 50 px * 0.01
  in.step();
  EXPECT_EQ(in.value(0), 0) << "no motion in the next step";
}

TEST(InputInjection, InjectedValuesActFromTheNextStepAndGiveWayWhenCleared) {
  InputSystem in(vehicleSet());
  const int throttle = in.find("throttle"), steer = in.find("steer");
  in.inject(steer, -0.25);
  EXPECT_EQ(in.value(steer), 0) << "the current step's snapshot does not change";
  in.step();
  EXPECT_EQ(in.value(steer), -0.25);
  EXPECT_FALSE(in.down(steer));
  in.inject(throttle, 1);
  in.step();
  EXPECT_TRUE(in.pressed(throttle));
  in.handleEvent(keyEvent(SDL_SCANCODE_W, true));
  in.clearInjection(throttle);
  in.clearInjection(steer);
  in.step();
  EXPECT_TRUE(in.down(throttle)) << "back to the keyboard, where W is held";
  EXPECT_FALSE(in.pressed(throttle)) << "still down: no new press";
  EXPECT_EQ(in.value(steer), 0);
}

TEST(InputInjection, TheSameInjectionsGiveTheSameStates) {
  auto trace = [] {
    InputSystem in(vehicleSet());
    std::vector<double> out;
    for (int i = 0; i < 30; ++i) {
      if (i % 7 == 0) in.inject(in.find("steer"), std::sin(i * 0.3));
      if (i % 5 == 0) in.inject(in.find("throttle"), (i / 5) % 2);
      in.step();
      out.push_back(in.value(in.find("steer")) + 10 * in.pressed(in.find("throttle")));
    }
    return out;
  };
  EXPECT_EQ(trace(), trace());
}

TEST(InputCapture, TheMenuCapturesTheNextKeyInsteadOfActing) {
  InputSystem in(vehicleSet());
  in.beginCapture();
  in.handleEvent(keyEvent(SDL_SCANCODE_LSHIFT, true));  // a modifier waits for its key
  EXPECT_TRUE(in.capturing());
  EXPECT_TRUE(in.handleEvent(keyEvent(SDL_SCANCODE_W, true)));
  auto got = in.takeCaptured();
  ASSERT_TRUE(got);
  EXPECT_TRUE(got->first);
  EXPECT_EQ(input::sourceLabel(got->second), "shift+W");
  in.step();
  EXPECT_FALSE(in.down(in.find("throttle"))) << "the captured key did not drive the game";

  in.beginCapture();
  in.handleEvent(keyEvent(SDL_SCANCODE_ESCAPE, true));
  got = in.takeCaptured();
  ASSERT_TRUE(got);
  EXPECT_FALSE(got->first) << "Escape cancels";
}

}  // namespace tumble::test

namespace tumble::test {

// Hot reload of bindings.lua: new defaults apply at once;
// an action the player rebound keeps the player's binding; a context a
// script switched on stays on; a new action appears.
TEST(InputReload, RedefineKeepsThePlayersOverridesAndTheContexts) {
  InputSystem in(vehicleSet());
  ASSERT_TRUE(in.setContextEnabled("vehicle", false).ok());  // a script turned it off
  const int reset = in.find("reset");
  auto f5 = input::parseBinding("key:F5");
  ASSERT_TRUE(f5.ok());
  in.setBindings(reset, {f5.value()});  // the player rebinds reset

  input::BindingSet edited = vehicleSet();
  edited.actions[0] = actionDef("throttle", ActionType::Button, "vehicle", {"key:Up"});  // a new default
  edited.actions.push_back(actionDef("horn", ActionType::Button, "vehicle", {"key:H"}));
  in.redefine(std::move(edited));

  EXPECT_FALSE(in.contextEnabled("vehicle")) << "the script's switch stays";
  ASSERT_TRUE(in.setContextEnabled("vehicle", true).ok());
  const int throttle = in.find("throttle");
  in.handleEvent(keyEvent(SDL_SCANCODE_UP, true));
  in.step();
  EXPECT_EQ(in.value(throttle), 1) << "the new default key drives the action";
  in.handleEvent(keyEvent(SDL_SCANCODE_UP, false));
  in.handleEvent(keyEvent(SDL_SCANCODE_W, true));
  in.step();
  EXPECT_EQ(in.value(throttle), 0) << "the old default no longer does";
  ASSERT_GE(in.find("horn"), 0);
  ASSERT_EQ(in.bindings(in.find("reset")).size(), 1u);
  EXPECT_EQ(in.bindings(in.find("reset"))[0], f5.value()) << "the player's rebinding is kept";
}

}  // namespace tumble::test
