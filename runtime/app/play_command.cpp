// `tumble play`: a scenario in a window with the fixed-step accumulator and
// interpolated rendering, input, hot reload and the tuning panel; without a
// display, a few seconds offscreen and a screenshot.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "app/bindings_menu.h"
#include "app/fixed_step.h"
#include "app/run_report.h"
#include "app/scene_models.h"
#include "app/scene_view.h"
#include "app/simulation_loop.h"
#include "app/tuning.h"
#include "core/log.h"
#include "input/overrides_file.h"
#include "script/hot_reload.h"

namespace tumble::app {

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
