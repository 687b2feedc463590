#pragma once
// A scenario in a throw-away mod folder, run against a real physics::World:
//   auto host = load(R"( return {on_start = function() ... end} )");
//   run(*host, 60);  // start, 60 fixed steps (update, step, afterStep), finish
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>

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

class ScriptTest : public ::testing::Test {
 protected:
  void SetUp() override {
    m_root = testRoot();
    fs::remove_all(m_root);
    fs::create_directories(m_root);
  }

  /// Loads `source` as scenarios/s.lua of mod `mod` (a fresh folder per name).
  std::unique_ptr<script::ScenarioHost> load(const std::string& source, const script::VmLimits& limits = {},
                                             const std::string& mod = "escape", std::uint64_t seed = 1,
                                             const std::map<std::string, std::string>& extraFiles = {}) {
    std::map<std::string, std::string> files = extraFiles;
    files["scenarios/s.lua"] = source;
    fs::path dir = makeMod(m_root, mod, "", files);
    auto info = script::loadManifest(dir.string());
    EXPECT_TRUE(info) << (info ? "" : info.error());
    script::ScenarioOptions options;
    options.limits = limits;
    options.seed = seed;
    options.scriptsDir = TUMBLE_SCRIPTS_DIR;
    auto host = script::ScenarioHost::load(*info, "s", m_world, options);
    EXPECT_TRUE(host) << (host ? "" : host.error());
    return host ? std::move(host.value()) : nullptr;
  }

  /// start, `steps` fixed steps of dt (update, World::step, afterStep), finish.
  void run(script::ScenarioHost& host, int steps, double dt = 1.0 / 60) {
    host.start();
    double t = 0;
    for (int i = 0; i < steps; ++i) {
      host.update(t, dt, i);
      m_world.step(Real(dt));
      t = double(i + 1) * dt;
      host.afterStep(t, i);
    }
    host.finish(t, steps);
  }

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
  physics::World m_world;
};

}  // namespace tumble::test
