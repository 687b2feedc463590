#pragma once
// A scene: what one scenario run creates. Subsystems are created only when
// used (ARCHITECTURE.md "Leave out what a scene does not need"): the world
// always, the script host when the scenario has a file, the renderer only
// for play or --screenshot. `subsystems()` lists what exists, for the report.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/result.h"
#include "physics/world.h"
#include "render/renderer.h"
#include "script/scenario_host.h"

namespace tumble::app {

struct SceneOptions {
  std::string scenarioRef = "base:drop";  ///< MOD:SCENARIO
  std::vector<std::string> modDirs;       ///< extra --mods folders
  std::map<std::string, std::string> sets;  ///< --set KEY=VALUE (physics.* go to the world)
  double dt_s = 1.0 / 60.0;
  int substeps = 0;  ///< 0: the world's default
  std::string integrator = "symplectic_euler";
  std::uint64_t seed = 1;
  /// terrain.* settings a scenario asks for by default (terrain_scene.h lists
  /// the keys); --set terrain.* wins. Empty: no terrain unless --set asks.
  std::map<std::string, std::string> terrainDefaults;
};

class TerrainScene;

/// Integrators the rigid-body world offers (more come with the numerics lab).
const std::vector<std::string>& rigidBodyIntegrators();

class Scene {
 public:
  static Result<std::unique_ptr<Scene>> create(const SceneOptions& options);
  ~Scene();

  physics::World& world() { return *m_world; }
  script::ScenarioHost& host() { return *m_host; }
  const script::ScenarioHost& host() const { return *m_host; }
  const SceneOptions& options() const { return m_options; }
  /// The fixed step now (s): --dt, or what the script asked for (world.set_dt).
  double dt_s() const { return m_host->requestedDt_s() > 0 ? m_host->requestedDt_s() : m_options.dt_s; }
  std::string name() const { return m_modName + ":" + m_scenarioName; }
  std::vector<std::string> subsystems() const;
  void noteSubsystem(const std::string& name) { m_extraSubsystems.push_back(name); }
  /// A terrain exists only when asked for (--set terrain.*, terrainDefaults).
  bool hasTerrain() const { return m_terrain != nullptr; }
  /// Registers every static body over the terrain in its tree of static
  /// objects (call after the scenario's on_start made them). No terrain: nothing.
  void registerStaticObjects();

  /// Builds what the renderer reads: every body as a shape with its colour.
  /// alpha in [0, 1] interpolates between the previous and current step.
  void snapshot(render::FrameSnapshot& out, double alpha) const;
  /// Remembers the current state as "previous" (call before each step).
  void savePreviousState();

 private:
  SceneOptions m_options;
  std::string m_modName, m_scenarioName;
  std::unique_ptr<TerrainScene> m_terrain;  ///< before m_world: the world points at its height field
  std::unique_ptr<physics::World> m_world;
  std::unique_ptr<script::ScenarioHost> m_host;
  std::vector<Vec3> m_prevPosition;
  std::vector<Quat> m_prevOrientation;
  std::vector<std::string> m_extraSubsystems;
};

}  // namespace tumble::app
