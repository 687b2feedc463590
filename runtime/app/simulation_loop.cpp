#include "app/simulation_loop.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/bindings_menu.h"
#include "app/fixed_step.h"
#include "app/run_report.h"
#include "app/tuning.h"
#include "app/scene_models.h"
#include "core/log.h"
#include "input/overrides_file.h"
#include "physics/joints/joint_system.h"
#include "script/hot_reload.h"
#include "vehicle/vehicle_system.h"

namespace tumble::app {

namespace {

int particleCount(Scene& scene) {
  const particles::ParticleSystem* ps = scene.particlesIfAny();
  return ps ? ps->particleCount() : 0;
}

// Orbit around the dynamic bodies, far enough to see them all.
void frameCamera(Scene& scene, render::Camera& cam) {
  // A scene with vehicles follows the first one from 12 m (until the chase
  // camera of the camera modes lands).
  if (const vehicle::VehicleSystem* vehicles = scene.vehiclesIfAny(); vehicles && vehicles->count() > 0) {
    bool first = true;
    vehicles->forEach([&](vehicle::VehicleId id) {
      if (!first) return;
      first = false;
      cam.target = scene.world().body(vehicles->chassis(id)).position_m.cast<float>();
      cam.distance_m = 12;
      cam.mode = render::CameraMode::Follow;
    });
    return;
  }
  Eigen::Vector3f lo(1e30f, 1e30f, 1e30f), hi = -lo;
  int n = 0;
  scene.world().forEachBody([&](physics::BodyId, const physics::Body& b) {
    if (b.type == physics::BodyType::Static) return;
    Eigen::Vector3f p = b.position_m.cast<float>();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    ++n;
  });
  if (n == 0) return;
  cam.target = (lo + hi) / 2;
  cam.target.y() = std::max(cam.target.y() * 0.5f, 0.5f);
  cam.distance_m = std::clamp((hi - lo).norm() * 1.4f + 6.0f, 6.0f, 400.0f);
}

Eigen::Vector3f dynamicCentroid(Scene& scene) {
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  int n = 0;
  scene.world().forEachBody([&](physics::BodyId, const physics::Body& b) {
    if (b.type != physics::BodyType::Dynamic) return;
    sum += b.position_m.cast<float>();
    ++n;
  });
  return n ? Eigen::Vector3f(sum / float(n)) : Eigen::Vector3f(0, 1, 0);
}

render::HudStats hudStats(Scene& scene, double fps, const RunTimings& perFrame, double time_s) {
  render::HudStats h;
  h.scenario = scene.host().title();
  h.fps = fps;
  h.physics_ms = perFrame.physics_s * 1000;
  h.script_ms = perFrame.script_s * 1000;
  h.render_ms = perFrame.render_s * 1000;
  h.particles_ms = perFrame.particles_s * 1000;
  h.simTime_s = time_s;
  h.bodies = scene.world().bodyCount();
  h.contacts = scene.world().contactPointCount();
  for (const auto& e : scene.host().errors()) h.messages.push_back(e.summary());
  if (h.messages.size() > 5) h.messages.erase(h.messages.begin(), h.messages.end() - 5);
  for (const auto& line : scene.host().hudText()) h.messages.insert(h.messages.begin(), line);
  for (const auto& m : scene.host().activeMessages(time_s)) h.messages.insert(h.messages.begin(), m);
  if (scene.host().hasScore()) h.messages.insert(h.messages.begin(), "score: " + std::to_string(scene.host().score()));
  if (scene.host().outcome() != script::Outcome::None)
    h.messages.insert(h.messages.begin(), std::string(scene.host().outcome() == script::Outcome::Won ? "WON: " : "LOST: ") +
                                              scene.host().outcomeReason());
  return h;
}

Result<std::unique_ptr<render::Renderer>> makeRenderer(Scene& scene, int w, int h, bool offscreen, bool hud) {
  render::WindowConfig cfg;
  cfg.width = w;
  cfg.height = h;
  cfg.title = "Tumble - " + scene.name();
  cfg.forceOffscreen = offscreen;
  cfg.hud = hud;
  if (scene.hasTerrain()) cfg.msaaSamples = 1;  // terrain fill rate on llvmpipe (render/README.md)
  auto r = render::Renderer::create(cfg);
  if (!r) return makeError("cannot open a window or an offscreen GL context: " + r.error());
  scene.noteSubsystem("render");
  return r;
}

}  // namespace

int runScenario(const RunOptions& o, const Stopwatch& processClock) {
  auto created = Scene::create(o.scene);
  if (!created) {
    log::error(created.error());
    return 1;
  }
  Scene& scene = **created;
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
  long long baseStep = 0, done = 0;
  for (long long i = 0; o.steps >= 0 ? i < steps : time_s < endTime_s - 0.5 * scene.dt_s(); ++i) {
    if (renderer && !shotTaken && time_s >= shotAt) takeShot(time_s);
    if (scene.dt_s() != stepDt) baseTime_s = time_s, baseStep = i, stepDt = scene.dt_s();
    stepScene(scene, StepTime{time_s, i}, t);
    time_s = baseTime_s + double(i + 1 - baseStep) * stepDt;
    done = i + 1;
    counts.bodiesMax = std::max(counts.bodiesMax, scene.world().bodyCount());
    if (const physics::JointSystem* joints = scene.jointsIfAny())
      counts.jointsMax = std::max(counts.jointsMax, joints->jointCount());
    counts.particlesMax = std::max(counts.particlesMax, particleCount(scene));
  }
  steps = done;
  if (renderer && !shotTaken) takeShot(time_s);
  {
    Stopwatch sw;
    scene.finish(time_s, steps);
    t.script_s += sw.seconds();
  }
  counts.bodiesMax = std::max(counts.bodiesMax, scene.world().bodyCount());
  t.total_s = processClock.seconds();
  int status = exitStatusFor(scene);
  if (!shotStatus) {
    log::error("screenshot: " + shotStatus.error());
    status = 1;
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
  return status;
}

int playScenario(const PlayOptions& o, const Stopwatch& processClock) {
  SceneOptions sceneOptions = o.scene;
  sceneOptions.tuneOverrides = true;  // a designer's saved values apply when playing
  auto created = Scene::create(sceneOptions);
  if (!created) {
    log::error(created.error());
    return 1;
  }
  Scene& scene = **created;
  auto r = makeRenderer(scene, o.width, o.height, false, true);
  if (!r) {
    log::error(r.error());
    return 1;
  }
  render::Renderer& renderer = *r.value();
  const double dt = o.scene.dt_s;
  RunTimings total, frame;
  render::Controls controls;
  render::FrameSnapshot snap;
  scene.start();
  frameCamera(scene, renderer.camera());  // after on_start made the bodies
  scene.savePreviousState();
  double time_s = 0, accumulator = 0;
  long long step = 0;

  if (renderer.offscreen()) {
    // No display: play a few seconds as fast as possible, then show the
    // last frame as a screenshot. No frame in between has a viewer, so none
    // is drawn.
    double seconds = std::min(o.offscreenSeconds, scene.host().duration_s());
    long long steps = std::llround(seconds / dt);
    Stopwatch wall;
    bool dtChanged = false;
    for (; step < steps; ++step) {
      const double h = scene.dt_s();  // world.set_dt may change it
      dtChanged = dtChanged || h != dt;
      scene.savePreviousState();
      stepScene(scene, StepTime{time_s, step}, total);
      time_s = dtChanged ? time_s + h : double(step + 1) * dt;
    }
    double simWall = wall.seconds();
    frameCamera(scene, renderer.camera());
    CameraDirector director;
    director.update(scene, 1.0, 0.0f, renderer.camera());
    scene.snapshot(snap, 1.0);
    director.decorate(scene, 1.0, renderer.camera(), snap);
    snap.simTime_s = time_s;
    RunTimings perStep = total;
    perStep.physics_s /= double(std::max(1LL, steps));
    perStep.script_s /= double(std::max(1LL, steps));
    perStep.particles_s /= double(std::max(1LL, steps));
    Status st = renderer.drawFrame(snap, hudStats(scene, 0, perStep, time_s), controls, o.screenshotPath.c_str());
    scene.finish(time_s, step);
    if (!st) {
      log::error("screenshot: " + st.error());
      return 1;
    }
    StepMsSummary sm = summarizeSteps(total.stepMs);
    std::printf("No display: played %s offscreen for %.2f s of simulated time (%lld steps) in %.2f s.\n",
                scene.name().c_str(), time_s, steps, simWall);
    std::printf("  bodies %d, contacts %d, step %.3f ms median (%.3f ms max), script errors %zu\n",
                scene.world().bodyCount(), scene.world().contactPointCount(), sm.median, sm.max,
                scene.host().errors().size());
    std::printf("  screenshot: %s\n", std::filesystem::absolute(o.screenshotPath).c_str());
    std::printf("  (start-up %.2f s; with a display, `tools/tumble play` opens a window)\n",
                processClock.seconds() - simWall);
    return 0;
  }

  // Input: SDL events -> the mods' actions; the player's overrides; F1 menu.
  input::InputSystem& in = scene.input();
  BindingsMenu menu(in, input::bindingsConfigPath());
  if (Status st = in.enableGamepads(); !st) log::info("input: " + st.error());
  renderer.setEventHook([&in](const SDL_Event& e, bool hudWants) { return in.handleEvent(e, hudWants); });
  renderer.addHudPanel([&menu] { menu.draw(); });
  // Live editing: saved .lua files of the mod take effect (polled at 4 Hz),
  // and the tuning panel (F2) edits the scenario's tunables.
  // Emitters, bindings and vehicles reload through hooks registered here:
  //   hotReload.addHook(script::ModFileKind::Emitter, [&](const std::string& path, const std::string& rel) {...});
  script::HotReload hotReload(scene.host());
  // Emitter files change the running emitters made from them; bindings.lua
  // replaces the actions (keeping the player's overrides).
  hotReload.addHook(script::ModFileKind::Emitter, [&scene](const std::string&, const std::string& rel) {
    return scene.host().emitters().reloadFile(rel, scene.particlesIfAny());
  });
  hotReload.addHook(script::ModFileKind::Bindings,
                    [&scene](const std::string&, const std::string&) { return scene.reloadBindings(); });
  render::TuningPanel tuning;
  tuning.title = scene.name();
  tuning.overridesPath = script::tuneOverridesPath(scene.host().mod().name);
  renderer.setTuningPanel(&tuning);

  CameraDirector director;
  Stopwatch clock;
  double last = clock.seconds(), fpsTime = 0;
  int fpsFrames = 0;
  double fps = 0;
  int shots = 0;
  double lastRender_s = 0;
  while (!controls.quitRequested) {
    renderer.processEvents(controls);
    applyFrameInput(in, menu, controls, renderer);
    double now = clock.seconds();
    for (const script::ReloadEvent& e : hotReload.poll(now, time_s, step))
      if (e.ok) scene.host().addMessage(e.message, 3);  // failures are already on the HUD as errors
    double elapsed = std::min(now - last, 0.25);  // avoid the spiral of death after a stall
    last = now;
    if (!controls.paused) accumulator += elapsed * controls.timeScale;
    if (controls.stepOnce) {
      accumulator += scene.dt_s();
      controls.stepOnce = false;
    }
    frame = RunTimings{};
    while (accumulator >= scene.dt_s()) {  // the step may change while playing (world.set_dt)
      const double h = scene.dt_s();
      scene.savePreviousState();
      stepScene(scene, StepTime{time_s, step}, frame);
      ++step;
      time_s += h;
      accumulator -= h;
    }
    director.update(scene, accumulator / scene.dt_s(), float(elapsed), renderer.camera());
    if (!director.hasTarget() && renderer.camera().mode == render::CameraMode::Follow) {
      renderer.camera().target = dynamicCentroid(scene);
    }
    scene.setCollisionView(controls.collisionView);  // F3
    scene.snapshot(snap, accumulator / scene.dt_s());
    director.decorate(scene, accumulator / scene.dt_s(), renderer.camera(), snap);
    snap.simTime_s = time_s;
    std::string shot;
    if (controls.screenshotRequested) {
      shot = "tumble-screenshot-" + std::to_string(++shots) + ".png";
      controls.screenshotRequested = false;
    }
    Stopwatch rs;
    frame.render_s = lastRender_s;
    if (controls.tuningPanelVisible) fillTuningPanel(scene.host().tunables(), tuning);
    Status st = renderer.drawFrame(snap, hudStats(scene, fps, frame, time_s), controls,
                                   shot.empty() ? nullptr : shot.c_str());
    applyTuningPanel(tuning, scene.host().tunables(), scene.host().mod().name);
    lastRender_s = rs.seconds();
    if (!shot.empty()) {
      if (st) log::info("screenshot saved: " + shot);
      else log::error("screenshot: " + st.error());
    }
    ++fpsFrames;
    if (now - fpsTime >= 0.5) {
      fps = fpsFrames / (now - fpsTime);
      fpsFrames = 0;
      fpsTime = now;
    }
  }
  scene.finish(time_s, step);
  return 0;
}

}  // namespace tumble::app
