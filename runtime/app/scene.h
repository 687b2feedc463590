#pragma once
// A scene: what one scenario run creates, and the owner of every system in
// it. Subsystems are created only when used (ARCHITECTURE.md "Leave out what
// a scene does not need"): the world and the script host always; terrain
// when the scenario asks for one; joints, vehicles, particles and ropes or
// cloth on the first script call that needs them (Scene implements
// script::SceneSystems, the interface scripts reach the scene through); the
// renderer only for play or --screenshot. `subsystems()` lists what exists,
// for the report. app/fixed_step.cpp steps them; nothing else does.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "audio/audio_system.h"
#include "audio/listener_motion.h"
#include "app/error_audit.h"
#include "core/result.h"
#include "input/input_system.h"
#include "physics/world.h"
#include "render/camera_rig.h"
#include "render/renderer.h"
#include "script/scenario_host.h"
#include "script/scene_systems.h"

namespace tumble::physics {
class JointSystem;
class DeformableSystem;
}
namespace tumble::vehicle {
class VehicleSystem;
}
namespace tumble::particles {
class ParticleSystem;
}

namespace tumble::app {

struct SceneOptions {
  std::string scenarioRef = "base:drop";  ///< MOD:SCENARIO
  std::vector<std::string> modDirs;       ///< extra --mods folders
  std::map<std::string, std::string> sets;  ///< --set KEY=VALUE (physics.* go to the world)
  double dt_s = 1.0 / 60.0;
  int substeps = 0;  ///< 0: the world's default
  int threads = 0;   ///< threads of the physics step (--threads); 0: the world's default, 1
  std::string integrator;  ///< --integrator; empty: the scenario's field, else symplectic_euler
  std::uint64_t seed = 1;
  /// terrain.* settings a scenario asks for by default (terrain_scene.h lists
  /// the keys); --set terrain.* wins. Empty: no terrain unless --set asks.
  std::map<std::string, std::string> terrainDefaults;
  /// Read the mod's saved tunable overrides (script/tunables.h). `play` does;
  /// `run` does not, so a headless run depends only on its command line.
  bool tuneOverrides = false;
  /// Where the scenario's save.read / save.write files go; empty: the
  /// player's data folder (script/bind_save.cpp).
  std::string saveDir;
  /// The Lua budgets the scenario runs under.
  script::VmLimits limits;
  /// The input actions; unset: those of base and the scenario's mod with its
  /// dependencies (their bindings.lua). Tools and tests that drive a
  /// scenario with their own actions set it.
  std::optional<input::BindingSet> bindings;
  /// Where the scene's sound goes: Silent (headless `run`, play --mute; no
  /// device), Device (play) or Loopback (run --audio-out: rendered offline).
  audio::AudioOutput audioOutput = audio::AudioOutput::Silent;
  audio::AudioVolumes volumes;  ///< the player's volume settings (play)
  /// Test switch (`run --freeze`): scripts, timers and input run, but no
  /// simulation system steps (bodies, joints, vehicles, ropes, cloth), so a
  /// scenario's expectations can be checked against a world that never moves.
  bool freezePhysics = false;
  /// A tunables overrides file to read instead of the mod's own (a replay's
  /// recorded values); empty: the mod's, when tuneOverrides is set.
  std::string tuneOverridesFile;
};

class TerrainScene;
class ModelCache;

/// Integrators the rigid-body world offers (physics/integrate.h), default first.
const std::vector<std::string>& rigidBodyIntegrators();

class Scene final : public script::SceneSystems {
 public:
  static Result<std::unique_ptr<Scene>> create(const SceneOptions& options);
  /// The parameters the scenario declares (its `params` field; nothing when
  /// it has none), read by loading the scenario file without running it:
  /// no terrain, no on_start. Tools check --set names against it.
  static Result<script::ParamDecls> declaredParams(const SceneOptions& options);
  /// The scenario's title and declared parameters, read the same way (the
  /// main menu's list of scenarios).
  struct Summary {
    std::string title;
    script::ParamDecls params;
  };
  static Result<Summary> summarize(const SceneOptions& options);
  ~Scene();

  physics::World& world() override { return *m_world; }
  const physics::World& world() const { return *m_world; }
  script::ScenarioHost& host() { return *m_host; }
  /// Input actions of base and the scenario's mod with its dependencies
  /// (their bindings.lua, merged in load order). Scripts read them; play
  /// feeds SDL events in; headless runs only see injected values.
  input::InputSystem& input() override { return *m_input; }
  const script::ScenarioHost& host() const { return *m_host; }
  const SceneOptions& options() const { return m_options; }

  // The systems scripts create on first use (script::SceneSystems).
  physics::JointSystem& joints() override;
  physics::JointSystem* jointsIfAny() override { return m_joints.get(); }
  const physics::JointSystem* jointsIfAny() const { return m_joints.get(); }
  vehicle::VehicleSystem& vehicles() override;
  vehicle::VehicleSystem* vehiclesIfAny() override { return m_vehicles.get(); }
  const vehicle::VehicleSystem* vehiclesIfAny() const { return m_vehicles.get(); }
  particles::ParticleSystem& particles() override;
  particles::ParticleSystem* particlesIfAny() override { return m_particles.get(); }
  const particles::ParticleSystem* particlesIfAny() const { return m_particles.get(); }
  physics::DeformableSystem& deformables() override;
  physics::DeformableSystem* deformablesIfAny() override { return m_deformables.get(); }
  const physics::DeformableSystem* deformablesIfAny() const { return m_deformables.get(); }
  /// The audio system, made on first use (a script's sound, or the first
  /// step with a vehicle or a collision when the output is not Silent). A
  /// Device that cannot open falls back to Silent with one message.
  audio::AudioSystem& audio() override;
  audio::AudioSystem* audioIfAny() { return m_audio.get(); }
  void attachSound(std::uint64_t sound, physics::BodyId body) override { m_soundBodies[sound] = body; }
  /// Script sounds following bodies (app/scene_audio.cpp moves them).
  std::map<std::uint64_t, physics::BodyId>& soundBodies() { return m_soundBodies; }
  /// The listener: play sets it to the camera each frame; unset, it rides
  /// behind the first vehicle like the chase camera, else at the origin.
  struct Listener {
    Vec3 position_m = Vec3::Zero(), forward = Vec3(0, 0, -1), up = Vec3::UnitY();
  };
  void setListener(const Listener& l) { m_listener = l; }
  const std::optional<Listener>& listener() const { return m_listener; }
  /// The listener's velocity from its movement between audio steps (Doppler).
  audio::ListenerMotion& listenerMotion() { return m_listenerMotion; }
  /// The joint solver (--set physics.joint_solver, else the scenario's
  /// joint_solver field, else impulse; world.set_joint_solver switches it).
  physics::JointSolverKind jointSolver() const override { return m_jointSolver; }
  void setJointSolver(physics::JointSolverKind kind) override;
  /// Largest joint anchor separation seen (m), 0 without joints: the run
  /// report's joint_error_max_m.
  double jointErrorMax_m() const;
  /// The run report's energy and momentum figures, kept by stepScene.
  /// After each World step: the first time in a run that a physics cost cap
  /// acted (WorldSettings::maxContactPairsPerBody,
  /// JointSettings::lagrangeMaxFactorWorkPerRow), a warning says what was
  /// capped and why; the run report keeps the counts.
  void warnOnceOfCostCaps();
  ErrorAudit& errorAudit() { return m_errorAudit; }
  const ErrorAudit& errorAudit() const { return m_errorAudit; }
  /// The fixed step now (s): --dt, or what the script asked for (world.set_dt).
  double dt_s() const override { return m_requestedDt_s > 0 ? m_requestedDt_s : m_options.dt_s; }
  void requestDt(double dt_s) override { m_requestedDt_s = dt_s; }
  Result<script::ModelBox> modelBounds(const std::string& file) override;
  Result<script::ModelTriangles> modelTriangles(const std::string& file) override;
  Result<physics::Shape> modelMeshShape(const std::string& file, const Vec3& scale) override;

  /// on_start (the scenario makes its bodies), then every static body goes
  /// into the terrain's tree. on_finish at the end.
  void start();
  void finish(double time_s, long long step);
  std::string name() const { return m_modName + ":" + m_scenarioName; }
  /// The integrator the world runs (the run report's `integrator`).
  std::string integratorName() const { return physics::bodyIntegratorName(m_world->settings().integrator); }
  std::vector<std::string> subsystems() const;
  void noteSubsystem(const std::string& name) { m_extraSubsystems.push_back(name); }
  /// A terrain exists only when asked for (--set terrain.*, terrainDefaults).
  bool hasTerrain() const { return m_terrain != nullptr; }
  /// The terrain, or null without one.
  const TerrainScene* terrainScene() const { return m_terrain.get(); }
  /// Registers every static body over the terrain in its tree of static
  /// objects (call after the scenario's on_start made them). No terrain: nothing.
  void registerStaticObjects();

  /// Builds what the renderer reads: every body as a shape with its colour.
  /// alpha in [0, 1] interpolates between the previous and current step.
  /// Bodies a model draws are left to the model, unless the collision view
  /// is on.
  void snapshot(render::FrameSnapshot& out, double alpha) const;
  /// Collision view (render::Controls::collisionView, F3 when playing):
  /// snapshot draws what collides instead of what models show. Every body
  /// is drawn as its collision shape, bodies with models too (a car as its
  /// chassis box, a static model as its box or mesh); static triangle
  /// meshes as wireframe lines, creases and open borders (the edges that
  /// make contacts) bright, flat seams dim. Models are left out; vehicle
  /// wheels (ray casts) stay.
  void setCollisionView(bool on) { m_collisionView = on; }
  bool collisionView() const { return m_collisionView; }
  /// The particles part of snapshot(): billboards of every live particle.
  void snapshotParticles(render::FrameSnapshot& out, double alpha) const;
  /// Vehicle wheels (ray casts, not bodies), ropes, cloth and script lines.
  void snapshotVehiclesAndLines(render::FrameSnapshot& out, double alpha) const;
  /// Hot reload of a saved bindings.lua: the mods' bindings are read again
  /// and replace the actions (the player's overrides and the contexts'
  /// on/off state are kept). With a problem nothing changes and the error
  /// names the file and line.
  Status reloadBindings();
  /// Remembers the current state as "previous" (call before each step).
  void savePreviousState();
  /// A body's pose interpolated like the snapshot; nullopt for a removed body.
  std::optional<render::BodyPose> bodyPose(physics::BodyId id, double alpha) const;
  /// The body whose model the snapshot leaves out (the car around a cockpit
  /// camera; CameraDirector sets it), or none.
  void hideModelOf(std::optional<physics::BodyId> body) { m_hiddenModelBody = body; }
  const std::optional<physics::BodyId>& hiddenModelBody() const { return m_hiddenModelBody; }
  /// Model files scripts named (body:set_model, world.add_static_model);
  /// loading on first use does not change the scene, so const may load.
  ModelCache& models() const { return *m_models; }

 private:
  /// create(), or with scriptOnly just the world and the loaded scenario
  /// file (declaredParams()).
  static Result<std::unique_ptr<Scene>> build(const SceneOptions& options, bool scriptOnly);
  SceneOptions m_options;
  std::string m_modName, m_scenarioName;
  std::unique_ptr<ModelCache> m_models;     ///< before m_host: the host's modelBounds uses it
  std::unique_ptr<TerrainScene> m_terrain;  ///< before m_world: the world points at its height field
  std::unique_ptr<physics::World> m_world;
  std::unique_ptr<input::InputSystem> m_input;
  // Created on first use; declared after the world they hold on to, so they
  // go first (vehicles before joints).
  std::unique_ptr<physics::JointSystem> m_joints;
  std::unique_ptr<vehicle::VehicleSystem> m_vehicles;
  std::unique_ptr<particles::ParticleSystem> m_particles;
  std::unique_ptr<physics::DeformableSystem> m_deformables;
  std::unique_ptr<audio::AudioSystem> m_audio;
  std::map<std::uint64_t, physics::BodyId> m_soundBodies;
  std::optional<Listener> m_listener;
  audio::ListenerMotion m_listenerMotion;
  physics::JointSolverKind m_jointSolver = physics::JointSolverKind::Impulse;  ///< JointSettings' default
  double m_requestedDt_s = 0;  ///< world.set_dt, 0 = none
  std::unique_ptr<script::ScenarioHost> m_host;  ///< last: scripts reach every system above
  std::vector<Vec3> m_prevPosition;
  std::vector<Quat> m_prevOrientation;
  /// Render meshes of the physics hulls seen so far (keyed by hull; the hull
  /// is kept alive so its address is never reused by another one).
  struct HullMesh {
    std::shared_ptr<const physics::ConvexHull> hull;
    std::shared_ptr<const render::ConvexMeshData> mesh;
  };
  mutable std::map<const physics::ConvexHull*, HullMesh> m_hullMeshes;
  std::shared_ptr<const render::ConvexMeshData> meshOf(const std::shared_ptr<const physics::ConvexHull>& hull) const;
  /// Wireframes of the mesh shapes seen so far in the collision view: each
  /// distinct triangle edge once, in the body frame (keyed and kept alive
  /// like m_hullMeshes).
  struct WireEdge {
    Eigen::Vector3f a_m, b_m;
    bool crease = true;  ///< an active edge (convex crease or open border): it makes contacts
  };
  struct MeshWire {
    std::shared_ptr<const physics::MeshShape> mesh;
    std::vector<WireEdge> edges;
  };
  mutable std::map<const physics::MeshShape*, MeshWire> m_meshWires;
  const std::vector<WireEdge>& wireOf(const std::shared_ptr<const physics::MeshShape>& mesh) const;
  std::vector<std::string> m_extraSubsystems;
  std::optional<physics::BodyId> m_hiddenModelBody;
  bool m_collisionView = false;
  ErrorAudit m_errorAudit;
  bool m_warnedPairCap = false, m_warnedJointCap = false;
};

}  // namespace tumble::app
