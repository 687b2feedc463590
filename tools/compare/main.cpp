// tumble_compare: one scene, built from the same data in Tumble and in
// Bullet 3, stepped single-threaded in the same process one after the other,
// with the same time step, gravity, sizes, masses and pair materials.
//
//   tumble_compare list
//   tumble_compare SCENE [--steps N] [--dt H] [--report FILE] [--quick]
//                        [--bullet-iterations N] [--no-bullet-default] [--sleep]
//   tumble_compare SCENE --sweep [--out DIR] [--steps N] [--quick]   (sweep.cpp)
//   tumble_compare terrain_rays [--rays N] [--terrain-size N] [--report FILE] [--quick]
//
// Solver budget. Tumble's default step is 8 substeps x (4 solve + 2 relax)
// sweeps = 48 sweeps over every contact and joint per 1/60 s step (at most:
// the solve sweeps of a substep stop once converged, see
// WorldSettings::solverTolerance; ragdolls_100 never gets there, all 48 run),
// with one collision pass. Bullet's equivalent is 1 step of 1/60 s
// with as many solver iterations (one collision pass, 48 sweeps): that is
// "bullet", the figure ratio_step_ms divides by. The count is read from
// WorldSettings, so it follows Tumble's defaults. (Until 2026-11-22 the peer
// got 40: the mapping was written for 4 + 1 and not updated when the relax
// sweeps became 2; `--bullet-iterations 40` reproduces it.) Bullet
// substepping (8 x 1/480 s with 6 iterations) was rejected as the peer: it
// would also run collision detection 8 times, which is not the same budget.
// Because nobody ships Bullet at 48 iterations, "bullet_default" also reports
// Bullet at its default 10 iterations (ratio_step_ms_default).
//
// Output: the JSON report on stdout and, with --report, written atomically.
// Exit status: 0 done, 1 bad arguments or the report could not be written.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "core/file_util.h"
#include "compare_report.h"
#include "physics/world.h"
#include "scenes.h"
#include "sweep.h"
#include "terrain_rays.h"

using nlohmann::json;
using namespace tumble::compare;

namespace {

constexpr int kQuickSteps = 20;
constexpr int kBulletDefaultIterations = 10;  // btContactSolverInfo's default

/// Prints the report on stdout and, when asked, writes it atomically; the
/// exit status: 0, or 1 when the file cannot be written.
int emitReport(const json& report, const std::string& path) {
  const std::string text = report.dump(2) + "\n";
  std::fputs(text.c_str(), stdout);
  if (!path.empty()) {
    if (auto s = tumble::writeFileAtomic(path, text); !s) {
      std::fprintf(stderr, "tumble_compare: %s\n", s.error().c_str());
      return 1;
    }
  }
  return 0;
}

double ratio(const json& a, const json& b, const char* field = "step_ms_median") {
  double den = b[field].get<double>();
  return den > 0 ? a[field].get<double>() / den : 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Tumble vs Bullet 3: the same scene stepped in both engines, single-threaded"};
  std::string sceneName;
  int steps = 0;
  double dt = 1.0 / 60.0;
  std::string reportPath;
  bool quick = false;
  const tumble::physics::WorldSettings defaults;
  // The peer does as many sweeps as Tumble's default step (see the top of this file).
  int bulletIterations = defaults.substeps * (defaults.velocityIterations + defaults.relaxIterations);
  bool noBulletDefault = false;
  bool sleep = false;
  std::string jointSolver = "impulse";
  app.add_option("scene", sceneName, "scene name, or 'list'")->required();
  app.add_option("--joint-solver", jointSolver, "Tumble's joint solver for scenes with joints: impulse or lagrange")
      ->check(CLI::IsMember({"impulse", "lagrange"}));
  app.add_option("--steps", steps, "steps to run (default: 300 for boxes_3000, 600 otherwise)")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--dt", dt, "time step in seconds (default 1/60)")
      ->check([](const std::string& text) -> std::string {
        const double v = std::strtod(text.c_str(), nullptr);  // CLI11's PositiveNumber lets NaN through
        return std::isfinite(v) && v > 0 ? std::string() : "expected a finite number > 0, got " + text;
      });
  app.add_option("--report", reportPath, "write the JSON report to this file (atomically)");
  app.add_flag("--quick", quick, "smoke test: " + std::to_string(kQuickSteps) + " steps");
  app.add_option("--bullet-iterations", bulletIterations,
                 "Bullet solver iterations of the main peer (default: Tumble's sweeps per step, " +
                     std::to_string(bulletIterations) + ")")
      ->check(CLI::Range(1, 10000));
  app.add_flag("--no-bullet-default", noBulletDefault, "skip the extra Bullet run at its default 10 iterations");
  app.add_flag("--sleep", sleep, "let both engines put resting bodies to sleep (off: time the solvers, not idle worlds)");
  int threads = 1;
  app.add_option("--threads", threads,
                 "threads of Tumble's step (WorldSettings::threads; the peers use one); step_cpu_ms then sums all "
                 "threads")
      ->check(CLI::Range(1, 64));
  bool sweep = false;
  std::string outDir = ".";
  app.add_flag("--sweep", sweep,
               "work-precision comparison: each engine over its accuracy settings, quality against CPU time per "
               "step with Pareto fronts (CSV, gnuplot PNG and JSON); with --quick a 2 x 2 grid of 20 steps");
  app.add_option("--out", outDir, "--sweep: folder for the CSV, data, gnuplot script and PNG (default: .)");
  TerrainRaysOptions rayOptions;
  app.add_option("--rays", rayOptions.rays, "terrain_rays: rays in the batch (default 100000)")
      ->check(CLI::Range(1, 100000000));
  app.add_option("--terrain-size", rayOptions.size, "terrain_rays: samples per side (default 1025)")
      ->check(CLI::Range(3, 4097));
  CLI11_PARSE(app, argc, argv);

  const std::vector<std::string> names = sceneNames();
  if (sceneName == "list") {
    for (const std::string& n : names) std::printf("%-20s %s\n", n.c_str(), sceneDescription(n).c_str());
    std::printf("%-20s %s\n", "terrain_rays", "a batch of ray casts against a 1025^2 height field");
    return 0;
  }
  if (sceneName == "terrain_rays") {
    if (quick) rayOptions.rays = std::min(rayOptions.rays, 3000), rayOptions.size = std::min(rayOptions.size, 257);
    const json report = runTerrainRays(rayOptions);
    if (report.contains("error")) {
      std::fprintf(stderr, "tumble_compare: terrain_rays: %s\n", report["error"].get<std::string>().c_str());
      return 1;
    }
    return emitReport(report, reportPath);
  }
  SceneSpec scene;
  if (!buildScene(sceneName, &scene)) {
    std::string valid;
    for (const std::string& n : names) valid += (valid.empty() ? "" : ", ") + n;
    std::fprintf(stderr, "tumble_compare: unknown scene '%s'; valid scenes: %s\n", sceneName.c_str(), valid.c_str());
    return 1;
  }
  if (!std::isfinite(dt) || dt <= 0) {
    std::fprintf(stderr, "tumble_compare: --dt must be a finite number > 0 (seconds)\n");
    return 1;
  }
  if (steps == 0) steps = quick ? kQuickSteps : scene.defaultSteps;

  if (sweep) {
    std::error_code ec;
    std::filesystem::create_directories(outDir, ec);
    if (ec) {
      std::fprintf(stderr, "tumble_compare: cannot create --out folder '%s': %s\n", outDir.c_str(), ec.message().c_str());
      return 1;
    }
    std::fprintf(stderr, "tumble_compare: %s sweep, %zu bodies, %d steps of %.6g s per run\n", scene.name.c_str(),
                 scene.bodies.size(), steps, dt);
    SweepOptions options;
    options.outDir = outDir;
    options.quick = quick;
    options.jointSolver = jointSolver;
    options.threads = threads;
    json report;
    try {
      report = runSweep(scene, steps, dt, options);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "tumble_compare: %s\n", e.what());
      return 1;
    }
    return emitReport(report, reportPath);
  }

  std::fprintf(stderr, "tumble_compare: %s, %zu bodies, %d steps of %.6g s\n", scene.name.c_str(),
               scene.bodies.size(), steps, dt);
  std::fprintf(stderr, "  tumble ...\n");
  TumbleConfig tumbleConfig;
  tumbleConfig.sleep = sleep;
  tumbleConfig.jointSolver = jointSolver;
  tumbleConfig.threads = threads;
  json tumble = measured(runTumble(scene, steps, dt, tumbleConfig));
  tumble.update(tumbleSettings(tumbleConfig));
  if (!scene.joints.empty()) tumble["joint_solver"] = jointSolver;
  std::fprintf(stderr, "  bullet (%d iterations) ...\n", bulletIterations);
  BulletConfig peer;
  peer.iterations = bulletIterations;
  peer.sleep = sleep;
  json bullet = measured(runBullet(scene, steps, dt, peer));
  bullet.update(bulletSettings(scene, peer));

  json report;
  report["scene"] = scene.name;
  report["description"] = scene.description;
  report["steps"] = steps;
  report["dt"] = dt;
  report["bodies"] = scene.bodies.size();
  report["joints"] = scene.joints.size();
  report["gravity_mps2"] = {scene.gravity_mps2.x(), scene.gravity_mps2.y(), scene.gravity_mps2.z()};
  report["friction"] = scene.friction;
  report["restitution"] = scene.restitution;
  report["threads"] = threads;  // Tumble's; Bullet runs on one
  report["sleep"] = sleep;
  report["tumble"] = tumble;
  report["bullet"] = bullet;
  report["ratio_step_ms"] = ratio(tumble, bullet);
  // The same from each thread's CPU time: on a shared machine, time spent
  // descheduled counts in the wall figures of whichever engine it hit.
  report["ratio_step_cpu_ms"] = ratio(tumble, bullet, "step_cpu_ms_median");
  if (!noBulletDefault && bulletIterations != kBulletDefaultIterations) {
    std::fprintf(stderr, "  bullet (default %d iterations) ...\n", kBulletDefaultIterations);
    BulletConfig def;
    def.iterations = kBulletDefaultIterations;
    def.sleep = sleep;
    json bulletDefault = measured(runBullet(scene, steps, dt, def));
    bulletDefault.update(bulletSettings(scene, def));
    report["bullet_default"] = bulletDefault;
    report["ratio_step_ms_default"] = ratio(tumble, bulletDefault);
    report["ratio_step_cpu_ms_default"] = ratio(tumble, bulletDefault, "step_cpu_ms_median");
  }
  {
    const tumble::physics::WorldSettings ws;
    const int sweeps = ws.substeps * (ws.velocityIterations + ws.relaxIterations);
    report["iteration_mapping"] =
        "tumble: " + std::to_string(ws.substeps) + " substeps x (" + std::to_string(ws.velocityIterations) +
        " solve + " + std::to_string(ws.relaxIterations) + " relax) = " + std::to_string(sweeps) +
        " contact sweeps and 1 collision pass per step; bullet: 1 step with " + std::to_string(bulletIterations) +
        " iterations = " + std::to_string(bulletIterations) +
        " sweeps and 1 collision pass (ratio_step_ms); bullet_default: Bullet's default " +
        std::to_string(kBulletDefaultIterations) + " iterations (ratio_step_ms_default)";
  }
  report["measures"] =
      "penetration_max_m: deepest overlap the narrow phase saw over the run (Tumble: errorStats; Bullet: most "
      "negative btManifoldPoint::getDistance() after each step); stack_drift_m: largest horizontal (x,z) "
      "displacement of a dynamic body from its start, at the end; escaped: dynamic bodies whose centre is "
      "outside the container's cavity at the end; kinetic_energy_ratio: end / start (null when starting at rest)";

  return emitReport(report, reportPath);
}
