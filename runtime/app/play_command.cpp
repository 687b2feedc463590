// `tumble play`: a scenario in a window with the fixed-step accumulator and
// interpolated rendering, input, the pause menu, restart, hot reload and
// the tuning panel; without a display, a few seconds offscreen and a
// screenshot; with --frames, a fixed number of frames offscreen, fed by an
// events file through SDL's event queue, and a play report.
#include <SDL.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/bindings_menu.h"
#include "app/fixed_step.h"
#include "app/pause_menu.h"
#include "app/play_events.h"
#include "app/replay.h"
#include "app/run_report.h"
#include "app/scene_models.h"
#include "app/scene_view.h"
#include "app/simulation_loop.h"
#include "app/tuning.h"
#include "core/log.h"
#include "input/overrides_file.h"
#include "render/camera_rig.h"
#include "script/hot_reload.h"
#include "vehicle/vehicle_system.h"

namespace tumble::app {

namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

// The first vehicle of a scene as the player sees it: speed, the ground it
// covered (m, summed over the steps in the horizontal plane), its heading
// (degrees from +Z towards +X) at the start and now, its up axis.
struct VehicleTrack {
  bool present = false;
  physics::BodyId chassis;
  double distance_m = 0, startHeading_deg = 0;
  Vec3 last = Vec3::Zero();

  static std::optional<physics::BodyId> firstChassis(Scene& scene) {
    const vehicle::VehicleSystem* vs = scene.vehiclesIfAny();
    if (!vs || vs->count() == 0) return std::nullopt;
    std::optional<physics::BodyId> found;
    vs->forEach([&](vehicle::VehicleId id) {
      if (!found) found = vs->chassis(id);
    });
    return found;
  }
  static double heading_deg(const physics::Body& b) {
    const Vec3 f = b.orientation * Vec3::UnitZ();
    return std::atan2(double(f.x()), double(f.z())) * kRadToDeg;
  }
  void start(Scene& scene) {
    auto c = firstChassis(scene);
    present = c.has_value();
    if (!present) return;
    chassis = *c;
    const physics::Body& b = scene.world().body(chassis);
    last = b.position_m;
    startHeading_deg = heading_deg(b);
    distance_m = 0;
  }
  void afterStep(Scene& scene) {
    if (!present) return;
    auto c = firstChassis(scene);  // tuning may remake the chassis body
    if (!c) return;
    chassis = *c;
    const Vec3 p = scene.world().body(chassis).position_m;
    distance_m += std::hypot(double(p.x() - last.x()), double(p.z() - last.z()));
    last = p;
  }
  nlohmann::json report(Scene& scene) const {
    if (!present) return nullptr;
    const vehicle::VehicleSystem* vs = scene.vehiclesIfAny();
    double speed_mps = 0;
    vs->forEach([&](vehicle::VehicleId id) {
      if (vs->chassis(id) == chassis) speed_mps = vs->telemetry(id).speed_mps;
    });
    const physics::Body& b = scene.world().body(chassis);
    const Vec3 up = b.orientation * Vec3::UnitY();
    return {{"speed_kmh", speed_mps * 3.6},
            {"distance_m", distance_m},
            {"start_heading_deg", startHeading_deg},
            {"heading_deg", heading_deg(b)},
            {"up_y", up.y()},
            {"position_m", {b.position_m.x(), b.position_m.y(), b.position_m.z()}}};
  }
};

// One scene being played and everything made for it; a restart replaces
// the whole session with a fresh one from the same options.
struct PlaySession {
  std::unique_ptr<Scene> scene;
  std::unique_ptr<BindingsMenu> bindings;
  std::unique_ptr<script::HotReload> hotReload;
  CameraDirector director;
  VehicleTrack vehicle;
  double time_s = 0, accumulator = 0;
  long long step = 0;
};

Result<std::unique_ptr<Scene>> createPlayScene(const SceneOptions& options) {
  SceneOptions o = options;
  o.tuneOverrides = true;  // a designer's saved values apply when playing
  auto created = Scene::create(o);
  if (!created) return makeError(created.error());
  return std::move(created.value());
}

// Starts the scene (on_start) and wires it to the window: input events, the
// bindings menu, hot reload hooks, the camera.
std::unique_ptr<PlaySession> startSession(std::unique_ptr<Scene> scene, render::Renderer& renderer,
                                          PauseMenu& pauseMenu) {
  auto s = std::make_unique<PlaySession>();
  s->scene = std::move(scene);
  Scene& sc = *s->scene;
  sc.start();
  renderer.camera() = render::Camera{};
  frameCamera(sc, renderer.camera());  // after on_start made the bodies
  sc.savePreviousState();
  s->vehicle.start(sc);
  // Input: SDL events -> the mods' actions; the player's overrides; F1 menu.
  input::InputSystem& in = sc.input();
  s->bindings = std::make_unique<BindingsMenu>(in, input::bindingsConfigPath());
  if (Status st = in.enableGamepads(); !st) log::info("input: " + st.error());
  renderer.setEventHook([&in](const SDL_Event& e, bool hudWants) { return in.handleEvent(e, hudWants); });
  pauseMenu.setInput(&in);
  // Live editing: saved .lua files of the mod take effect (polled at 4 Hz).
  // Emitter files change the running emitters made from them; bindings.lua
  // replaces the actions (keeping the player's overrides).
  s->hotReload = std::make_unique<script::HotReload>(sc.host());
  s->hotReload->addHook(script::ModFileKind::Emitter, [&sc](const std::string&, const std::string& rel) {
    return sc.host().emitters().reloadFile(rel, sc.particlesIfAny());
  });
  s->hotReload->addHook(script::ModFileKind::Bindings,
                        [&sc](const std::string&, const std::string&) { return sc.reloadBindings(); });
  return s;
}

// Percentile of frame times (nearest rank), ms.
double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t rank = std::size_t(std::ceil(p * double(v.size())));  // 1-based
  return v[std::min(v.size() - 1, rank > 0 ? rank - 1 : 0)];
}

// No display and no --frames: play a few seconds as fast as possible, then
// show the last frame as a screenshot. No frame in between has a viewer, so
// none is drawn.
int playOffscreenSnapshot(const PlayOptions& o, Scene& scene, render::Renderer& renderer,
                          const Stopwatch& processClock) {
  const double dt = o.scene.dt_s;
  RunTimings total;
  render::Controls controls;
  render::FrameSnapshot snap;
  scene.start();
  frameCamera(scene, renderer.camera());
  scene.savePreviousState();
  double time_s = 0;
  long long step = 0;
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
  std::printf("  (start-up %.2f s; with a display, `tools/tumble play` opens a window; --frames N --events FILE\n"
              "   plays scripted input offscreen)\n",
              processClock.seconds() - simWall);
  return 0;
}

}  // namespace

int playScenario(const PlayOptions& o, const Stopwatch& processClock) {
  const bool scripted = o.frames >= 0;
  std::vector<PlayEvent> events;
  if (!o.eventsPath.empty()) {
    if (!scripted) {
      log::error("--events needs --frames N (how many frames to play)");
      return 1;
    }
    auto loaded = loadPlayEvents(o.eventsPath);
    if (!loaded) {
      log::error(loaded.error());
      return 1;
    }
    events = std::move(*loaded);
  }
  auto first = createPlayScene(o.scene);
  if (!first) {
    log::error(first.error());
    return 1;
  }
  // --frames always renders offscreen, so a test gives the same pictures and
  // events with or without a display.
  auto r = makeRenderer(**first, o.width, o.height, scripted, true);
  if (!r) {
    log::error(r.error());
    return 1;
  }
  render::Renderer& renderer = *r.value();
  if (renderer.offscreen() && !scripted) return playOffscreenSnapshot(o, **first, renderer, processClock);

  PauseMenu pauseMenu;
  std::unique_ptr<PlaySession> session = startSession(std::move(*first), renderer, pauseMenu);
  // The HUD's extra windows follow the current session (a restart replaces it).
  renderer.addHudPanel([&session] { session->bindings->draw(); });
  renderer.addHudPanel([&pauseMenu] { pauseMenu.draw(); });
  render::TuningPanel tuning;
  auto setUpTuning = [&] {
    tuning = render::TuningPanel{};
    tuning.title = session->scene->name();
    tuning.overridesPath = script::tuneOverridesPath(session->scene->host().mod().name);
  };
  setUpTuning();
  renderer.setTuningPanel(&tuning);
  // --record: what the scripts read of the input, step by step (a restart
  // starts the recording over: a replay is one session from its start).
  std::optional<ReplayRecorder> recorder;
  SceneOptions recordedOptions = o.scene;
  recordedOptions.tuneOverrides = true;  // as createPlayScene
  if (!o.recordPath.empty()) recorder.emplace().start(*session->scene, recordedOptions);

  RunTimings frame;
  render::Controls controls;
  render::FrameSnapshot snap;
  Stopwatch clock;
  double last = clock.seconds(), fpsTime = 0;
  int fpsFrames = 0, restarts = 0;
  double fps = 0;
  int shots = 0;
  double lastRender_s = 0;
  std::vector<double> frameMs;
  std::size_t nextEvent = 0;
  float pointer[2] = {0, 0};
  long long frameNo = 0;
  for (; !controls.quitRequested && (!scripted || frameNo < o.frames); ++frameNo) {
    Stopwatch frameClock;
    // Scripted input goes into SDL's own queue, then takes the player's path.
    for (; nextEvent < events.size() && events[nextEvent].frame <= frameNo; ++nextEvent) {
      SDL_Event e = toSdlEvent(events[nextEvent], renderer.windowId(), pointer);
      if (SDL_PushEvent(&e) < 0) log::warn(std::string("events: SDL_PushEvent failed: ") + SDL_GetError());
    }
    renderer.processEvents(controls);
    FrameRequests requests;
    applyFrameInput(session->scene->input(), *session->bindings, controls, renderer, &pauseMenu, &requests);
    if (requests.restart) {
      // A fresh scene from the same options: the start state again. If the
      // scenario cannot start now (a broken edit), the current one goes on.
      auto fresh = createPlayScene(o.scene);
      if (fresh) {
        session.reset();  // the old scene's systems go before the new ones start
        session = startSession(std::move(*fresh), renderer, pauseMenu);
        setUpTuning();
        if (recorder) recorder->start(*session->scene, recordedOptions);
        ++restarts;
        controls.paused = false;
        controls.stepOnce = false;
      } else {
        log::error("restart: " + fresh.error());
        session->scene->host().addMessage("restart failed: " + fresh.error(), 5);
      }
    }
    Scene& scene = *session->scene;
    double now = clock.seconds();
    for (const script::ReloadEvent& e : session->hotReload->poll(now, session->time_s, session->step))
      if (e.ok) scene.host().addMessage(e.message, 3);  // failures are already on the HUD as errors
    // Scripted frames each take one fixed step (the same steps on any
    // machine); a window takes the steps due in the wall time that passed.
    double elapsed = scripted ? scene.dt_s() : std::min(now - last, 0.25);  // avoid the spiral of death after a stall
    last = now;
    if (!controls.paused) session->accumulator += elapsed * (scripted ? 1.0 : controls.timeScale);
    if (controls.stepOnce) {
      session->accumulator += scene.dt_s();
      controls.stepOnce = false;
    }
    frame = RunTimings{};
    while (session->accumulator >= scene.dt_s() - (scripted ? 1e-9 : 0.0)) {  // the step may change (world.set_dt)
      const double h = scene.dt_s();
      scene.savePreviousState();
      stepScene(scene, StepTime{session->time_s, session->step}, frame);
      session->vehicle.afterStep(scene);
      if (recorder) recorder->afterStep(scene);
      ++session->step;
      session->time_s += h;
      session->accumulator = std::max(0.0, session->accumulator - h);
    }
    const double alpha = std::clamp(session->accumulator / scene.dt_s(), 0.0, 1.0);
    session->director.update(scene, alpha, float(elapsed), renderer.camera());
    if (!session->director.hasTarget() && renderer.camera().mode == render::CameraMode::Follow) {
      renderer.camera().target = dynamicCentroid(scene);
    }
    scene.setCollisionView(controls.collisionView);  // F3
    scene.snapshot(snap, alpha);
    session->director.decorate(scene, alpha, renderer.camera(), snap);
    snap.simTime_s = session->time_s;
    std::string shot;
    if (controls.screenshotRequested) {
      shot = "tumble-screenshot-" + std::to_string(++shots) + ".png";
      controls.screenshotRequested = false;
    }
    if (scripted && o.screenshotGiven && frameNo + 1 == o.frames) shot = o.screenshotPath;  // the last frame
    Stopwatch rs;
    frame.render_s = lastRender_s;
    if (controls.tuningPanelVisible) fillTuningPanel(scene.host().tunables(), tuning);
    Status st = renderer.drawFrame(snap, hudStats(scene, fps, frame, session->time_s), controls,
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
    frameMs.push_back(frameClock.seconds() * 1000);
  }
  Scene& scene = *session->scene;
  if (recorder) {
    if (Status st = recorder->write(scene, session->time_s, o.recordPath); !st) {
      log::error(st.error());
      scene.finish(session->time_s, session->step);
      return 1;
    }
    log::info("replay of " + std::to_string(session->step) + " steps written to " + o.recordPath);
  }
  if (!o.reportPath.empty()) {
    nlohmann::json items = nlohmann::json::array();
    for (const PauseMenu::ItemRect& it : pauseMenu.lastLayout())
      items.push_back({{"label", it.label}, {"x_px", it.x_px}, {"y_px", it.y_px}, {"w_px", it.w_px}, {"h_px", it.h_px}});
    nlohmann::json errors = nlohmann::json::array();
    for (const auto& e : scene.host().errors())
      errors.push_back({{"mod", e.mod}, {"file", e.file}, {"line", e.line}, {"message", e.message}});
    const auto& selectedItem = pauseMenu.items()[std::size_t(pauseMenu.selected())];
    nlohmann::json report = {
        {"scenario", scene.name()},
        {"title", scene.host().title()},
        {"frames", frameNo},
        {"steps", session->step},
        {"simulated_seconds", session->time_s},
        {"restarts", restarts},
        {"quit", controls.quitRequested},
        {"paused", controls.paused},
        {"pause_menu", {{"open", pauseMenu.isOpen()}, {"selected", selectedItem.label}, {"items", items}}},
        {"bindings_menu_open", session->bindings->isOpen()},
        {"debug_panel", controls.debugPanelVisible},
        {"camera", render::cameraModeName(renderer.camera().mode)},
        {"vehicle", session->vehicle.report(scene)},
        {"frame_ms", {{"p50", percentile(frameMs, 0.5)}, {"p95", percentile(frameMs, 0.95)},
                      {"max", frameMs.empty() ? 0.0 : *std::max_element(frameMs.begin(), frameMs.end())}}},
        {"hud_messages", hudStats(scene, fps, frame, session->time_s).messages},
        {"script_errors", errors},
        {"state_hash", stateHashText(scene)},
    };
    if (auto st = writeReport(o.reportPath, report); !st) {
      log::error("report: " + st.error());
      scene.finish(session->time_s, session->step);
      return 1;
    }
  }
  scene.finish(session->time_s, session->step);
  return 0;
}

}  // namespace tumble::app
