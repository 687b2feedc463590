// `tumble run`: a scenario headless (or offscreen for --screenshot) for a
// number of fixed steps, its expectations, the run report.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <optional>
#include <system_error>

#include "app/fixed_step.h"
#include "app/replay.h"
#include "app/run_report.h"
#include "app/scene_state.h"
#include "app/scene_models.h"
#include "app/scene_view.h"
#include "app/simulation_loop.h"
#include "core/file_util.h"
#include "core/log.h"
#include "physics/deformable.h"
#include "physics/joints/joint_system.h"

namespace tumble::app {

namespace {

// A folder under the system's temporary directory (mkdtemp: a fresh name,
// mode 0700) that is removed with everything in it when this goes away.
class ThrowAwayDir {
 public:
  static Result<ThrowAwayDir> create() {
    std::error_code ec;
    const std::filesystem::path base = std::filesystem::temp_directory_path(ec);
    if (ec) return makeError("no temporary directory for the run's saves: " + ec.message() + " (give --save-dir DIR)");
    std::string name = (base / "tumble-run-saves-XXXXXX").string();
    if (!mkdtemp(name.data()))
      return makeError("cannot create a temporary folder for the run's saves in " + base.string() + " (give --save-dir DIR)");
    return ThrowAwayDir(name);
  }
  ThrowAwayDir(ThrowAwayDir&& o) noexcept : m_path(std::move(o.m_path)) { o.m_path.clear(); }
  ThrowAwayDir(const ThrowAwayDir&) = delete;
  ThrowAwayDir& operator=(const ThrowAwayDir&) = delete;
  ThrowAwayDir& operator=(ThrowAwayDir&&) = delete;
  ~ThrowAwayDir() {
    std::error_code ec;
    if (!m_path.empty()) std::filesystem::remove_all(m_path, ec);
  }
  const std::string& path() const { return m_path; }

 private:
  explicit ThrowAwayDir(std::string path) : m_path(std::move(path)) {}
  std::string m_path;
};

/// run --inject-nan: the first dynamic body's position and velocity become
/// NaN, as a solver fault would leave them. Returns false when the world has
/// no dynamic body to break.
/// Without one, the last particle of the first rope or cloth gets a NaN
/// velocity; without those, the next ode.system step of the script leaves
/// NaN in its state.
void injectNan(Scene& scene) {
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  physics::World& world = scene.world();
  bool done = false;
  world.forEachBody([&](physics::BodyId id, const physics::Body& b) {
    if (done || !b.isDynamic()) return;
    world.setPosition(id, Vec3(nan, b.position_m.y(), b.position_m.z()));
    world.setLinearVelocity(id, Vec3::Constant(nan));
    done = true;
  });
  if (physics::DeformableSystem* ds = scene.deformablesIfAny(); ds && !done) {
    ds->forEach([&](int id, const physics::Deformable&) {
      physics::Deformable* d = done ? nullptr : ds->get(id);
      if (d && d->particleCount() > 0) done = d->setVelocity(d->particleCount() - 1, Vec3::Constant(nan));
    });
  }
  if (!done) scene.host().requestNanInjection();
}


}  // namespace

int runScenario(const RunOptions& options, const Stopwatch& processClock) {
  RunOptions o = options;
  std::optional<ThrowAwayDir> saves;
  if (o.saveDir.empty()) {
    auto made = ThrowAwayDir::create();
    if (!made) {
      log::error(made.error());
      return 1;
    }
    saves.emplace(std::move(made.value()));
    o.scene.saveDir = saves->path();
  } else {
    o.scene.saveDir = o.saveDir;
  }
  if (!o.audioOutPath.empty()) o.scene.audioOutput = audio::AudioOutput::Loopback;
  // --replay: the recorded session's scenario, settings and input.
  std::optional<Replay> replay;
  if (!o.replayPath.empty()) {
    auto loaded = loadReplay(o.replayPath);
    if (!loaded) {
      log::error(loaded.error());
      return 1;
    }
    replay.emplace(std::move(loaded.value()));
    o.scene.scenarioRef = replay->scenario;
    o.scene.seed = replay->seed;
    o.scene.dt_s = replay->dt_s;
    o.scene.substeps = replay->substeps;
    o.scene.integrator = replay->integrator;
    o.scene.sets = replay->sets;
    o.steps = (long long)replay->steps.size();
    if (!replay->tuneOverrides.is_null()) {
      // The player's tunable values as recorded, read from the run's own folder.
      o.scene.tuneOverridesFile = o.scene.saveDir + "/recorded-tune-overrides.json";
      if (Status st = writeFileAtomic(o.scene.tuneOverridesFile, replay->tuneOverrides.dump()); !st) {
        log::error("replay: " + st.error());
        return 1;
      }
    }
  }
  // --load-state: the snapshot's scenario and settings.
  std::optional<SceneStateFile> loaded;
  if (!o.loadStatePath.empty()) {
    auto file = loadSceneState(o.loadStatePath);
    if (!file) {
      log::error(file.error());
      return 1;
    }
    if (o.scene.scenarioRef != file->scenario) {
      log::error(o.loadStatePath + ": field \"scenario\": the snapshot is of " + file->scenario + ", not " +
                 o.scene.scenarioRef);
      return 1;
    }
    loaded.emplace(std::move(file.value()));
    applySceneStateOptions(*loaded, o.scene);
  }
  auto created = Scene::create(o.scene);
  if (!created) {
    log::error(created.error());
    return 1;
  }
  Scene& scene = **created;
  // Offline sound covers the whole run, from before on_start.
  if (!o.audioOutPath.empty() && scene.audio().output() != audio::AudioOutput::Loopback) {
    log::error("--audio-out: cannot render sound offline (see the message above)");
    return 1;
  }
  if (replay)
    for (const std::string& w : replayVersionWarnings(*replay, scene)) log::warn("replay " + o.replayPath + ": " + w);
  RunTimings t;
  RunCounts counts;
  const double dt = o.scene.dt_s;
  long long steps = o.steps >= 0 ? o.steps
                                 : std::llround((o.seconds >= 0 ? o.seconds : scene.host().duration_s()) / dt);
  std::unique_ptr<render::Renderer> renderer;
  if (!o.screenshotPath.empty()) {
    auto r = makeRenderer(scene, o.width, o.height, true, false);
    if (!r) {
      log::error(r.error());
      return 1;
    }
    renderer = std::move(r.value());
  }
  {
    Stopwatch sw;
    scene.start();
    t.script_s += sw.seconds();
  }
  if (renderer) frameCamera(scene, renderer->camera());  // after on_start made the bodies
  if (loaded) {
    if (Status st = restoreSceneState(scene, *loaded, o.loadStatePath); !st) {
      log::error(st.error());
      return 1;
    }
  }
  t.startup_s = processClock.seconds();
  const double shotAt = o.screenshotAt_s >= 0 ? o.screenshotAt_s : double(steps) * dt;
  bool shotTaken = false;
  Status shotStatus = Ok{};
  CameraDirector director;  // camera.set_mode from the scenario
  auto takeShot = [&](double time_s) {
    Stopwatch sw;
    if (scene.vehiclesIfAny()) frameCamera(scene, renderer->camera());  // where the car is now
    render::FrameSnapshot frame;
    director.update(scene, 1.0, 0.0f, renderer->camera());
    scene.snapshot(frame, 1.0);
    director.decorate(scene, 1.0, renderer->camera(), frame);
    frame.simTime_s = time_s;
    render::Controls controls;
    shotStatus = renderer->drawFrame(frame, hudStats(scene, 0, RunTimings{}, time_s), controls,
                                     o.screenshotPath.c_str());
    shotTaken = true;
    t.render_s += sw.seconds();
  };
  double time_s = 0;
  // Time is base + (steps since the last dt change) * dt, so that without a
  // change it is exactly (i + 1) * dt as before. With --seconds (or the
  // scenario's duration) a changed dt still ends the run at that time.
  const double endTime_s = double(steps) * dt;
  double baseTime_s = 0, stepDt = dt;
  long long baseStep = 0, done = 0, first = 0;
  if (loaded) {
    time_s = loaded->clock.time_s;
    baseTime_s = loaded->clock.baseTime_s;
    baseStep = loaded->clock.baseStep;
    stepDt = loaded->clock.stepDt_s;
    first = done = loaded->clock.step;
  }
  const double saveAt_s = o.screenshotAt_s >= 0 ? o.screenshotAt_s : endTime_s;
  bool saved = o.saveStatePath.empty();
  for (long long i = first; o.steps >= 0 ? i < steps : time_s < endTime_s - 0.5 * scene.dt_s(); ++i) {
    if (renderer && !shotTaken && time_s >= shotAt) takeShot(time_s);
    if (scene.dt_s() != stepDt) baseTime_s = time_s, baseStep = i, stepDt = scene.dt_s();
    if (i == o.injectNanAtStep) injectNan(scene);
    if (replay) playBackStep(*replay, i, scene);
    stepScene(scene, StepTime{time_s, i}, t);
    // A replay keeps time as play does (a sum of the steps).
    time_s = replay ? time_s + stepDt : baseTime_s + double(i + 1 - baseStep) * stepDt;
    done = i + 1;
    if (!saved && time_s >= saveAt_s - 1e-9) {
      if (Status st = saveSceneState(scene, RunClock{done, time_s, baseTime_s, baseStep, stepDt}, o.saveStatePath); !st) {
        log::error(st.error());
        return 1;
      }
      log::info("snapshot written: " + o.saveStatePath + " (step " + std::to_string(done) + ", t = " +
                std::to_string(time_s) + " s)");
      saved = true;
    }
    counts.bodiesMax = std::max(counts.bodiesMax, scene.world().bodyCount());
    if (const physics::JointSystem* joints = scene.jointsIfAny())
      counts.jointsMax = std::max(counts.jointsMax, joints->jointCount());
    counts.particlesMax = std::max(counts.particlesMax, particleCount(scene));
  }
  steps = done;
  if (!saved) {
    log::error("--save-state: the run ended at " + std::to_string(time_s) + " s, before --at " +
               std::to_string(saveAt_s) + " s; nothing was written");
    return 1;
  }
  if (renderer && !shotTaken) takeShot(time_s);
  // A replay's state is taken where play took it: before on_finish.
  const std::string replayedHash = replay ? stateHashText(scene) : std::string();
  {
    Stopwatch sw;
    scene.finish(time_s, steps);
    t.script_s += sw.seconds();
  }
  counts.bodiesMax = std::max(counts.bodiesMax, scene.world().bodyCount());
  // A body whose state went non-finite was frozen by the world: whatever the
  // scenario checked, the run is not physics any more. Only a failure is
  // added, so runs without one keep exactly the scenario's expectations.
  if (const long nan = nonFiniteEvents(scene); nan > 0) {
    script::Expectation e;
    e.name = "physics state stayed finite (non-finite bodies frozen, rope or cloth steps undone)";
    e.value = double(nan);
    e.max = 0;
    scene.host().addExpectation(e);
    log::error(scene.name() + ": " + std::to_string(nan) +
               " times a body, rope or cloth went non-finite and was held where its step began "
               "(report: error.nan_events)");
  }
  t.total_s = processClock.seconds();
  int status = exitStatusFor(scene);
  if (!shotStatus) {
    log::error("screenshot: " + shotStatus.error());
    status = 1;
  }
  if (!o.audioOutPath.empty()) {
    const audio::AudioSystem& a = *scene.audioIfAny();
    if (a.renderTruncated())
      log::warn("--audio-out: only the first " + std::to_string(int(audio::AudioSystem::kMaxRenderSeconds)) + " s are kept");
    if (auto st = audio::writeWav(o.audioOutPath, a.rendered(), 2, audio::kSampleRate_hz); !st) {
      log::error("--audio-out: " + st.error());
      status = 1;
    } else {
      log::info("sound written: " + o.audioOutPath);
    }
  }
  auto report = buildReport(scene, steps, time_s, t, counts);
  if (!o.reportPath.empty()) {
    if (auto st = writeReport(o.reportPath, report); !st) {
      log::error("report: " + st.error());
      return 1;
    }
  }
  // A short summary on stdout; the report has everything.
  int failed = 0;
  for (const auto& e : scene.host().expectations()) failed += !e.ok;
  std::printf("%s: %lld steps (%.2f s simulated) in %.2f s; %zu expectations, %d failed; %zu script errors; "
              "state %s\n",
              scene.name().c_str(), steps, time_s, t.total_s, scene.host().expectations().size(), failed,
              scene.host().errors().size(), report["state_hash"].get<std::string>().c_str());
  for (const auto& e : scene.host().expectations())
    if (!e.ok) std::printf("  expectation failed: %s (value %g)\n", e.name.c_str(), e.value);
  if (replay) {
    const std::string& hash = replayedHash;
    if (hash != replay->stateHash) {
      std::printf("replay %s: DIVERGED: the recorded session ended in state %s, this run in %s\n",
                  o.replayPath.c_str(), replay->stateHash.c_str(), hash.c_str());
      return 4;
    }
    std::printf("replay %s: reproduced the recorded state %s after %lld steps\n", o.replayPath.c_str(), hash.c_str(),
                steps);
  }
  return status;
}

}  // namespace tumble::app
