// The Lua side: scripts read actions by name, never keys; unknown names are
// errors that suggest the right one; injection drives headless runs.
#include <fstream>

#include "input_fixture.h"
#include "app/fixed_step.h"
#include "app/scene.h"
#include "physics/world.h"
#include "script/scenario_host.h"

namespace tumble::test {

namespace fs = std::filesystem;

class LuaInput : public ::testing::Test {
 protected:
  LuaInput() {
    input::BindingSet s;
    s.contexts = {{"vehicle", 10, true}, {"interact", 5, false}};
    s.actions = {actionDef("throttle", input::ActionType::Button, "vehicle", {"key:W"}),
                 actionDef("steer", input::ActionType::Axis, "vehicle", {"keys:A/D"}),
                 actionDef("grab", input::ActionType::Button, "interact", {"mouse:left"})};
    m_bindings = s;
  }

  /// The scenario in mod "m", in a scene with this test's actions.
  script::ScenarioHost* load(const std::string& source) {
    const fs::path root = testDir(), dir = root / "m";
    fs::create_directories(dir / "scenarios");
    std::ofstream(dir / "mod.lua") << "return {name = \"m\", version = \"1.0.0\", api = 1}\n";
    std::ofstream(dir / "scenarios" / "s.lua") << source;
    app::SceneOptions options;
    options.scenarioRef = "m:s";
    options.modDirs = {root.string()};
    options.bindings = m_bindings;
    auto scene = app::Scene::create(options);
    EXPECT_TRUE(scene) << (scene ? "" : scene.error());
    if (!scene) return nullptr;
    m_scene = std::move(scene.value());
    m_input = &m_scene->input();
    return &m_scene->host();
  }

  /// One fixed step as the app runs it.
  void step(script::ScenarioHost&) {
    app::RunTimings t;
    app::stepScene(*m_scene, app::StepTime{m_time, m_step++}, t);
    m_time += 1.0 / 60;
  }

  static void expectAllHeld(const script::ScenarioHost& host) {
    EXPECT_FALSE(host.expectations().empty());
    for (const auto& e : host.expectations()) EXPECT_TRUE(e.ok) << e.name << " = " << e.value;
    for (const auto& e : host.errors()) ADD_FAILURE() << e.summary();
  }

  input::BindingSet m_bindings;
  std::unique_ptr<app::Scene> m_scene;
  input::InputSystem* m_input = nullptr;
  double m_time = 0;
  std::int64_t m_step = 0;
};

TEST_F(LuaInput, ScriptsReadTheKeysOnlyThroughTheirActions) {
  auto host = load(R"(
    local seen = {}
    return {on_update = function(ctx)
      seen[#seen + 1] = {input.value("throttle"), input.down("throttle"), input.pressed("throttle"),
                         input.released("throttle"), input.value("steer")}
    end, on_finish = function()
      expect("step 1: pressed", seen[1][3] and seen[1][2] and seen[1][1] == 1)
      expect("step 1: steer left", seen[1][5], {min = -1, max = -1})
      expect("step 2: held, not pressed again", seen[2][2] and not seen[2][3])
      expect("step 3: released", seen[3][4] and not seen[3][2] and seen[3][1] == 0)
      expect("no raw keys in the API", input.key == nil and input.keys == nil)
    end})");
  ASSERT_TRUE(host);
  m_scene->start();
  m_input->handleEvent(keyEvent(SDL_SCANCODE_W, true));
  m_input->handleEvent(keyEvent(SDL_SCANCODE_A, true));
  step(*host);
  step(*host);
  m_input->handleEvent(keyEvent(SDL_SCANCODE_W, false));
  step(*host);
  host->finish(m_time, m_step);
  expectAllHeld(*host);
}

TEST_F(LuaInput, AnUnknownActionIsALuaErrorThatSuggestsTheName) {
  auto host = load(R"(return {on_update = function() local v = input.value("trottle") end})");
  ASSERT_TRUE(host);
  m_scene->start();
  step(*host);
  ASSERT_EQ(host->errors().size(), 1u);
  const std::string msg = host->errors()[0].message;
  EXPECT_NE(msg.find("input.value: unknown action \"trottle\" (did you mean: throttle?)"), std::string::npos) << msg;
  EXPECT_EQ(host->errors()[0].line, 1) << "the error points at the script line";
}

TEST_F(LuaInput, InjectedValuesDriveActionsFromTheNextStep) {
  auto host = load(R"(
    local n, values = 0, {}
    return {on_update = function()
      n = n + 1
      values[n] = {input.value("steer"), input.pressed("throttle"), input.down("throttle")}
      if n == 1 then input.inject("steer", 0.5); input.inject("throttle", true) end
      if n == 3 then input.inject("throttle", nil) end
    end, on_finish = function()
      expect("not before the next step", values[1][1], {min = 0, max = 0})
      expect("steer injected", values[2][1], {min = 0.5, max = 0.5})
      expect("throttle pressed by injection", values[2][2])
      expect("still down", values[3][3] and not values[3][2])
      expect("back to the (idle) keyboard", not values[4][3])
    end})");
  ASSERT_TRUE(host);
  m_scene->start();
  for (int i = 0; i < 4; ++i) step(*host);
  host->finish(m_time, m_step);
  expectAllHeld(*host);
}

TEST_F(LuaInput, ContextsSwitchFromLuaAndUnknownOnesAreErrors) {
  auto host = load(R"(
    return {on_start = function()
      expect("interact starts off", not input.context_enabled("interact"))
      input.set_context("interact", true)
      expect("now on", input.context_enabled("interact"))
      local ok, err = pcall(input.set_context, "interract", true)
      expect("unknown context fails", not ok)
      expect("and suggests the name", err:find("did you mean: interact", 1, true) ~= nil)
      local names = {}
      for _, a in ipairs(input.actions()) do names[#names + 1] = a.name .. ":" .. a.type .. ":" .. a.context end
      expect("actions listed", table.concat(names, ",") == "throttle:button:vehicle,steer:axis:vehicle,grab:button:interact")
    end})");
  ASSERT_TRUE(host);
  m_scene->start();
  expectAllHeld(*host);
  EXPECT_TRUE(m_input->contextEnabled("interact"));
}

TEST_F(LuaInput, ANonStringActionNameIsAClearError) {
  auto host = load(R"(return {on_start = function()
      local ok, err = pcall(input.down, 3)
      expect("rejected", not ok and err:find("expected an action name", 1, true) ~= nil)
    end})");
  ASSERT_TRUE(host);
  m_scene->start();
  expectAllHeld(*host);
}

TEST_F(LuaInput, ThePointerRayFeedsWorldRaycastToPickWhatIsUnderTheMouse) {
  auto host = load(R"(
    local box
    return {on_start = function()
      expect("no ray before the app sets one", input.pointer_ray() == nil)
      box = world.box{size = {1, 1, 1}, position = {0, 2, -10}, type = "static"}
    end, on_update = function()
      local o, d = input.pointer_ray()
      local hit = world.raycast(o, d, 100)
      expect("picked the box", hit ~= nil and hit.body == box)
      expect("at its front face, m", hit and hit.distance or -1, {min = 9.49, max = 9.51})
    end})");
  ASSERT_TRUE(host);
  m_scene->start();
  m_input->setPointerRay(Vec3(0, 2, 0), Vec3(0, 0, -1));  // what play computes from the camera
  step(*host);
  expectAllHeld(*host);
}

}  // namespace tumble::test

namespace tumble::test {

// scripts/tumble/interact.lua, the rag-doll paper's hands: with the pointer
// over a box, holding "grab" drags it towards the cursor's point (a spring),
// and "impulse" kicks what is under the cursor along the ray.
TEST(Interact, GrabDragsTheBodyUnderThePointerAndImpulseKicksIt) {
  input::BindingSet s;
  s.contexts = {{"interact", 5, false}};
  for (const char* name : {"grab", "impulse", "dt_up", "dt_down"})
    s.actions.push_back(actionDef(name, input::ActionType::Button, "interact", {"key:G"}));
  const fs::path dir = fs::path(TUMBLE_TEST_TMP) / "Interact" / "m";
  fs::create_directories(dir / "scenarios");
  std::ofstream(dir / "mod.lua") << "return {name = \"m\", version = \"1.0.0\", api = 1}\n";
  std::ofstream(dir / "scenarios" / "s.lua") << R"(
    local interact = require "tumble.interact"
    local hands, crate, kicked, held
    return {
      on_start = function()
        world.set_gravity({0, 0, 0})
        hands = interact.new{kick = 2}
        crate = world.box{size = {1, 1, 1}, position = {0, 0, -10}, mass = 3}
        kicked = world.box{size = {1, 1, 1}, position = {5, 0, -10}, mass = 2}
      end,
      on_update = function(ctx)
        held = hands:update()
        if ctx.step == 10 then expect("the crate is held", held == crate) end
      end,
      on_finish = function()
        -- Grabbed at its front face (z = -9.5), pulled towards the cursor's
        -- point 9.5 m out along the ray, now aimed 2 m to the left: x = -2.
        expect("dragged towards the cursor", crate:position().x, {max = -1.5})
        -- 2 kg kicked with mass * 2 m/s along the ray (towards -z).
        expect("kick speed", kicked:velocity().z, {min = -2.01, max = -1.99})
      end,
    }
  )";
  app::SceneOptions options;
  options.scenarioRef = "m:s";
  options.modDirs = {dir.parent_path().string()};
  options.bindings = s;
  auto scene = app::Scene::create(options);
  ASSERT_TRUE(scene) << scene.error();
  script::ScenarioHost& h = scene.value()->host();
  input::InputSystem& in = scene.value()->input();
  scene.value()->start();
  const int grab = in.find("grab"), impulse = in.find("impulse");
  auto step = [&](int i) {
    app::RunTimings t;
    app::stepScene(*scene.value(), app::StepTime{i / 60.0, i}, t);
  };
  in.setPointerRay(Vec3(0, 0, 0), Vec3(0, 0, -1));  // the camera looks at the crate
  in.inject(grab, 1);
  for (int i = 0; i < 5; ++i) step(i);
  in.setPointerRay(Vec3(0, 0, 0), Vec3(-2, 0, -9.5).normalized());  // the cursor moves left, still held
  for (int i = 5; i < 120; ++i) step(i);
  in.inject(grab, 0);
  step(120);
  in.setPointerRay(Vec3(5, 0, 0), Vec3(0, 0, -1));  // over the second box
  in.inject(impulse, 1);
  step(121);
  in.inject(impulse, 0);
  step(122);
  h.finish(123 / 60.0, 123);
  ASSERT_FALSE(h.expectations().empty());
  for (const auto& e : h.expectations()) EXPECT_TRUE(e.ok) << e.name << " = " << e.value;
  for (const auto& e : h.errors()) ADD_FAILURE() << e.summary();
}

}  // namespace tumble::test
