#include "app/run_report.h"

#include <algorithm>
#include <cstdlib>

#include "app/scene.h"
#include "app/scene_models.h"
#include "core/file_util.h"
#include "core/hash.h"
#include "core/process_stats.h"
#include "particles/particle_system.h"
#include "physics/deformable.h"
#include "physics/joints/joint_system.h"

namespace tumble::app {
namespace {

/// The bodies' hash, extended with every other simulated state a scene
/// may have: rope and cloth particles, and live effect particles (positions,
/// velocities, ages), each in creation order. Exact bits, as World::stateHash.
std::uint64_t sceneStateHash(Scene& scene) {
  Hasher h;
  h.value(scene.world().stateHash());
  if (const physics::DeformableSystem* ds = scene.deformablesIfAny()) {
    ds->forEach([&](int id, const physics::Deformable& d) {
      h.value(id);
      for (int i = 0; i < d.particleCount(); ++i) {
        const Vec3 x = d.position(i), v = d.velocity(i);
        h.bytes(x.data(), sizeof(Real) * 3);
        h.bytes(v.data(), sizeof(Real) * 3);
      }
    });
  }
  if (const particles::ParticleSystem* ps = scene.particlesIfAny()) {
    ps->forEach([&](particles::EmitterId id, const particles::Emitter& e) {
      h.value(id.index);
      const particles::ParticlePool& p = e.pool;
      h.value(p.count);
      for (const std::vector<float>* a : {&p.px, &p.py, &p.pz, &p.vx, &p.vy, &p.vz, &p.age_s})
        h.bytes(a->data(), sizeof(float) * p.count);
    });
  }
  return h.digest();
}

}  // namespace

std::string stateHashText(Scene& scene) {
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(sceneStateHash(scene)));
  return hash;
}

long nonFiniteEvents(Scene& scene) {
  long n = scene.world().errorStats().nanEvents;
  if (const physics::DeformableSystem* ds = scene.deformablesIfAny())
    ds->forEach([&](int, const physics::Deformable& d) { n += d.stats().nanEvents; });
  return n;
}

StepMsSummary summarizeSteps(std::vector<double> ms) {
  StepMsSummary s;
  if (ms.empty()) return s;
  std::sort(ms.begin(), ms.end());
  s.median = ms[ms.size() / 2];
  s.p99 = ms[std::min(ms.size() - 1, std::size_t(double(ms.size()) * 0.99))];
  s.max = ms.back();
  return s;
}

nlohmann::json buildReport(Scene& scene, long long steps, double simulatedSeconds, const RunTimings& t,
                           const RunCounts& counts) {
  using nlohmann::json;
  const physics::World& world = scene.world();
  const physics::ErrorStats& err = world.errorStats();
  StepMsSummary sm = summarizeSteps(t.stepMs);
  json expectations = json::array();
  for (const auto& e : scene.host().expectations()) {
    json limit = nullptr;
    if (e.min || e.max) {
      limit = json::object();
      limit["min"] = e.min ? json(*e.min) : json(nullptr);
      limit["max"] = e.max ? json(*e.max) : json(nullptr);
    }
    json value = e.isBool ? json(e.value == 1) : (std::isfinite(e.value) ? json(e.value) : json(nullptr));
    expectations.push_back({{"name", e.name}, {"ok", e.ok}, {"value", value}, {"limit", limit}});
  }
  json errors = json::array();
  for (const auto& e : scene.host().errors())
    errors.push_back({{"mod", e.mod}, {"file", e.file}, {"line", e.line}, {"message", e.message},
                      {"traceback", e.traceback}});
  // Game state scripts set (game.score, game.win/lose, game.message).
  const auto& host = scene.host();
  json game = {{"score", host.hasScore() ? json(host.score()) : json(nullptr)},
               {"outcome", host.outcome() == script::Outcome::Won    ? json("won")
                           : host.outcome() == script::Outcome::Lost ? json("lost")
                                                                     : json(nullptr)},
               {"reason", host.outcomeReason()},
               {"at_s", host.outcome() != script::Outcome::None ? json(host.outcomeTime_s()) : json(nullptr)},
               {"messages", json::array()}};
  for (const auto& m : host.messages()) game["messages"].push_back({{"text", m.text}, {"time_s", m.time_s}});
  // Tunables and the values this run used (defaults or --set tune.*).
  json tunables = json::object();
  for (const auto& tn : host.tunables().items()) {
    if (tn.kind == script::Tunable::Kind::Number) tunables[tn.name] = tn.value();
    else if (tn.kind == script::Tunable::Kind::Bool) tunables[tn.name] = tn.value() != 0;
    else tunables[tn.name] = tn.valueText();
  }
  // Scenario parameters: each declared one with the value this run used
  // (--set or its default), typed as declared; a scenario that declares none
  // lists the --set values it was given, as text.
  json params = json::object();
  if (const script::ParamDecls& decls = host.declaredParams()) {
    for (const script::ParamDecl& d : *decls) {
      auto given = host.options().params.find(d.name);
      const std::string& text = given != host.options().params.end() ? given->second : d.defaultText;
      if (d.type == script::ParamDecl::Type::Number) params[d.name] = std::strtod(text.c_str(), nullptr);
      else if (d.type == script::ParamDecl::Type::Boolean) params[d.name] = text == "true";
      else params[d.name] = text;
    }
  } else {
    for (const auto& [name, text] : host.options().params) params[name] = text;
  }
  // What the static meshes' object trees saved (all zero without meshes).
  const physics::MeshStats& mesh = world.meshStats();
  const json meshCollision = {{"pairs", mesh.pairs},
                              {"nodes_visited", mesh.nodesVisited},
                              {"subtrees_skipped", mesh.subtreesSkipped},
                              {"nodes_skipped_tight", mesh.nodesSkippedTight},
                              {"triangles_tested", mesh.trianglesTested},
                              {"exact_tests", mesh.exactTests},
                              {"rays", mesh.rays},
                              // Static models' mesh shapes: placements given
                              // one, shapes built (one per file and scale).
                              {"shapes_placed", scene.models().meshShapesPlaced()},
                              {"shapes_built", scene.models().meshShapesBuilt()}};
  const std::string hash = stateHashText(scene);
  return json{
      {"scenario", scene.name()},
      {"seed", scene.options().seed},
      {"dt", scene.options().dt_s},
      {"substeps", world.settings().substeps},
      {"threads", world.settings().threads},
      {"steps_on_threads", world.stepsOnThreads()},
      {"integrator", scene.integratorName()},
      {"joint_solver", physics::jointSolverName(scene.jointSolver())},
      {"steps", steps},
      {"simulated_seconds", simulatedSeconds},
      {"wall_seconds",
       {{"total", t.total_s},
        {"startup", t.startup_s},
        {"physics", t.physics_s},
        {"script", t.script_s},
        {"particles", t.particles_s},
        {"render", t.render_s}}},
      {"step_ms", {{"median", sm.median}, {"p99", sm.p99}, {"max", sm.max}}},
      {"subsystems", scene.subsystems()},
      {"peak_rss_mb", peakRssMb()},
      {"counts",
       {{"bodies", counts.bodiesMax},
        {"joints", counts.jointsMax},
        {"contacts_max", err.contactsMax},
        {"joint_steps_over_cost_cap", scene.jointsIfAny() ? scene.jointsIfAny()->stepsOverCostCap() : 0L},
        {"particles_max", counts.particlesMax}}},
      {"error",
       {{"energy_rel_drift_max", scene.errorAudit().energyRelDriftMax()},
        {"energy_gain_max_J", scene.errorAudit().energyGainMax_J()},
        {"energy_scale_J", scene.errorAudit().energyScale_J()},
        {"penetration_max_m", err.penetrationMax_m},
        {"joint_error_max_m", scene.jointErrorMax_m()},
        {"momentum_rel_drift_max", scene.errorAudit().momentumRelDriftMax()},
        {"momentum_residual_max_Ns", scene.errorAudit().momentumResidualMax_Ns()},
        {"momentum_scale_Ns", scene.errorAudit().momentumScale_Ns()},
        {"nan_events", nonFiniteEvents(scene)},
        {"contact_pairs_skipped", err.contactPairsSkipped}}},
      {"expectations", expectations},
      {"script_errors", errors},
      {"game", game},
      {"params", params},
      {"tunables", tunables},
      {"mesh_collision", meshCollision},
      {"state_hash", hash},
  };
}

int exitStatusFor(const Scene& scene) {
  const auto& host = scene.host();
  if (!host.errors().empty()) return 3;
  for (const auto& e : host.expectations())
    if (!e.ok) return 2;
  return 0;
}

Status writeReport(const std::string& path, const nlohmann::json& report) {
  return writeFileAtomic(path, report.dump(2) + "\n");
}

}  // namespace tumble::app
