#include "app/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <set>
#include <sstream>

#include "app/paths.h"
#include "app/scene_models.h"
#include "core/log.h"
#include "physics/deformable.h"
#include "physics/joints/joint_system.h"
#include "script/mod_bindings.h"
#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/mesh_shape.h"
#include "script/mods.h"
#include "vehicle/vehicle_system.h"
#if TUMBLE_HAVE_TERRAIN
#include "app/terrain_scene.h"
#include "script/terrain_build.h"
#endif

namespace tumble::app {

const std::vector<std::string>& rigidBodyIntegrators() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& info : physics::bodyIntegrators()) n.emplace_back(info.name);
    return n;
  }();
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
                     "physics.solver_tolerance, physics.gravity, physics.joint_solver)");
  }
  return Ok{};
}

// Bindings of base and of the scenario's mod with everything it depends on,
// in load order. Problems are reported and the valid rest is used: a typo in
// one binding must not stop the game.
script::ModBindings readBindings(const script::ModRegistry& registry, const script::ModInfo& mod) {
  std::set<std::string> wanted{"base", mod.name};
  for (bool grew = true; grew;) {
    grew = false;
    for (const script::ModInfo& m : registry.mods()) {
      if (!wanted.count(m.name)) continue;
      for (const script::ModDependency& d : m.depends)
        if (registry.find(d.name) && wanted.insert(d.name).second) grew = true;
    }
  }
  std::vector<script::ModInfo> mods;
  for (const script::ModInfo& m : registry.mods())
    if (wanted.count(m.name)) mods.push_back(m);
  return script::loadBindings(mods);
}

std::unique_ptr<input::InputSystem> loadInput(const script::ModRegistry& registry, const script::ModInfo& mod) {
  script::ModBindings bindings = readBindings(registry, mod);
  for (const script::ModProblem& p : bindings.problems) log::warn("bindings: " + p.text());
  return std::make_unique<input::InputSystem>(std::move(bindings.set));
}

}  // namespace

Result<std::unique_ptr<Scene>> Scene::create(const SceneOptions& options) {
  auto ref = script::parseScenarioRef(options.scenarioRef);
  if (!ref) return makeError(ref.error());
  if (!(options.dt_s > 0 && options.dt_s <= 1)) return makeError("--dt must be a time step in (0, 1] seconds");
  // --integrator wins over the scenario's integrator = "..." field.
  std::optional<physics::BodyIntegrator> forcedIntegrator;
  if (!options.integrator.empty()) {
    auto m = physics::parseBodyIntegrator(options.integrator);
    if (!m) return makeError("--integrator: " + m.error());
    forcedIntegrator = *m;
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
  so.mods = registry.mods();  // emitters may come from other mods ("base:dust")
  if (options.tuneOverrides) so.tuneOverridesFile = script::tuneOverridesPath(mod->name);
  std::map<std::string, std::string> terrainSettings = options.terrainDefaults;
  for (const auto& [key, value] : options.sets) {
    if (key.rfind("terrain.", 0) == 0) {
      terrainSettings[key] = value;
    } else if (key.rfind("tune.", 0) == 0) {
      // tune.NAME, or tune.MOD.NAME for this mod (other mods' are not running).
      std::string name = key.substr(5);
      if (name.rfind(mod->name + ".", 0) == 0) name = name.substr(mod->name.size() + 1);
      if (name.empty()) return makeError("--set " + key + ": expected tune.NAME=VALUE or tune.MOD.NAME=VALUE");
      so.tuneSets[name] = value;
    } else if (key == "physics.joint_solver") {
      physics::JointSolverKind kind;
      if (!physics::parseJointSolver(value, &kind))
        return makeError("--set " + key + "=" + value + ": expected lagrange or impulse");
      so.jointSolver = value;
    } else if (key.rfind("physics.", 0) == 0) {
      if (auto st = applyPhysicsSetting(ws, key, value); !st) return makeError(st.error());
    } else {
      so.params[key] = value;
    }
  }
  scene->m_world = std::make_unique<physics::World>(ws);
  scene->m_input = loadInput(registry, *mod);
  so.input = scene->m_input.get();
  // Models: "MOD:path" references and collision boxes from model bounds.
  for (const script::ModInfo& m : registry.mods()) so.modDirs[m.name] = m.dir;
  scene->m_models = std::make_unique<ModelCache>();
  so.modelBounds = [models = scene->m_models.get()](const std::string& file) { return models->bounds(file); };
  so.modelTriangles = [models = scene->m_models.get()](const std::string& file) { return models->triangles(file); };
  so.modelMeshShape = [models = scene->m_models.get()](const std::string& file, const Vec3& scale) {
    return models->meshShape(file, scale);
  };
  auto host = script::ScenarioHost::load(*mod, ref->second, *scene->m_world, so);
  if (!host) return makeError(host.error());
  scene->m_host = std::move(host.value());
  physics::BodyIntegrator integrator = physics::BodyIntegrator::SymplecticEuler;
  if (forcedIntegrator) {
    integrator = *forcedIntegrator;
  } else if (!scene->m_host->integratorRequest().empty()) {
    auto m = physics::parseBodyIntegrator(scene->m_host->integratorRequest());
    if (!m) return makeError(scene->m_host->scenarioFile() + ": field 'integrator': " + m.error());
    integrator = *m;
  }
  scene->m_world->settings().integrator = integrator;
  // The scenario's own terrain = {...} comes first; --set terrain.* overrides.
  for (const auto& [key, value] : scene->m_host->terrainRequest()) terrainSettings.emplace(key, value);
#if TUMBLE_HAVE_TERRAIN
  // terrain.build(map) in the scenario makes the height map in Lua, unless
  // the command line asks for another one (--set terrain.heightmap or
  // terrain.generate: a player can play any scenario on any map).
  std::optional<terrain::HeightMap> built;
  const bool commandLineMap = std::any_of(options.sets.begin(), options.sets.end(), [](const auto& kv) {
    return kv.first == "terrain.heightmap" || kv.first == "terrain.generate";
  });
  if (scene->m_host->hasTerrainBuild() && !commandLineMap) {
    double size = 1025;
    if (auto it = terrainSettings.find("terrain.size"); it != terrainSettings.end()) {
      char* end = nullptr;
      size = std::strtod(it->second.c_str(), &end);
      if (end == it->second.c_str() || *end != '\0' || size != std::floor(size))
        return makeError("terrain.size=" + it->second + ": expected a whole number of samples per side");
    }
    auto map = script::buildScenarioTerrain(*scene->m_host, int(size), int(size));
    if (!map) return makeError(map.error());
    built = std::move(map.value());
  }
  terrainSettings.erase("terrain.build");
  if (built || TerrainScene::requested(terrainSettings)) {
    auto terrain = TerrainScene::create(terrainSettings, built ? &*built : nullptr);
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

Status Scene::reloadBindings() {
  script::ModRegistry registry = script::ModRegistry::discover(modSearchDirs(m_options.modDirs));
  const script::ModInfo* mod = registry.find(m_modName);
  if (!mod) return makeError("bindings: mod \"" + m_modName + "\" is no longer found");
  script::ModBindings bindings = readBindings(registry, *mod);
  if (!bindings.problems.empty()) {
    std::string text;
    for (const script::ModProblem& p : bindings.problems) {
      if (!text.empty()) text += '\n';
      text += p.text();
    }
    return makeError(text + "\n(the previous bindings stay)");
  }
  m_input->redefine(std::move(bindings.set));
  return Ok{};
}

void Scene::stepDeformables(Real dt_s) {
  physics::DeformableSystem* d = m_host->deformablesIfAny();
  if (!d) return;
  physics::DeformableEnvironment env;
  env.gravity_mps2 = m_world->settings().gravity_mps2;
  env.world = m_world.get();
  env.heightField = m_world->heightField();
  d->step(dt_s, env);
}

void Scene::registerStaticObjects() {
#if TUMBLE_HAVE_TERRAIN
  if (!m_terrain) return;
  m_world->forEachBody([&](physics::BodyId id, const physics::Body& b) {
    if (b.type != physics::BodyType::Static || b.shape.type == physics::ShapeType::Plane) return;
    if (b.shape.type == physics::ShapeType::Mesh) {  // a static model: its tree's covering box, placed
      Vec3 lo, hi;
      b.shape.bounds(b.position_m, b.orientation, &lo, &hi);
      (void)m_terrain->terrain().addStaticObject(id.index, terrain::Aabb{lo, hi});
      return;
    }
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
  if (m_host->particlesIfAny()) names.push_back("particles");  // created by the first particles.spawn
  if (m_host && m_host->vehiclesIfAny()) names.push_back("vehicle");
  if (m_models && m_models->size() > 0) names.push_back("models");
  if (m_host && m_host->deformablesIfAny()) names.push_back("deformables");
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

std::optional<render::BodyPose> Scene::bodyPose(physics::BodyId id, double alpha) const {
  if (!m_world->isValid(id)) return std::nullopt;
  const physics::Body& b = m_world->body(id);
  Vec3 p = b.position_m;
  Quat q = b.orientation;
  if (id.index < m_prevPosition.size() && b.type != physics::BodyType::Static) {
    p = m_prevPosition[id.index] + Real(alpha) * (b.position_m - m_prevPosition[id.index]);
    q = m_prevOrientation[id.index].slerp(Real(alpha), b.orientation);
  }
  return render::BodyPose{p.cast<float>(), q.cast<float>()};
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

const std::vector<Scene::WireEdge>& Scene::wireOf(const std::shared_ptr<const physics::MeshShape>& mesh) const {
  auto it = m_meshWires.find(mesh.get());
  if (it != m_meshWires.end()) return it->second.edges;
  // Each edge once: neighbours share an edge's two end points (the mesh
  // shape matched them bit for bit when it set the flags).
  std::map<std::array<float, 6>, bool> unique;
  for (const physics::MeshTriangle& t : mesh->triangles)
    for (int e = 0; e < 3; ++e) {
      Eigen::Vector3f a = t.v[e].cast<float>(), b = t.v[(e + 1) % 3].cast<float>();
      if (std::lexicographical_compare(b.data(), b.data() + 3, a.data(), a.data() + 3)) std::swap(a, b);
      const bool crease = (t.activeEdges >> e) & 1u;
      auto [slot, added] = unique.emplace(std::array<float, 6>{a.x(), a.y(), a.z(), b.x(), b.y(), b.z()}, crease);
      if (!added) slot->second = slot->second || crease;
    }
  MeshWire wire{mesh, {}};
  wire.edges.reserve(unique.size());
  for (const auto& [k, crease] : unique)
    wire.edges.push_back({Eigen::Vector3f(k[0], k[1], k[2]), Eigen::Vector3f(k[3], k[4], k[5]), crease});
  return m_meshWires.emplace(mesh.get(), std::move(wire)).first->second.edges;
}

void Scene::snapshot(render::FrameSnapshot& out, double alpha) const {
  out.shapes.clear();
  out.models.clear();
  out.lines.clear();  // ropes, cloth and script lines follow in snapshotVehiclesAndLines
  // Bodies drawn with a model (body:set_model, static models' collision
  // boxes) are not also drawn as their plain shape; in the collision view
  // the shapes are drawn and the models are not.
  std::vector<bool> hasModel;
  const script::Presentation& presentation = m_host->presentation();
  auto mark = [&](physics::BodyId id) {
    if (id.isNull() || !m_world->isValid(id)) return;
    if (hasModel.size() <= id.index) hasModel.resize(id.index + 1, false);
    hasModel[id.index] = true;
  };
  if (!m_collisionView) {
    for (const auto& a : presentation.attachments) mark(a.body);
    for (const auto& s : presentation.statics) mark(s.body);
    appendModelInstances(*this, alpha, out.models);
  }
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
      case physics::ShapeType::Mesh: {  // wireframe: creases and borders bright, flat seams dim
        static const Eigen::Vector3f kCrease(1.0f, 0.55f, 0.05f), kSeam(0.45f, 0.3f, 0.12f);
        for (const WireEdge& e : wireOf(shape.mesh))
          out.lines.push_back(render::DebugLine{s.position + s.orientation * e.a_m,
                                                s.position + s.orientation * e.b_m, e.crease ? kCrease : kSeam});
        return;
      }
    }
    out.shapes.push_back(std::move(s));
  };
  m_world->forEachBody([&](physics::BodyId id, const physics::Body& b) {
    if (id.index < hasModel.size() && hasModel[id.index]) return;
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
  snapshotParticles(out, alpha);
  snapshotVehiclesAndLines(out, alpha);
}

void Scene::snapshotParticles(render::FrameSnapshot& out, double alpha) const {
  out.particles.clear();
  out.additiveParticles.clear();
  const particles::ParticleSystem* ps = m_host->particlesIfAny();
  if (!ps) return;
  // Positions are the step's end; back them up along the velocity to the
  // interpolated time (alpha = 1: the step's end).
  const float back_s = float((1.0 - alpha) * m_options.dt_s);
  ps->forEach([&](particles::EmitterId, const particles::Emitter& e) {
    const particles::ParticlePool& p = e.pool;
    const particles::EmitterDef& d = e.def;
    std::vector<render::DrawParticle>& dst =
        d.blend == particles::BlendMode::Additive ? out.additiveParticles : out.particles;
    const bool local = d.space == particles::SimSpace::Local;
    const Eigen::Matrix3f rot = e.rotation.toRotationMatrix();
    for (std::uint32_t i = 0; i < p.count; ++i) {
      const float life = std::min(1.0f, p.age_s[i] * p.invLifetime[i]);
      render::DrawParticle q;
      q.size_m = d.size_m.eval(life);
      const float a = d.alpha.eval(life);
      if (q.size_m <= 0 || a <= 0) continue;
      Eigen::Vector3f pos(p.px[i] - p.vx[i] * back_s, p.py[i] - p.vy[i] * back_s, p.pz[i] - p.vz[i] * back_s);
      q.position = local ? Eigen::Vector3f(rot * pos + e.position_m) : pos;
      const Eigen::Vector3f rgb = d.color.eval(life);
      q.color = Eigen::Vector4f(rgb.x(), rgb.y(), rgb.z(), a);
      q.angle_rad = p.angle_rad[i] - p.spin_radps[i] * back_s;
      if (d.stretch_s > 0) {
        const Eigen::Vector3f v(p.vx[i], p.vy[i], p.vz[i]);
        q.stretch_m = (local ? Eigen::Vector3f(rot * v) : v) * d.stretch_s;
      }
      dst.push_back(q);
    }
  });
}

void Scene::snapshotVehiclesAndLines(render::FrameSnapshot& out, double alpha) const {
  // Vehicle wheels are ray casts, not bodies: drawn with the runtime's wheel
  // model (assets/models; axle along X, radius 0.35 m, width 0.25 m) at each
  // hub, steered and turned by its accumulated spin; as spheres if the model
  // is missing.
  std::shared_ptr<const render::Model> wheelModel;
  if (const vehicle::VehicleSystem* vehicles = m_host->vehiclesIfAny(); vehicles && vehicles->count() > 0) {
    auto loaded = m_models->get(assetPath("models/wheel.obj"));
    if (loaded) wheelModel = loaded.value();
  }
  constexpr float kWheelModelRadius_m = 0.35f, kWheelModelWidth_m = 0.25f;
  if (const vehicle::VehicleSystem* vehicles = m_host->vehiclesIfAny())
    vehicles->forEach([&](vehicle::VehicleId id) {
      // Hubs ride with the chassis' interpolated pose, so they do not lag it.
      const physics::BodyId c = vehicles->chassis(id);
      const physics::Body& b = m_world->body(c);
      Vec3 p = b.position_m;
      Quat q = b.orientation;
      if (c.index < m_prevPosition.size()) {
        p = m_prevPosition[c.index] + Real(alpha) * (b.position_m - m_prevPosition[c.index]);
        q = m_prevOrientation[c.index].slerp(Real(alpha), b.orientation);
      }
      for (int i = 0; i < vehicles->wheelCount(id); ++i) {
        const vehicle::WheelTelemetry& w = vehicles->wheel(id, i);
        const Vec3 hub = p + q * (b.orientation.conjugate() * (w.hub_m - b.position_m));
        if (wheelModel) {
          render::ModelInstance m;
          m.model = wheelModel;
          m.position = hub.cast<float>();
          const Quat turn = q * Quat(Eigen::AngleAxis<Real>(w.steer_rad, Vec3::UnitY())) *
                            Quat(Eigen::AngleAxis<Real>(w.rotation_rad, Vec3::UnitX()));
          m.orientation = turn.cast<float>();
          const float r = float(w.radius_m) / kWheelModelRadius_m;
          m.scale = Eigen::Vector3f(float(w.width_m) / kWheelModelWidth_m, r, r);
          out.models.push_back(std::move(m));
          continue;
        }
        render::DrawShape s;
        s.kind = render::ShapeKind::Sphere;
        s.position = hub.cast<float>();
        s.radius_m = float(w.radius_m);
        s.color = Eigen::Vector3f(0.12f, 0.12f, 0.13f);
        out.shapes.push_back(s);
      }
    });
  // Ropes, cloth and the lines scripts drew (no interpolation: lines),
  // after the collision view's mesh wireframes (snapshot cleared the list).
  if (const physics::DeformableSystem* d = m_host->deformablesIfAny()) {
    d->forEach([&](int id, const physics::Deformable& def) {
      const Eigen::Vector3f color = m_host->deformableColor(id);
      def.forEachStructuralSegment([&](const Vec3& a, const Vec3& b) {
        out.lines.push_back(render::DebugLine{a.cast<float>(), b.cast<float>(), color});
      });
    });
  }
  for (const auto& l : m_host->scriptLines())
    out.lines.push_back(render::DebugLine{l.a_m.cast<float>(), l.b_m.cast<float>(), l.color});
}

}  // namespace tumble::app
