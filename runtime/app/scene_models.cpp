#include "app/scene_models.h"

#include <algorithm>
#include <cmath>

#include "app/scene.h"
#include "core/log.h"
#include "core/math.h"
#include "vehicle/vehicle_system.h"

namespace tumble::app {

Result<std::shared_ptr<const render::Model>> ModelCache::get(const std::string& file) {
  auto it = m_models.find(file);
  if (it == m_models.end()) it = m_models.emplace(file, render::loadModel(file)).first;
  if (!it->second.ok()) return makeError(it->second.error());
  return it->second.value();
}

Result<script::ModelBox> ModelCache::bounds(const std::string& file) {
  auto model = get(file);
  if (!model) return makeError(model.error());
  const render::BoundingBox& box = (*model)->nodes[0].coverBox;
  return script::ModelBox{box.min.cast<Real>(), box.max.cast<Real>()};
}

Result<script::ModelTriangles> ModelCache::triangles(const std::string& file) {
  auto model = get(file);
  if (!model) return makeError(model.error());
  const render::FlatMesh flat = render::flattenModel(**model);
  script::ModelTriangles out;
  out.vertices_m.reserve(flat.positions.size());
  for (const Eigen::Vector3f& p : flat.positions) out.vertices_m.push_back(p.cast<Real>());
  out.triangles = flat.triangles;
  return out;
}

Result<physics::MeshTreeInput> ModelCache::meshTree(const std::string& file) {
  auto model = get(file);
  if (!model) return makeError(model.error());
  const render::Model& m = **model;
  physics::MeshTreeInput tree;
  tree.nodes.resize(m.nodes.size());
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    const render::ModelNode& node = m.nodes[i];
    physics::MeshTreeNodeInput& out = tree.nodes[i];
    out.parent = node.parent;
    out.name = node.name;
    const bool mirrored = node.toModel.topLeftCorner<3, 3>().determinant() < 0;
    for (int meshIndex : node.meshes) {
      const render::ModelMesh& mesh = m.meshes[std::size_t(meshIndex)];
      const auto base = static_cast<std::uint32_t>(out.vertices_m.size());
      for (const Eigen::Vector3f& p : mesh.positions)
        out.vertices_m.push_back((node.toModel * p.homogeneous()).head<3>().cast<Real>());
      for (const auto& t : mesh.triangles)
        out.triangles.push_back(mirrored ? std::array<std::uint32_t, 3>{base + t[0], base + t[2], base + t[1]}
                                         : std::array<std::uint32_t, 3>{base + t[0], base + t[1], base + t[2]});
    }
  }
  return tree;
}

Result<physics::Shape> ModelCache::meshShape(const std::string& file, const Vec3& scale) {
  const MeshKey key{file, {scale.x(), scale.y(), scale.z()}};
  auto it = m_meshShapes.find(key);
  if (it == m_meshShapes.end()) {
    Result<physics::Shape> built = [&]() -> Result<physics::Shape> {
      auto tree = meshTree(file);
      if (!tree) return makeError(tree.error());
      auto shape = physics::makeMeshShape(*tree, scale);
      if (!shape) return makeError(file + ": " + shape.error());
      ++m_meshShapesBuilt;
      return shape;
    }();
    it = m_meshShapes.emplace(key, std::move(built)).first;
  }
  if (!it->second.ok()) return makeError(it->second.error());
  ++m_meshShapesPlaced;
  return it->second.value();
}

namespace {

render::ModelInstance instanceAt(const std::shared_ptr<const render::Model>& model, const Vec3& position,
                                 const Quat& rotation, const Vec3& scale) {
  render::ModelInstance instance;
  instance.model = model;
  instance.position = position.cast<float>();
  instance.orientation = rotation.cast<float>();
  instance.scale = scale.cast<float>();
  return instance;
}

}  // namespace

void appendModelInstances(const Scene& scene, double alpha, std::vector<render::ModelInstance>& out) {
  const script::Presentation& p = scene.host().presentation();
  for (const script::ModelAttachment& a : p.attachments) {
    if (scene.hiddenModelBody() && *scene.hiddenModelBody() == a.body) continue;  // the cockpit's own car
    const auto pose = scene.bodyPose(a.body, alpha);
    if (!pose) continue;  // the body was removed
    auto model = scene.models().get(a.file);
    if (!model) continue;  // checked when the script attached it
    const Quat q = pose->orientation.cast<Real>();
    out.push_back(instanceAt(*model, pose->position_m.cast<Real>() + q * a.offset_m, q * a.rotation, a.scale));
  }
  for (const script::StaticModel& s : p.statics) {
    auto model = scene.models().get(s.file);
    if (!model) continue;
    out.push_back(instanceAt(*model, s.position_m, s.rotation, s.scale));
  }
}

void CameraDirector::update(Scene& scene, double alpha, float frameDt_s, render::Camera& camera) {
  const script::CameraRequest& request = scene.host().presentation().camera;
  if (request.revision != m_revision) {
    m_revision = request.revision;
    if (auto mode = render::cameraModeFromName(request.mode)) camera.mode = *mode;
    m_target = request.target;
    m_interior = request.interiorFile;
    m_speedGauge_m = request.speedGauge_m;
    m_rpmGauge_m = request.rpmGauge_m;
    m_gaugeRadius_m = request.gaugeRadius_m;
    render::CameraRigSettings s;  // defaults, then what the script gave
    if (request.offset_m) s.chaseOffset_m = request.offset_m->cast<float>();
    if (request.lookAt_m) s.chaseLookAt_m = request.lookAt_m->cast<float>();
    if (request.stiffness_per_s) s.chaseStiffness_per_s = float(*request.stiffness_per_s);
    if (request.eye_m) s.hoodEye_m = s.cockpitEye_m = request.eye_m->cast<float>();
    if (request.hoodEye_m) s.hoodEye_m = request.hoodEye_m->cast<float>();
    if (request.distance_m) camera.distance_m = float(*request.distance_m);
    m_rig.settings = s;
    m_rig.reset();
    camera.vehicleModes = m_target.has_value();
  }
  // The cockpit hides the car's own model when an interior is drawn in its
  // place; an open car (no interior) keeps its model: its seat and cage.
  const bool cockpit = m_target && camera.mode == render::CameraMode::Cockpit && !m_interior.empty();
  scene.hideModelOf(cockpit ? m_target : std::nullopt);
  if (!m_target) return;
  const auto pose = scene.bodyPose(*m_target, alpha);
  if (!pose) return;  // the followed body is gone: the camera stays where it was
  m_rig.update(*pose, frameDt_s, camera);
}

void CameraDirector::decorate(const Scene& scene, double alpha, const render::Camera& camera,
                              render::FrameSnapshot& frame) const {
  if (!m_target || camera.mode != render::CameraMode::Cockpit || m_interior.empty()) return;
  const auto pose = scene.bodyPose(*m_target, alpha);
  if (!pose) return;
  auto model = scene.models().get(m_interior);
  if (!model) return;
  render::ModelInstance interior;
  interior.model = *model;
  interior.position = pose->position_m + pose->orientation * m_rig.settings.cockpitEye_m;
  interior.orientation = pose->orientation;
  frame.models.push_back(interior);
  if (!m_speedGauge_m && !m_rpmGauge_m) return;
  // The dials read the vehicle whose chassis the camera follows.
  const vehicle::VehicleSystem* vehicles = scene.vehiclesIfAny();
  if (!vehicles) return;
  std::optional<vehicle::VehicleTelemetry> t;
  Real maxRpm = 0;
  vehicles->forEach([&](vehicle::VehicleId id) {
    if (vehicles->chassis(id) != *m_target) return;
    t = vehicles->telemetry(id);
    maxRpm = vehicles->def(id).engine.maxRpm;
  });
  if (!t) return;
  // A dark dial facing the driver with a scale and a needle from its centre:
  // 270 degrees from lower left (zero) through the top to lower right (full
  // scale), as the driver sees it (+X is the driver's left). Scale marks
  // every `minor` of full scale, longer every `major`; marks from `redFrom`
  // (a fraction of full scale) on are red.
  const float r = float(m_gaugeRadius_m);
  auto dialAngle = [](double fraction) { return (-135.0 + 270.0 * std::clamp(fraction, 0.0, 1.0)) * kPi / 180.0; };
  auto onDial = [&](const Vec3& centre_m, const Eigen::Vector3f& offset_m) {
    return Eigen::Vector3f(interior.position + pose->orientation * (centre_m.cast<float>() + offset_m));
  };
  auto dial = [&](const Vec3& centre_m, double fraction, double minor, int major, double redFrom) {
    // A round face: a flat cylinder whose axis (local Y) points at the driver.
    render::DrawShape face;
    face.kind = render::ShapeKind::Cylinder;
    face.position = onDial(centre_m, {0, 0, -0.004f});
    face.orientation = pose->orientation * Eigen::Quaternionf(Eigen::AngleAxisf(float(kPi) / 2, Eigen::Vector3f::UnitX()));
    face.radius_m = r;
    face.halfHeight_m = 0.002f;
    face.color = {0.03f, 0.03f, 0.035f};
    frame.shapes.push_back(face);
    // The marks, and one at full scale (the rev limiter) when the steps miss it.
    const int marks = std::min(40, int(std::floor(1.0 / minor + 1e-9)));
    const bool endMark = marks * minor < 1.0 - 1e-6;
    for (int k = 0; k <= marks + (endMark ? 1 : 0); ++k) {
      const double at = k > marks ? 1.0 : k * minor;
      const bool big = k > marks || k % major == 0;
      const Eigen::Quaternionf spin(Eigen::AngleAxisf(float(dialAngle(at)), Eigen::Vector3f::UnitZ()));
      const float length = big ? 0.16f * r : 0.09f * r;
      render::DrawShape mark;
      mark.position = onDial(centre_m, spin * Eigen::Vector3f(0, 0.9f * r - length / 2, 0) - Eigen::Vector3f(0, 0, 0.006f));
      mark.orientation = pose->orientation * spin;
      mark.halfExtents = {big ? 0.025f * r : 0.015f * r, length / 2, 0.001f};
      mark.color = at >= redFrom - 1e-9 ? Eigen::Vector3f(0.85f, 0.06f, 0.05f) : Eigen::Vector3f(0.85f, 0.85f, 0.82f);
      frame.shapes.push_back(mark);
    }
    const Eigen::Quaternionf spin(Eigen::AngleAxisf(float(dialAngle(fraction)), Eigen::Vector3f::UnitZ()));
    render::DrawShape needle;
    needle.position = onDial(centre_m, spin * Eigen::Vector3f(0, 0.45f * r, 0) - Eigen::Vector3f(0, 0, 0.008f));
    needle.orientation = pose->orientation * spin;
    needle.halfExtents = {0.06f * r, 0.45f * r, 0.002f};
    needle.color = {1.0f, 0.42f, 0.05f};
    frame.shapes.push_back(needle);
  };
  // The speedometer reads to 200 km/h, marked every 20 and long every 40;
  // the rev counter to the rev limiter, marked every 1000 rpm (every 2000
  // past 12 000, and so on), red over the last mark's step below the limiter.
  constexpr double kFullScale_mps = 200.0 / 3.6;
  if (m_speedGauge_m) dial(*m_speedGauge_m, std::abs(double(t->speed_mps)) / kFullScale_mps, 0.1, 2, 2.0);
  if (m_rpmGauge_m && maxRpm > 0) {
    const double step_rpm = 1000.0 * std::max(1.0, std::ceil(double(maxRpm) / 12000.0));
    const double step = step_rpm / double(maxRpm);
    dial(*m_rpmGauge_m, double(t->rpm) / double(maxRpm), step, 1, 1.0 - step);
  }
}

}  // namespace tumble::app
