#include "app/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <set>
#include <sstream>

#include "app/paths.h"
#include "app/physics_settings.h"
#include "app/scene_models.h"
#include "core/log.h"
#include "physics/deformable.h"
#include "particles/particle_system.h"
#include "physics/joints/joint_system.h"
#include "script/mod_bindings.h"
#include "physics/compound_shape.h"
#include "physics/convex_hull.h"
#include "physics/mesh_shape.h"
#include "script/mods.h"
#include "vehicle/vehicle_system.h"
#if TUMBLE_HAVE_TERRAIN
#include "app/terrain_scene.h"
#include "terrain/height_map.h"
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

Result<std::unique_ptr<Scene>> Scene::create(const SceneOptions& options) { return build(options, false); }

Result<script::ParamDecls> Scene::declaredParams(const SceneOptions& options) {
  SceneOptions bare = options;
  bare.sets.clear();  // the declaration, not a run: no --set, no terrain
  auto scene = build(bare, true);
  if (!scene) return makeError(scene.error());
  return (*scene)->host().declaredParams();
}

Result<Scene::Summary> Scene::summarize(const SceneOptions& options) {
  SceneOptions bare = options;
  bare.sets.clear();
  auto scene = build(bare, true);
  if (!scene) return makeError(scene.error());
  return Summary{(*scene)->host().title(), (*scene)->host().declaredParams()};
}

Result<std::unique_ptr<Scene>> Scene::build(const SceneOptions& options, bool scriptOnly) {
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
  if (options.threads > 0) ws.threads = options.threads;
  script::ScenarioOptions so;
  so.seed = options.seed;
  so.limits = options.limits;
  so.saveDir = options.saveDir;
  so.freezeSimulation = options.freezePhysics;
  so.scriptsDir = scriptsDir();
  so.mods = registry.mods();  // emitters may come from other mods ("base:dust")
  if (options.tuneOverrides) so.tuneOverridesFile = script::tuneOverridesPath(mod->name);
  if (!options.tuneOverridesFile.empty()) so.tuneOverridesFile = options.tuneOverridesFile;
  std::map<std::string, std::string> terrainSettings = options.terrainDefaults;
  std::optional<physics::JointSolverKind> forcedJointSolver;
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
      forcedJointSolver = kind;
    } else if (key.rfind("physics.", 0) == 0) {
      if (auto st = applyPhysicsSetting(ws, key, value); !st) return makeError(st.error());
    } else {
      so.params[key] = value;
    }
  }
  scene->m_world = std::make_unique<physics::World>(ws);
  scene->m_input = options.bindings ? std::make_unique<input::InputSystem>(*options.bindings)
                                    : loadInput(registry, *mod);
  if (forcedJointSolver) scene->m_jointSolver = *forcedJointSolver;
  // Models: "MOD:path" references and collision boxes from model bounds.
  for (const script::ModInfo& m : registry.mods()) so.modDirs[m.name] = m.dir;
  scene->m_models = std::make_unique<ModelCache>();
  auto host = script::ScenarioHost::load(*mod, ref->second, *scene, so);
  if (!host) return makeError(host.error());
  scene->m_host = std::move(host.value());
  if (scriptOnly) return scene;
  // A scenario that declares its parameters takes no other plain --set.
  if (const script::ParamDecls& decls = scene->m_host->declaredParams())
    for (const auto& [key, value] : so.params)
      if (Status st = script::checkParamValue(*decls, options.scenarioRef, key, value); !st) return makeError(st.error());
  // The scenario's joint_solver field, unless the command line chose.
  if (!forcedJointSolver && scene->m_host->jointSolverRequest())
    scene->setJointSolver(*scene->m_host->jointSolverRequest());
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
      if (end == it->second.c_str() || *end != '\0' || !std::isfinite(size) || size != std::floor(size) ||
          size < 2 || size > terrain::kMaxHeightMapSide)
        return makeError("terrain.size=" + it->second + ": expected a whole number of samples per side, 2 to " +
                         std::to_string(terrain::kMaxHeightMapSide));
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

physics::JointSystem& Scene::joints() {
  if (!m_joints) {
    // Velocity-only projection when joints or jointed bodies are new (see
    // JointSettings::postStabilize): moving positions would push bodies
    // lying on the ground into it.
    physics::JointSettings js;
    js.projectPositions = false;
    js.solver = m_jointSolver;
    m_joints = std::make_unique<physics::JointSystem>(*m_world, js);
  }
  return *m_joints;
}

void Scene::warnOnceOfCostCaps() {
  if (!m_warnedPairCap && m_world->contactPairsSkippedLastStep() > 0) {
    m_warnedPairCap = true;
    log::warn(name() + ": " + std::to_string(m_world->contactPairsSkippedLastStep()) +
              " overlapping body pairs were not collided in one step: more than " +
              std::to_string(m_world->settings().maxContactPairsPerBody) +
              " pairs per body, which only bodies created inside each other reach; those pairs pass through "
              "each other until the heap spreads (report: error.contact_pairs_skipped)");
  }
  if (!m_warnedJointCap && m_joints && m_joints->stepsOverCostCap() > 0) {
    m_warnedJointCap = true;
    char work[64];
    std::snprintf(work, sizeof work, "%.3g", m_joints->overCostCapWorkPerRow());
    log::warn(name() + ": the lagrange joint solver would need " + work +
              " multiply-adds per row to factorize the joints' matrix, over its cost cap of " +
              std::to_string(int(m_joints->settings().lagrangeMaxFactorWorkPerRow)) +
              " (a body carrying many joints, or a lattice of joint loops), so the impulse solver solves "
              "the joints until they change (report: counts.joint_steps_over_cost_cap)");
  }
}

void Scene::setJointSolver(physics::JointSolverKind kind) {
  m_jointSolver = kind;
  if (m_joints) m_joints->setSolver(kind);
}

double Scene::jointErrorMax_m() const { return m_joints ? m_joints->maxAnchorError_m() : 0.0; }

vehicle::VehicleSystem& Scene::vehicles() {
  if (!m_vehicles) m_vehicles = std::make_unique<vehicle::VehicleSystem>(*m_world);
  return *m_vehicles;
}

particles::ParticleSystem& Scene::particles() {
  if (!m_particles) {
    m_particles = std::make_unique<particles::ParticleSystem>(m_options.seed);
    m_particles->setGravity(m_world->settings().gravity_mps2.cast<float>());
  }
  return *m_particles;
}

audio::AudioSystem& Scene::audio() {
  if (!m_audio) {
    auto made = audio::AudioSystem::create(m_options.audioOutput);
    if (!made) {
      static bool said = false;  // once per process, not at every restart
      if (!said) log::info("audio: " + made.error() + "; playing silently");
      said = true;
      made = audio::AudioSystem::create(audio::AudioOutput::Silent);
    }
    m_audio = std::move(made.value());
    m_audio->setVolumes(m_options.volumes);
  }
  return *m_audio;
}

physics::DeformableSystem& Scene::deformables() {
  if (!m_deformables) m_deformables = std::make_unique<physics::DeformableSystem>();
  return *m_deformables;
}

Result<script::ModelBox> Scene::modelBounds(const std::string& file) { return m_models->bounds(file); }

Result<script::ModelTriangles> Scene::modelTriangles(const std::string& file) { return m_models->triangles(file); }

Result<physics::Shape> Scene::modelMeshShape(const std::string& file, const Vec3& scale) {
  return m_models->meshShape(file, scale);
}

void Scene::start() {
  m_host->start();
  registerStaticObjects();
}

void Scene::finish(double time_s, long long step) { m_host->finish(time_s, step); }

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
  if (m_particles) names.push_back("particles");  // created by the first particles.spawn
  if (m_vehicles) names.push_back("vehicle");
  if (m_models && m_models->size() > 0) names.push_back("models");
  if (m_deformables) names.push_back("deformables");
  if (m_joints) names.push_back("joints");
  if (m_audio && m_audio->output() != audio::AudioOutput::Silent) names.push_back("audio");  // a device or offline render
  names.insert(names.end(), m_extraSubsystems.begin(), m_extraSubsystems.end());
  return names;
}

}  // namespace tumble::app
