#pragma once
// What scripts ask for that is seen, not simulated: models drawn on bodies
// (body:set_model), static scenery models (world.add_static_model) and the
// camera (camera.set_mode). Plain data the app reads each frame; script
// never includes render (ARCHITECTURE.md), so loading a model's bounds for
// a collision box goes through ModelBoundsFn, which the app provides.
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "physics/body.h"
#include "physics/shape.h"

namespace tumble::script {

struct ModInfo;

/// Axis-aligned bounds of a model file in its own frame (before scale), m.
struct ModelBox {
  Vec3 min_m = Vec3::Zero(), max_m = Vec3::Zero();
};
/// Loads (or finds in a cache) the model at an absolute path and returns its
/// bounds, or an error naming the file and what is wrong with it.
using ModelBoundsFn = std::function<Result<ModelBox>(const std::string& file)>;

/// Every triangle of a model file in its own frame (before scale), for mass
/// properties (world.model_mass_properties).
struct ModelTriangles {
  std::vector<Vec3> vertices_m;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};
using ModelTrianglesFn = std::function<Result<ModelTriangles>(const std::string& file)>;

/// The collision shape of a model file at a placement's scale (world.add_static_model
/// with collision = "mesh"): a ShapeType::Mesh built from the model's object
/// tree (physics::makeMeshShape). The app builds one per (file, scale) and
/// hands the same immutable shape to every placement that asks again; an
/// error names the file and what is wrong with it.
using ModelMeshShapeFn = std::function<Result<physics::Shape>(const std::string& file, const Vec3& scale)>;

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
  std::optional<Real> stiffness_per_s; ///< chase: spring rate (critically damped)
  std::optional<Real> distance_m;      ///< orbit / follow: distance from the target
  std::string interiorFile;            ///< cockpit: absolute path of the interior model ("" none)
  std::uint64_t revision = 0;          ///< bumped by every camera.set_mode
};

/// Everything above, owned by the ScenarioHost.
struct Presentation {
  std::vector<ModelAttachment> attachments;  ///< at most one per body (a new one replaces)
  std::vector<StaticModel> statics;
  CameraRequest camera;
  std::uint64_t revision = 0;  ///< bumped whenever attachments or statics change
};

/// Resolves a model path as scripts write it: "MOD:path/in/mod" or
/// "path/in/mod" (the calling mod). The path must stay inside the mod's
/// folder; the file must exist. `modDirs` maps mod names to their folders.
Result<std::string> resolveModFile(const std::string& ref, const ModInfo& caller,
                                   const std::map<std::string, std::string>& modDirs);

}  // namespace tumble::script
