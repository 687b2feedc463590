#pragma once
// The app's side of models and cameras: loads the model files scripts name
// (once each, shared), builds their collision meshes (once per file and
// scale, shared by every placement), turns the scenario's Presentation (script/
// presentation.h) into render::ModelInstances every frame, and drives the
// renderer's camera from camera.set_mode with a CameraRig.
#include <array>
#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "core/result.h"
#include "physics/mesh_shape.h"
#include "render/camera_rig.h"
#include "render/model.h"
#include "render/renderer.h"
#include "script/presentation.h"

namespace tumble::app {

class Scene;

/// Model files by absolute path, loaded on first use. A file that failed
/// keeps its error (asked again, it is not re-read). Owned by the scene:
/// models and collision shapes are freed with it.
class ModelCache {
 public:
  Result<std::shared_ptr<const render::Model>> get(const std::string& file);
  /// Bounds of the model's root covering box, for collision boxes.
  Result<script::ModelBox> bounds(const std::string& file);
  /// Every triangle in model space (render::flattenModel).
  Result<script::ModelTriangles> triangles(const std::string& file);
  /// The object tree as collision data: each node's own triangles in model
  /// space (mirroring node transforms turn the winding back over).
  Result<physics::MeshTreeInput> meshTree(const std::string& file);
  /// The model's collision shape (ShapeType::Mesh, physics::makeMeshShape)
  /// at a placement's scale, built on the first request for this (file,
  /// scale) and shared after that: 40 trees of one file at one scale hold
  /// one node tree, one triangle array and one set of edge flags, not 40.
  /// Scales are compared exactly (a shape is only shared when building it
  /// again would give the same bits). An error names the file.
  Result<physics::Shape> meshShape(const std::string& file, const Vec3& scale);
  std::size_t size() const { return m_models.size(); }
  /// Mesh shapes built so far (one per distinct file and scale that built).
  std::size_t meshShapesBuilt() const { return m_meshShapesBuilt; }
  /// meshShape requests that returned a shape, shared or just built.
  std::size_t meshShapesPlaced() const { return m_meshShapesPlaced; }

 private:
  std::map<std::string, Result<std::shared_ptr<const render::Model>>> m_models;
  using MeshKey = std::pair<std::string, std::array<Real, 3>>;  // file, scale per axis
  std::map<MeshKey, Result<physics::Shape>> m_meshShapes;       // errors are kept too
  std::size_t m_meshShapesBuilt = 0, m_meshShapesPlaced = 0;
};

/// Appends what the scene's scripts asked to draw with models: bodies with
/// body:set_model (interpolated like the shapes) and static models.
void appendModelInstances(const Scene& scene, double alpha, std::vector<render::ModelInstance>& out);

/// Applies camera.set_mode to the renderer's camera and moves it each drawn
/// frame. Without a request the camera stays as the app framed it.
/// Per frame: update() before Scene::snapshot, decorate() after it.
class CameraDirector {
 public:
  /// Places the camera; frameDt_s is real time since the last drawn frame
  /// (0 for a single shot). In Cockpit mode the followed body's own model is
  /// hidden from the next snapshot (the eye is inside it) and decorate()
  /// draws the interior instead.
  void update(Scene& scene, double alpha, float frameDt_s, render::Camera& camera);
  /// Adds the cockpit interior to `frame` in Cockpit mode, with its dials'
  /// needles at the followed vehicle's speed and rpm.
  void decorate(const Scene& scene, double alpha, const render::Camera& camera, render::FrameSnapshot& frame) const;
  /// True once a scenario named a body to follow.
  bool hasTarget() const { return m_target.has_value(); }

 private:
  render::CameraRig m_rig;
  std::uint64_t m_revision = 0;
  std::optional<physics::BodyId> m_target;
  std::string m_interior;
  std::optional<Vec3> m_speedGauge_m, m_rpmGauge_m;  // interior frame
  Real m_gaugeRadius_m = Real(0.05);
};

}  // namespace tumble::app
