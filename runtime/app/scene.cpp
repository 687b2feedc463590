#include "app/scene.h"

#include <algorithm>
#include <sstream>

#include "app/paths.h"
#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "script/mods.h"
#if TUMBLE_HAVE_TERRAIN
#include "app/terrain_scene.h"
#endif

namespace tumble::app {

const std::vector<std::string>& rigidBodyIntegrators() {
  static const std::vector<std::string> names{"symplectic_euler"};
  return names;
}

namespace {

template <typename T>
Status parseSetting(const std::string& key, const std::string& text, T* out) {
  std::istringstream in(text);
  T v{};
  if constexpr (std::is_same_v<T, bool>) {
    if (text == "true" || text == "1") v = true;
    else if (text == "false" || text == "0") v = false;
    else return makeError("--set " + key + "=" + text + ": expected true or false");
  } else {
    in >> v;
    if (!in || !in.eof()) return makeError("--set " + key + "=" + text + ": expected a number");
  }
  *out = v;
  return Ok{};
}

// physics.* settings from --set, applied to the world before the script runs.
Status applyPhysicsSetting(physics::WorldSettings& s, const std::string& key, const std::string& value) {
  const std::string k = key.substr(std::string("physics.").size());
  Status st = Ok{};
  double d = 0;
  int i = 0;
  bool b = false;
  if (k == "substeps") {
    if (!(st = parseSetting(key, value, &i))) return st;
    if (i < 1 || i > 1000) return makeError("--set " + key + ": substeps must be 1..1000");
    s.substeps = i;
  } else if (k == "iterations") {
    if (!(st = parseSetting(key, value, &i))) return st;
    if (i < 1 || i > 1000) return makeError("--set " + key + ": iterations must be 1..1000");
    s.velocityIterations = i;
  } else if (k == "relax_iterations") {
    if (!(st = parseSetting(key, value, &i))) return st;
    if (i < 0 || i > 1000) return makeError("--set " + key + ": relax_iterations must be 0..1000");
    s.relaxIterations = i;
  } else if (k == "soft_contacts") {
    if (!(st = parseSetting(key, value, &b))) return st;
    s.softContacts = b;
  } else if (k == "sleep") {
    if (!(st = parseSetting(key, value, &b))) return st;
    s.enableSleep = b;
  } else if (k == "baumgarte") {
    if (!(st = parseSetting(key, value, &d))) return st;
    if (!(d > 0 && d <= 1)) return makeError("--set " + key + ": baumgarte must be in (0, 1]");
    s.baumgarte = Real(d);
  } else if (k == "solver_tolerance") {
    if (!(st = parseSetting(key, value, &d))) return st;
    if (!(d >= 0 && d < 1)) return makeError("--set " + key + ": solver_tolerance must be in [0, 1)");
    s.solverTolerance = Real(d);
  } else if (k == "gravity") {
    if (!(st = parseSetting(key, value, &d))) return st;
    s.gravity_mps2 = Vec3(0, Real(-d), 0);
  } else {
    return makeError("--set " + key +
                     ": unknown physics setting (known: physics.substeps, physics.iterations, "
                     "physics.relax_iterations, physics.soft_contacts, physics.sleep, physics.baumgarte, "
                     "physics.solver_tolerance, physics.gravity)");
  }
  return Ok{};
}

}  // namespace

Result<std::unique_ptr<Scene>> Scene::create(const SceneOptions& options) {
  auto ref = script::parseScenarioRef(options.scenarioRef);
  if (!ref) return makeError(ref.error());
  if (!(options.dt_s > 0 && options.dt_s <= 1)) return makeError("--dt must be a time step in (0, 1] seconds");
  const auto& integrators = rigidBodyIntegrators();
  if (std::find(integrators.begin(), integrators.end(), options.integrator) == integrators.end()) {
    std::string known;
    for (auto& n : integrators) known += (known.empty() ? "" : ", ") + n;
    return makeError("--integrator " + options.integrator + ": the rigid-body world offers " + known);
  }
  auto scene = std::unique_ptr<Scene>(new Scene());
  scene->m_options = options;
  scene->m_modName = ref->first;
  scene->m_scenarioName = ref->second;

  script::ModRegistry registry = script::ModRegistry::discover(modSearchDirs(options.modDirs));
  const script::ModInfo* mod = registry.find(ref->first);
  if (!mod) {
    std::string msg = "mod \"" + ref->first + "\" not found";
    std::string known;
    for (auto& m : registry.mods()) known += (known.empty() ? "" : ", ") + m.name;
    msg += " (found: " + (known.empty() ? std::string("none") : known) + ")";
    for (auto& p : registry.problems()) msg += "\n  " + p.text();
    return makeError(msg);
  }

  physics::WorldSettings ws;
  if (options.substeps > 0) ws.substeps = options.substeps;
  script::ScenarioOptions so;
  so.seed = options.seed;
  so.scriptsDir = scriptsDir();
  std::map<std::string, std::string> terrainSettings = options.terrainDefaults;
  for (const auto& [key, value] : options.sets) {
    if (key.rfind("terrain.", 0) == 0) {
      terrainSettings[key] = value;
    } else if (key.rfind("physics.", 0) == 0) {
      if (auto st = applyPhysicsSetting(ws, key, value); !st) return makeError(st.error());
    } else {
      so.params[key] = value;
    }
  }
  scene->m_world = std::make_unique<physics::World>(ws);
  auto host = script::ScenarioHost::load(*mod, ref->second, *scene->m_world, so);
  if (!host) return makeError(host.error());
  scene->m_host = std::move(host.value());
  // The scenario's own terrain = {...} comes first; --set terrain.* overrides.
  for (const auto& [key, value] : scene->m_host->terrainRequest()) terrainSettings.emplace(key, value);
#if TUMBLE_HAVE_TERRAIN
  if (TerrainScene::requested(terrainSettings)) {
    auto terrain = TerrainScene::create(terrainSettings);
    if (!terrain) return makeError(terrain.error());
    scene->m_terrain = std::move(terrain.value());
    scene->m_world->setHeightField(&scene->m_terrain->heightField());
  }
#else
  if (!terrainSettings.empty()) return makeError("terrain.*: this build has no terrain module");
#endif
  return scene;
}

Scene::~Scene() = default;

void Scene::registerStaticObjects() {
#if TUMBLE_HAVE_TERRAIN
  if (!m_terrain) return;
  m_world->forEachBody([&](physics::BodyId id, const physics::Body& b) {
    if (b.type != physics::BodyType::Static || b.shape.type == physics::ShapeType::Plane) return;
    Vec3 ext = Vec3::Constant(b.shape.boundingRadius());
    if (b.shape.type == physics::ShapeType::Box)
      ext = b.orientation.toRotationMatrix().cwiseAbs() * b.shape.halfExtents_m;
    // Objects off the map are simply not registered.
    (void)m_terrain->terrain().addStaticObject(id.index, terrain::Aabb{b.position_m - ext, b.position_m + ext});
  });
#endif
}

std::vector<std::string> Scene::subsystems() const {
  std::vector<std::string> names{"physics", "script"};
  if (m_terrain) names.push_back("terrain");
  names.insert(names.end(), m_extraSubsystems.begin(), m_extraSubsystems.end());
  return names;
}

void Scene::savePreviousState() {
  const auto& bodies = *m_world;
  std::size_t n = 0;
  bodies.forEachBody([&](physics::BodyId id, const physics::Body&) { n = std::max<std::size_t>(n, id.index + 1); });
  m_prevPosition.resize(n);
  m_prevOrientation.resize(n);
  bodies.forEachBody([&](physics::BodyId id, const physics::Body& b) {
    m_prevPosition[id.index] = b.position_m;
    m_prevOrientation[id.index] = b.orientation;
  });
}

std::shared_ptr<const render::ConvexMeshData> Scene::meshOf(
    const std::shared_ptr<const physics::ConvexHull>& hull) const {
  auto it = m_hullMeshes.find(hull.get());
  if (it != m_hullMeshes.end()) return it->second.mesh;
  auto mesh = std::make_shared<render::ConvexMeshData>();
  mesh->id = m_hullMeshes.size() + 1;
  for (const Vec3& v : hull->vertices_m) mesh->vertices.push_back(v.cast<float>());
  for (const auto& t : hull->triangles) mesh->indices.insert(mesh->indices.end(), t.begin(), t.end());
  m_hullMeshes.emplace(hull.get(), HullMesh{hull, mesh});
  return mesh;
}

void Scene::snapshot(render::FrameSnapshot& out, double alpha) const {
  out.shapes.clear();
#if TUMBLE_HAVE_TERRAIN
  out.terrain = m_terrain ? &m_terrain->surface() : nullptr;
#endif
  // One draw shape per simple shape; compounds give one per child.
  auto emit = [&](const physics::Shape& shape, render::DrawShape s) {
    switch (shape.type) {
      case physics::ShapeType::Box:
        s.kind = render::ShapeKind::Box;
        s.halfExtents = shape.halfExtents_m.cast<float>();
        break;
      case physics::ShapeType::Sphere:
        s.kind = render::ShapeKind::Sphere;
        s.radius_m = float(shape.radius_m);
        break;
      case physics::ShapeType::Capsule:
        s.kind = render::ShapeKind::Capsule;
        s.radius_m = float(shape.radius_m);
        s.halfHeight_m = float(shape.halfHeight_m);
        break;
      case physics::ShapeType::Hull:
        s.kind = render::ShapeKind::ConvexMesh;
        s.convexMesh = meshOf(shape.hull);
        break;
      case physics::ShapeType::Plane: s.kind = render::ShapeKind::Plane; break;
      case physics::ShapeType::Compound: return;  // children are emitted instead
    }
    out.shapes.push_back(std::move(s));
  };
  m_world->forEachBody([&](physics::BodyId id, const physics::Body& b) {
    render::DrawShape s;
    Vec3 p = b.position_m;
    Quat q = b.orientation;
    if (id.index < m_prevPosition.size() && b.type != physics::BodyType::Static) {
      p = m_prevPosition[id.index] + Real(alpha) * (b.position_m - m_prevPosition[id.index]);
      q = m_prevOrientation[id.index].slerp(Real(alpha), b.orientation);
    }
    s.position = p.cast<float>();
    s.orientation = q.cast<float>();
    s.color = m_host->colorOf(id);
    s.sleeping = !b.awake;
    if (b.shape.type != physics::ShapeType::Compound) return emit(b.shape, s);
    for (const physics::CompoundChild& c : b.shape.compound->children) {
      render::DrawShape part = s;
      part.position = (p + q * c.position_m).cast<float>();
      part.orientation = (q * c.orientation).cast<float>();
      emit(c.shape, part);
    }
  });
}

}  // namespace tumble::app
