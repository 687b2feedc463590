#pragma once
// What scripts ask for that is seen, not simulated: models drawn on bodies
// (body:set_model), static scenery models (world.add_static_model), the
// camera (camera.set_mode), body and rope colours and the lines scripts
// draw (draw_line). Plain data the app reads each frame; script never
// includes render (ARCHITECTURE.md), so loading a model's bounds for a
// collision box goes through SceneSystems, which the app implements.
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/byte_stream.h"
#include "core/math.h"
#include "core/result.h"
#include "physics/body.h"
#include "physics/shape.h"
#include "script/environment_request.h"

namespace tumble::script {

struct ModInfo;

/// Axis-aligned bounds of a model file in its own frame (before scale), m.
struct ModelBox {
  Vec3 min_m = Vec3::Zero(), max_m = Vec3::Zero();
};
/// Every triangle of a model file in its own frame (before scale), for mass
/// properties (world.model_mass_properties).
struct ModelTriangles {
  std::vector<Vec3> vertices_m;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// body:set_model: drawn at body transform * translate(offset) * rotate(rotation) * scale.
struct ModelAttachment {
  physics::BodyId body;
  std::string file;  ///< absolute path
  Vec3 offset_m = Vec3::Zero();
  Quat rotation = Quat::Identity();
  Vec3 scale = Vec3::Ones();
};

/// world.add_static_model: a model placed once; `body` is its static
/// collision body, a mesh or a box (null id when collision = "none").
struct StaticModel {
  std::string file;  ///< absolute path
  Vec3 position_m = Vec3::Zero();
  Quat rotation = Quat::Identity();
  Vec3 scale = Vec3::Ones();
  physics::BodyId body;
};

/// camera.set_mode. Unset optionals keep the app's defaults for the mode.
struct CameraRequest {
  std::string mode = "orbit";          ///< "orbit", "follow", "chase", "hood" or "cockpit"
  std::optional<physics::BodyId> target;
  std::optional<Vec3> offset_m;        ///< chase: eye in the target's frame
  std::optional<Vec3> lookAt_m;        ///< chase: looked-at point in the target's frame
  std::optional<Vec3> eye_m;           ///< hood / cockpit: eye in the target's frame
  std::optional<Vec3> hoodEye_m;       ///< hood only (wins over eye_m for hood), target's frame
  std::optional<Real> stiffness_per_s; ///< chase: spring rate (critically damped)
  std::optional<Real> distance_m;      ///< orbit / follow: distance from the target
  std::string interiorFile;            ///< cockpit: absolute path of the interior model ("" none)
  /// cockpit: centres of the speed and rpm dials in the interior's frame
  /// (origin at the eye, +Z forward), faces towards the driver; drawn with
  /// needles that follow the followed vehicle's telemetry.
  std::optional<Vec3> speedGauge_m, rpmGauge_m;
  Real gaugeRadius_m = Real(0.05);     ///< cockpit: dial radius, m
  std::uint64_t revision = 0;          ///< bumped by every camera.set_mode
};

/// A line a script drew this step (draw_line), world frame.
struct ScriptLine {
  Vec3 a_m, b_m;
  Eigen::Vector3f color;
};

/// hud.set_lap: what the driving HUD's lap widget shows. The scenario keeps
/// its own timer and hands the figures over each step (bind_hud.cpp).
struct LapDisplay {
  bool shown = false;                ///< false until hud.set_lap, again after hud.clear_lap
  double time_s = 0;                 ///< the lap being driven, s
  std::optional<double> last_s;      ///< the previous lap, s
  std::optional<double> best_s;      ///< the best lap (e.g. read with save.read), s
  int gate = 0, gates = 0;           ///< the next gate k of n; 0 of 0: no gates
  int lap = 0, laps = 0;             ///< lap k of n; 0 of 0: not shown
  bool finished = false;             ///< the run is over: the timer stops on screen
};

/// Everything above, owned by the ScenarioHost.
struct Presentation {
  std::vector<ModelAttachment> attachments;  ///< at most one per body (a new one replaces)
  std::vector<StaticModel> statics;
  CameraRequest camera;
  EnvironmentRequest environment;  ///< environment.set (bind_environment.cpp)
  std::uint64_t revision = 0;  ///< bumped whenever attachments or statics change
  LapDisplay lap;               ///< hud.set_lap
  std::vector<Vec3> gates_m;    ///< hud.set_gates: gate centres in order (minimap), m, world

  /// Display colour (linear RGB 0..1) of a body the script made or coloured.
  void setColor(physics::BodyId id, const Eigen::Vector3f& rgb);
  Eigen::Vector3f colorOf(physics::BodyId id) const;
  /// Ground texture drawn on a plane body (render::DrawShape::groundTexture:
  /// -1 the checkerboard, else the terrain texture index); -1 when unset.
  void setGroundTexture(physics::BodyId id, int layer);
  int groundTextureOf(physics::BodyId id) const;
  /// Colour of a rope or cloth by its DeformableSystem id.
  void setDeformableColor(int id, const Eigen::Vector3f& rgb) { m_deformableColors[id] = rgb; }
  Eigen::Vector3f deformableColor(int id) const;
  /// Lines drawn since the last fixed step (the host clears them before on_update).
  const std::vector<ScriptLine>& scriptLines() const { return m_scriptLines; }
  void addScriptLine(const ScriptLine& line);
  void clearScriptLines() { m_scriptLines.clear(); }
  static constexpr std::size_t kMaxScriptLines = 65536;

  /// Snapshots (docs/snapshots.md): everything above but the lines of this
  /// step, so that a run loaded from a snapshot looks as the run without a
  /// split (a body made after on_start keeps its colour and model, a camera
  /// or sky set in on_update stays). Model files are written as "MOD:path"
  /// (`refOf`) and read back through `resolve` (resolveModFile: inside a
  /// mod, or refused).
  void saveState(ByteWriter& w, const std::function<std::string(const std::string&)>& refOf) const;
  /// Reads what saveState wrote, checked whole (every number finite and in
  /// the range the script API allows, every body one `bodyKnown` accepts:
  /// a slot of the world, alive or not, as a model may stay attached to a
  /// removed body; every file resolved) before anything changes. The
  /// revisions move on, so the app reloads models and sky.
  Status restoreState(ByteReader& r, const std::function<Result<std::string>(const std::string&)>& resolve,
                      const std::function<bool(physics::BodyId)>& bodyKnown, std::size_t bodySlots);

 private:
  std::vector<Eigen::Vector3f> m_colors;  ///< by body slot index; x < 0: unset
  std::vector<int> m_groundTextures;      ///< by body slot index; -1: the checkerboard
  std::map<int, Eigen::Vector3f> m_deformableColors;
  std::vector<ScriptLine> m_scriptLines;
};

/// Resolves a model path as scripts write it: "MOD:path/in/mod" or
/// "path/in/mod" (the calling mod). The path must stay inside the mod's
/// folder; the file must exist. `modDirs` maps mod names to their folders.
Result<std::string> resolveModFile(const std::string& ref, const ModInfo& caller,
                                   const std::map<std::string, std::string>& modDirs);
/// Whether `file` (a path resolveModFile gave) is a regular file inside one
/// of the folders of `modDirs` (snapshots check the files they name with it).
bool isFileInMods(const std::string& file, const std::map<std::string, std::string>& modDirs);

}  // namespace tumble::script
