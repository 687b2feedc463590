#pragma once
// Runs one scenario: loads <mod>/scenarios/<name>.lua into the mod's sandboxed
// environment and calls its lifecycle (ARCHITECTURE.md):
//   on_start(ctx), on_update(ctx, dt) at the fixed rate, on_finish(ctx).
// Errors never escape: each becomes a ScriptError (mod, file, line,
// traceback) and the game goes on. A callback that fails kMaxConsecutiveErrors
// times in a row is paused, so one broken line does not flood the log.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "physics/world.h"
#include "script/lua_vm.h"
#include "script/mods.h"
#include "script/script_error.h"

namespace tumble::script {

struct Expectation {
  std::string name;
  bool ok = false;
  bool isBool = false;
  double value = 0;  ///< the number, or 1/0 for a boolean
  std::optional<double> min, max;
};

struct ScenarioOptions {
  std::map<std::string, std::string> params;  ///< --set KEY=VALUE for the script (param())
  std::uint64_t seed = 1;
  std::string scriptsDir;  ///< the runtime's Lua library (require "tumble.x")
  VmLimits limits;
};

class ScenarioHost {
 public:
  static constexpr int kMaxConsecutiveErrors = 3;

  /// Loads and runs the scenario file's top level. Fails (Result error) if
  /// the file is missing, does not compile, errors at top level or does not
  /// return a table; the message names mod, file and line.
  static Result<std::unique_ptr<ScenarioHost>> load(const ModInfo& mod, const std::string& scenario,
                                                    physics::World& world, const ScenarioOptions& options);
  ~ScenarioHost();

  void start();
  void update(double time_s, double dt_s, std::int64_t step);
  void finish(double time_s, std::int64_t step);

  bool hasUpdate() const { return m_hasUpdate && !m_updatePaused; }
  const std::string& title() const { return m_title; }
  /// Seconds the scenario asks to run for when --seconds/--steps are absent.
  double duration_s() const { return m_duration_s; }
  const std::vector<ScriptError>& errors() const { return m_errors; }
  const std::vector<Expectation>& expectations() const { return m_expectations; }
  /// Lines scripts asked to show on the HUD (hud_text), latest frame.
  const std::vector<std::string>& hudText() const { return m_hudText; }
  /// Display colour (linear RGB 0..1) of a body made by the script.
  Eigen::Vector3f colorOf(physics::BodyId id) const;
  physics::World& world() { return m_world; }
  const ModInfo& mod() const { return m_mod; }
  const std::string& scenarioFile() const { return m_file; }
  std::size_t luaMemoryBytes() const { return m_vm.memoryUsed(); }

  // Used by the bindings (bind_*.cpp).
  void setColor(physics::BodyId id, const Eigen::Vector3f& rgb);
  void addExpectation(Expectation e) { m_expectations.push_back(std::move(e)); }
  const ScenarioOptions& options() const { return m_options; }
  void setHudText(std::vector<std::string> lines) { m_hudText = std::move(lines); }
  static ScenarioHost* from(lua_State* L);

 private:
  ScenarioHost(const ModInfo& mod, physics::World& world, const ScenarioOptions& options);
  void buildEnvironment();
  bool callLifecycle(const char* name, int nargs, bool* paused, int* consecutive);
  void pushCtx(double time_s, double dt_s, std::int64_t step);

  LuaVm m_vm;
  ModInfo m_mod;
  physics::World& m_world;
  ScenarioOptions m_options;
  std::string m_file;
  std::string m_title;
  double m_duration_s = 10;
  int m_envRef = 0, m_scenarioRef = 0, m_ctxRef = 0;
  bool m_hasUpdate = false, m_updatePaused = false;
  int m_updateErrors = 0;
  std::vector<ScriptError> m_errors;
  std::vector<Expectation> m_expectations;
  std::vector<std::string> m_hudText;
  std::vector<Eigen::Vector3f> m_colors;  ///< by body slot index
};

/// Registers the `world` table and Body type (bind_world.cpp, bind_body.cpp).
void openWorldBindings(lua_State* L, int envIndex);
void openBodyType(lua_State* L);
void pushBody(lua_State* L, physics::BodyId id);

}  // namespace tumble::script
