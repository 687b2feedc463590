#pragma once
// A scenario in a throw-away mod folder, run in a real scene (app::Scene,
// the one owner of a scene's systems) through the app's fixed step:
//   auto host = load(R"( return {on_start = function() ... end} )");
//   run(*host, 60);  // start, 60 fixed steps (app::stepScene), finish
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include "app/fixed_step.h"
#include "app/scene.h"
#include "physics/world.h"
#include "script/mods.h"
#include "script/scenario_host.h"

namespace tumble::test {

namespace fs = std::filesystem;

inline fs::path testRoot() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return fs::path(TUMBLE_TEST_TMP) / (std::string(info->test_suite_name()) + "." + info->name());
}

inline void writeFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

/// Writes <root>/<name>/mod.lua (and any other files) and returns the folder.
inline fs::path makeMod(const fs::path& root, const std::string& name, const std::string& manifestExtra = "",
                        const std::map<std::string, std::string>& files = {}, const std::string& version = "1.0.0") {
  fs::path dir = root / name;
  writeFile(dir / "mod.lua", "return {\n  name = \"" + name + "\",\n  version = \"" + version +
                                 "\",\n  api = 1,\n" + manifestExtra + "}\n");
  for (const auto& [file, text] : files) writeFile(dir / file, text);
  return dir;
}

/// A loaded scenario: the scene that owns it, used like a pointer to its host.
struct LoadedScenario {
  std::unique_ptr<app::Scene> scene;
  script::ScenarioHost* operator->() const { return &scene->host(); }
  script::ScenarioHost& operator*() const { return scene->host(); }
  explicit operator bool() const { return scene != nullptr; }
};

/// The scene a host belongs to (every host in these tests is an app::Scene's).
inline app::Scene& sceneOf(script::ScenarioHost& host) { return dynamic_cast<app::Scene&>(host.scene()); }

/// One fixed step of the host's scene, as `tumble run` takes it.
inline void stepOnce(script::ScenarioHost& host, double time_s, std::int64_t step) {
  app::RunTimings t;
  app::stepScene(sceneOf(host), app::StepTime{time_s, step}, t);
}

class ScriptTest : public ::testing::Test {
 protected:
  void SetUp() override {
    m_root = testRoot();
    fs::remove_all(m_root);
    fs::create_directories(m_root);
  }

  /// Loads `source` as scenarios/s.lua of mod `mod` (a fresh folder per name).
  LoadedScenario load(const std::string& source, const script::VmLimits& limits = {},
                      const std::string& mod = "escape", std::uint64_t seed = 1,
                      const std::map<std::string, std::string>& extraFiles = {},
                      const std::map<std::string, std::string>& sets = {}) {
    std::map<std::string, std::string> files = extraFiles;
    files["scenarios/s.lua"] = source;
    makeMod(m_root, mod, "", files);
    app::SceneOptions options;
    options.scenarioRef = mod + ":s";
    options.modDirs = {m_root.string()};
    options.limits = limits;
    options.seed = seed;
    options.sets = sets;
    auto scene = app::Scene::create(options);
    EXPECT_TRUE(scene) << (scene ? "" : scene.error());
    if (!scene) return {};
    m_world = &scene.value()->world();
    return LoadedScenario{std::move(scene.value())};
  }

  /// start, `steps` fixed steps of dt (app::stepScene), finish.
  void run(script::ScenarioHost& host, int steps, double dt = 1.0 / 60) {
    sceneOf(host).start();
    double t = 0;
    for (int i = 0; i < steps; ++i) {
      stepOnce(host, t, i);
      t = double(i + 1) * dt;
    }
    host.finish(t, steps);
  }

  /// The world of the scenario loaded last.
  physics::World& world() { return *m_world; }

  static const script::Expectation* expectation(const script::ScenarioHost& host, const std::string& name) {
    for (const auto& e : host.expectations())
      if (e.name == name) return &e;
    return nullptr;
  }

  /// Every expectation the script recorded held, and there was at least one.
  static void expectAllHeld(const script::ScenarioHost& host) {
    EXPECT_FALSE(host.expectations().empty());
    for (const auto& e : host.expectations()) EXPECT_TRUE(e.ok) << e.name << " = " << e.value;
    for (const auto& e : host.errors()) ADD_FAILURE() << e.summary() << "\n" << e.traceback;
  }

  fs::path m_root;
  physics::World* m_world = nullptr;
};

}  // namespace tumble::test
