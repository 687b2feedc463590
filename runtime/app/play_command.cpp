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
#include "app/designer_mode.h"
#include "app/driving_hud.h"
#include "app/fixed_step.h"
#include "app/game_catalog.h"
#include "app/main_menu.h"
#include "app/paths.h"
#include "app/player_settings.h"
#include "app/thumbnails.h"
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
#include "app/scene_audio.h"
#include "script/hot_reload.h"
#include "script/mod_bindings.h"
#include "script/tunables.h"
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
    std::string name;
    vs->forEach([&](vehicle::VehicleId id) {
      if (vs->chassis(id) == chassis) name = vs->def(id).name;
    });
    return {{"name", name},
            {"speed_kmh", speed_mps * 3.6},
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

// At most `budget` particles are drawn: beyond it an evenly spaced subset
// (every k-th), so a dense cloud thins out rather than losing one end. The
// simulation keeps every particle.
void thinParticles(render::FrameSnapshot& snap, int budget) {
  auto thin = [](std::vector<render::DrawParticle>& v, std::size_t keep) {
    if (v.size() <= keep) return;
    const double stride = double(v.size()) / double(std::max<std::size_t>(1, keep));
    std::size_t out = 0;
    for (std::size_t i = 0; i < keep; ++i) v[out++] = v[std::size_t(double(i) * stride)];
    v.resize(out);
  };
  const std::size_t total = snap.particles.size() + snap.additiveParticles.size();
  if (budget < 0 || total <= std::size_t(budget)) return;
  const double share = double(budget) / double(total);
  thin(snap.particles, std::size_t(double(snap.particles.size()) * share));
  thin(snap.additiveParticles, std::size_t(double(snap.additiveParticles.size()) * share));
}

// The window for the main menu, before any scene exists.
Result<std::unique_ptr<render::Renderer>> makeMenuRenderer(int w, int h, bool offscreen) {
  render::WindowConfig cfg;
  cfg.width = w;
  cfg.height = h;
  cfg.title = "Tumble";
  cfg.forceOffscreen = offscreen;
  auto r = render::Renderer::create(cfg);
  if (!r) return makeError("cannot open a window or an offscreen GL context: " + r.error());
  return r;
}

}  // namespace

int playScenario(const PlayOptions& options, const Stopwatch& processClock) {
  PlayOptions o = options;
  // Sound: the default device unless --mute.
  o.scene.audioOutput = o.mute ? audio::AudioOutput::Silent : audio::AudioOutput::Device;
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
  // The player's settings; a broken file is reported and the defaults used.
  const std::string settingsFile = settingsPath();
  PlayerSettings settings;
  std::string settingsProblem;
  if (auto loaded = loadPlayerSettings(settingsFile)) {
    settings = *loaded;
  } else {
    settingsProblem = loaded.error() + " -- using the default settings; the file is rewritten when you change one";
    log::error("settings: " + settingsProblem);
  }
  // The player's volumes (the settings page changes them while playing).
  o.scene.volumes = audio::AudioVolumes{float(settings.volume_master), float(settings.volume_effects),
                                        float(settings.volume_engine)};
  QualityLevel quality = settings.quality;
  if (!o.quality.empty()) {
    auto q = parseQuality(o.quality);
    if (!q) {
      log::error("--quality: " + q.error());
      return 1;
    }
    quality = *q;
  }
  const int width = o.sizeGiven ? o.width : settings.width, height = o.sizeGiven ? o.height : settings.height;

  std::unique_ptr<Scene> first;
  if (!o.menu && !o.design) {
    auto created = createPlayScene(o.scene);
    if (!created) {
      log::error(created.error());
      return 1;
    }
    first = std::move(*created);
  }
  // --frames always renders offscreen, so a test gives the same pictures and
  // events with or without a display.
  auto r = first ? makeRenderer(*first, width, height, scripted, true) : makeMenuRenderer(width, height, scripted);
  if (!r) {
    log::error(r.error());
    return 1;
  }
  render::Renderer& renderer = *r.value();
  auto applyQuality = [&] { renderer.setQuality(renderQuality(qualityPreset(quality))); };
  applyQuality();
  if (renderer.offscreen() && !scripted && o.design) {
    log::error("design: the designer needs a display (or --frames N --events FILE for scripted input)");
    return 1;
  }
  if (renderer.offscreen() && !scripted) {
    if (!first) {  // nobody can see a menu: show the default scenario as before
      std::printf("No display for the main menu: playing %s.\n", o.scene.scenarioRef.c_str());
      auto created = createPlayScene(o.scene);
      if (!created) {
        log::error(created.error());
        return 1;
      }
      first = std::move(*created);
      first->noteSubsystem("render");
    }
    return playOffscreenSnapshot(o, *first, renderer, processClock);
  }
  if (!o.sizeGiven && settings.fullscreen && !scripted) renderer.setWindowMode(width, height, true);
  std::pair<int, int> appliedResolution{settings.width, settings.height};  // the settings' size last applied

  GameCatalog catalog(modSearchDirs(o.scene.modDirs));
  ThumbnailCache thumbnails(renderer, o.scene.modDirs);
  MainMenu mainMenu(catalog, settings, settingsFile, &thumbnails);
  if (!settingsProblem.empty()) mainMenu.setStatus(settingsProblem);
  // The menu's own keys and pad buttons (no mod needs to be loaded).
  input::InputSystem menuInput(menuBindings());
  if (Status st = menuInput.enableGamepads(); !st) log::info("input: " + st.error());
  // The bindings menu reached from the main menu's settings (no scene): the
  // actions of every mod found, the player's overrides.
  std::unique_ptr<input::InputSystem> looseInput;
  std::unique_ptr<BindingsMenu> looseBindings;

  PauseMenu pauseMenu;
  SceneOptions current = o.scene;  // what the session plays (the menu's choice of scenario and vehicle)
  std::unique_ptr<PlaySession> session;
  auto offersVehicle = [&](const std::string& ref) {
    const ScenarioEntry* e = catalog.scenario(ref);
    return e != nullptr && e->takesVehicle;
  };
  // The designer (design_*.cpp): shown while it exists and no scene is
  // driven; a scene it drives returns to it (F5, Back to designer).
  std::unique_ptr<DesignerMode> designer;
  render::Camera cameraBeforeDrive;
  auto designerShown = [&] { return designer && !session && !mainMenu.isOpen(); };
  if (first) {
    session = startSession(std::move(first), renderer, pauseMenu);
    pauseMenu.setVehicleChoice(offersVehicle(current.scenarioRef));
  } else if (o.design) {
    designer = std::make_unique<DesignerMode>(catalog, o.scene.modDirs, renderer);
    if (o.designRef.empty() || o.designRef == "new") {
      designer->showNewMap();
    } else if (Status st = designer->open(o.designRef); !st) {
      log::error(st.error());
      return 1;
    }
  } else {
    mainMenu.openRoot();
  }
  bool backToDesigner = false;
  GameHud gameHud;  // speed, rpm, gear, lap, minimap, messages, script-error console
  gameHud.setRenderer(&renderer);
  renderer.addHudPanel([&gameHud, &session, &mainMenu] {
    // A menu page opened over the game (Change vehicle, Settings) covers the
    // screen; the HUD under it would show through its title.
    if (session && !mainMenu.isOpen()) gameHud.draw();
  });
  auto openBindingsMenu = [&]() -> BindingsMenu* {
    if (session) return session->bindings->isOpen() ? session->bindings.get() : nullptr;
    return looseBindings && looseBindings->isOpen() ? looseBindings.get() : nullptr;
  };
  // Events go to what the player is looking at: the bindings menu's actions
  // while it is open, else the main menu's keys, else the game's actions.
  renderer.setEventHook([&](const SDL_Event& e, bool hudWants) {
    if (openBindingsMenu()) return session ? session->scene->input().handleEvent(e, hudWants)
                                           : looseInput->handleEvent(e, hudWants);
    // Every input hears a release: a key pressed in one (Return choosing a
    // pause menu item) and let go in another (the menu page it opened) must
    // not stay held there and fire again when that one listens again.
    if (e.type == SDL_KEYUP || e.type == SDL_MOUSEBUTTONUP || e.type == SDL_CONTROLLERBUTTONUP) {
      menuInput.handleEvent(e, hudWants);
      if (looseInput) looseInput->handleEvent(e, hudWants);
      if (session) session->scene->input().handleEvent(e, hudWants);
    }
    if (e.type == SDL_QUIT || e.type == SDL_WINDOWEVENT) {  // closing and resizing the window always work
      if (session) session->scene->input().handleEvent(e, hudWants);
      return false;
    }
    if (mainMenu.isOpen()) {
      menuInput.handleEvent(e, hudWants);
      return true;  // nothing of the game (camera, pause keys) under the menu
    }
    if (designerShown()) return designer->handleEvent(e, hudWants);
    if (designer && session && e.type == SDL_KEYDOWN && e.key.keysym.sym == SDLK_F5 && e.key.repeat == 0) {
      backToDesigner = true;  // F5 again: back from driving
      return true;
    }
    if (session) return session->scene->input().handleEvent(e, hudWants);
    return true;
  });
  // The HUD's extra windows follow the current session (a restart replaces it).
  renderer.addHudPanel([&mainMenu] { mainMenu.draw(); });
  renderer.addHudPanel([&] {
    if (designerShown()) designer->draw();
  });
  renderer.addHudPanel([&pauseMenu] { pauseMenu.draw(); });
  renderer.addHudPanel([&] {
    if (session) session->bindings->draw();
    else if (looseBindings) looseBindings->draw();
  });
  render::TuningPanel tuning;
  auto setUpTuning = [&] {
    tuning = render::TuningPanel{};
    if (!session) return;
    tuning.title = session->scene->name();
    tuning.overridesPath = script::tuneOverridesPath(session->scene->host().mod().name);
  };
  setUpTuning();
  renderer.setTuningPanel(&tuning);
  // --record: what the scripts read of the input, step by step, from the
  // start of the scenario played (a restart, or another scenario from the
  // menu, starts the recording over: a replay is one session from its start).
  std::optional<ReplayRecorder> recorder;
  auto startRecording = [&](const SceneOptions& options) {
    if (o.recordPath.empty() || !session) return;
    SceneOptions recordedOptions = options;
    recordedOptions.tuneOverrides = true;  // as createPlayScene
    if (!recorder) recorder.emplace();
    recorder->start(*session->scene, recordedOptions);
  };
  startRecording(current);
  // Replaces the session with a fresh one from `options`; false (and the
  // message on the HUD or the menu) if the scenario cannot start.
  auto startFresh = [&](const SceneOptions& options) -> Status {
    auto fresh = createPlayScene(options);
    if (!fresh) return makeError(fresh.error());
    session.reset();  // the old scene's systems go before the new ones start
    session = startSession(std::move(*fresh), renderer, pauseMenu);
    gameHud.newSession();
    current = options;
    pauseMenu.setVehicleChoice(offersVehicle(current.scenarioRef));
    setUpTuning();
    startRecording(options);
    return Ok{};
  };

  RunTimings frame;
  render::Controls controls;
  render::FrameSnapshot snap;
  Stopwatch clock;
  double last = clock.seconds(), fpsTime = 0;
  int fpsFrames = 0, restarts = 0;
  double fps = 0;
  int shots = 0;
  double lastRender_s = 0;
  std::vector<double> frameMs, simulationMs, renderMs;  // per frame: all, the fixed steps, drawFrame
  std::size_t nextEvent = 0;
  float pointer[2] = {0, 0};
  long long frameNo = 0;
  bool menuPausedGame = false, pausedBeforeMenu = false;
  for (; !controls.quitRequested && (!scripted || frameNo < o.frames); ++frameNo) {
    Stopwatch frameClock;
    // Scripted input goes into SDL's own queue, then takes the player's path.
    for (; nextEvent < events.size() && events[nextEvent].frame <= frameNo; ++nextEvent) {
      SDL_Event e = toSdlEvent(events[nextEvent], renderer.windowId(), pointer);
      if (SDL_PushEvent(&e) < 0) log::warn(std::string("events: SDL_PushEvent failed: ") + SDL_GetError());
    }
    renderer.processEvents(controls);
    for (int a : menuInput.takeFramePresses())
      if (mainMenu.isOpen() && !openBindingsMenu()) mainMenu.onAction(menuInput.action(a).name);
    FrameRequests requests;
    if (session) applyFrameInput(session->scene->input(), *session->bindings, controls, renderer, &pauseMenu, &requests);
    else if (looseBindings) applyFrameInput(*looseInput, *looseBindings, controls, renderer);
    if (requests.toggleConsole) gameHud.console().toggle();
    if (requests.toggleHud) gameHud.toggleVisible();
    if (requests.changeVehicle) {
      const auto set = current.sets.find(kVehicleParam);
      mainMenu.openVehicles(current.scenarioRef, set != current.sets.end() ? set->second : std::string());
    }
    if (requests.settings) mainMenu.openSettings();
    if ((requests.backToDesigner || backToDesigner) && designer && session) {
      session.reset();  // the drive ends; the document was never touched
      pauseMenu.setInput(nullptr);
      pauseMenu.setDesignerReturn(false);
      pauseMenu.close();
      setUpTuning();
      controls.paused = false;
      renderer.camera() = cameraBeforeDrive;
      designer->resume();
    }
    backToDesigner = false;
    if (requests.mainMenu) {  // the scene goes; the menu's root comes back
      designer.reset();
      pauseMenu.setDesignerReturn(false);
      session.reset();
      pauseMenu.setInput(nullptr);
      setUpTuning();
      controls.paused = false;
      menuPausedGame = false;
      mainMenu.openRoot();
    }
    MainMenu::Requests menuRequests = mainMenu.takeRequests();
    if (menuRequests.quit) controls.quitRequested = true;
    if (menuRequests.openDesigner) {
      designer = std::make_unique<DesignerMode>(catalog, o.scene.modDirs, renderer);
      designer->showNewMap();
    }
    if (designer && !session) {
      DesignerMode::Requests d = designer->takeRequests();
      if (d.quit) controls.quitRequested = true;
      if (d.mainMenu) {
        designer.reset();
        mainMenu.openRoot();
      } else if (d.drive) {
        auto driving = designer->driveOptions(o.scene);
        cameraBeforeDrive = renderer.camera();
        if (!driving) {
          log::error(driving.error());
        } else if (Status st = startFresh(*driving); !st) {
          log::error("drive: " + st.error());
        } else {
          pauseMenu.setDesignerReturn(true);
          controls.paused = false;
        }
      }
    }
    if (menuRequests.backToGame && session) pauseMenu.open();
    if (menuRequests.openBindings) {
      if (session) {
        session->bindings->toggle();
      } else {
        if (!looseBindings) {
          looseInput = std::make_unique<input::InputSystem>(script::loadBindings(catalog.mods()).set);
          looseBindings = std::make_unique<BindingsMenu>(*looseInput, input::bindingsConfigPath());
        }
        looseBindings->toggle();
      }
    }
    if (menuRequests.settingsChanged) {
      // Scripted play keeps its --width/--height until the resolution
      // itself is changed (offscreen has no desktop to fill).
      if (!scripted) renderer.setWindowMode(settings.width, settings.height, settings.fullscreen);
      else if (std::pair(settings.width, settings.height) != appliedResolution)
        renderer.setWindowMode(settings.width, settings.height, false);
      appliedResolution = {settings.width, settings.height};
      // The volumes apply at once, and to every scene started from now on.
      o.scene.volumes = audio::AudioVolumes{float(settings.volume_master), float(settings.volume_effects),
                                            float(settings.volume_engine)};
      current.volumes = o.scene.volumes;
      if (session)
        if (audio::AudioSystem* a = session->scene->audioIfAny()) a->setVolumes(o.scene.volumes);
      if (o.quality.empty()) quality = settings.quality;  // --quality wins for this session
      applyQuality();
    }
    if (menuRequests.startScenario) {
      SceneOptions next = o.scene;
      next.scenarioRef = *menuRequests.startScenario;
      if (menuRequests.vehicle) next.sets[kVehicleParam] = *menuRequests.vehicle;
      if (Status st = startFresh(next); !st) {
        log::error("start: " + st.error());
        if (session) {
          session->scene->host().addMessage("cannot start: " + st.error(), 5);
        } else {
          mainMenu.openRoot();
          mainMenu.setStatus("cannot start " + next.scenarioRef + ": " + st.error());
        }
      }
      menuPausedGame = false;
      controls.paused = false;
      controls.stepOnce = false;
    }
    if (requests.restart && session) {
      // A fresh scene from the same options: the start state again. If the
      // scenario cannot start now (a broken edit), the current one goes on.
      if (Status st = startFresh(current); st) {
        ++restarts;
        controls.paused = false;
        controls.stepOnce = false;
      } else {
        log::error("restart: " + st.error());
        session->scene->host().addMessage("restart failed: " + st.error(), 5);
      }
    }
    // The game waits while a menu page is over it.
    if (session && mainMenu.isOpen() && !menuPausedGame) {
      menuPausedGame = true;
      pausedBeforeMenu = controls.paused;
      controls.paused = true;
    } else if (menuPausedGame && !mainMenu.isOpen()) {
      menuPausedGame = false;
      controls.paused = pausedBeforeMenu;
    }
    if (session) pauseMenu.syncPause(controls);  // back from a page to the pause menu: still no step
    double now = clock.seconds();
    double elapsed = std::min(now - last, 0.25);  // avoid the spiral of death after a stall
    last = now;
    if (session) {
      Scene& scene = *session->scene;
      for (const script::ReloadEvent& e : session->hotReload->poll(now, session->time_s, session->step))
        if (e.ok) {
          scene.host().addMessage(e.message, 3);  // failures are already on the HUD as errors
          gameHud.reloaded();                     // ... and leave it once the fix is in
        }
      // Scripted frames each take one fixed step (the same steps on any
      // machine); a window takes the steps due in the wall time that passed.
      if (scripted) elapsed = scene.dt_s();
      if (!controls.paused) session->accumulator += elapsed * (scripted ? 1.0 : controls.timeScale);
      if (controls.stepOnce) {
        session->accumulator += scene.dt_s();
        controls.stepOnce = false;
      }
      frame = RunTimings{};
      Stopwatch simulationClock;
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
      simulationMs.push_back(simulationClock.seconds() * 1000);
      const double alpha = std::clamp(session->accumulator / scene.dt_s(), 0.0, 1.0);
      session->director.update(scene, alpha, float(elapsed), renderer.camera());
      scene.setListener(listenerAtCamera(renderer.camera()));  // heard where it is seen (next step's audio)
      if (!session->director.hasTarget() && renderer.camera().mode == render::CameraMode::Follow) {
        renderer.camera().target = dynamicCentroid(scene);
      }
      scene.setCollisionView(controls.collisionView);  // F3
      scene.snapshot(snap, alpha);
      session->director.decorate(scene, alpha, renderer.camera(), snap);
      thinParticles(snap, qualityPreset(quality).particleBudget);
      snap.simTime_s = session->time_s;
    } else if (designerShown()) {
      designer->update(float(scripted ? o.scene.dt_s : elapsed), snap);  // scripted: the same on any machine
    } else {
      snap = render::FrameSnapshot{};  // the menu over the sky
    }
    std::string shot;
    if (controls.screenshotRequested) {
      shot = "tumble-screenshot-" + std::to_string(++shots) + ".png";
      controls.screenshotRequested = false;
    }
    if (scripted && o.screenshotGiven && frameNo + 1 == o.frames) shot = o.screenshotPath;  // the last frame
    Stopwatch rs;
    frame.render_s = lastRender_s;
    if (session && controls.tuningPanelVisible) fillTuningPanel(session->scene->host().tunables(), tuning);
    render::HudStats hud;
    if (session) {
      gameHud.update(*session->scene, session->time_s);
      hud = hudStats(*session->scene, fps, frame, session->time_s);
      hud.messages.clear();  // the game HUD shows them, coloured by kind
    }
    Status st = renderer.drawFrame(snap, hud, controls, shot.empty() ? nullptr : shot.c_str());
    if (session) applyTuningPanel(tuning, session->scene->host().tunables(), session->scene->host().mod().name);
    lastRender_s = rs.seconds();
    renderMs.push_back(lastRender_s * 1000);
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
  if (recorder && session) {
    Scene& scene = *session->scene;
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
    nlohmann::json menuItems = nlohmann::json::array();
    for (const MainMenu::ItemRect& it : mainMenu.lastLayout())
      menuItems.push_back({{"label", it.label}, {"x_px", it.x_px}, {"y_px", it.y_px}, {"w_px", it.w_px}, {"h_px", it.h_px}});
    nlohmann::json errors = nlohmann::json::array();
    if (session)
      for (const auto& e : session->scene->host().errors())
        errors.push_back({{"mod", e.mod}, {"file", e.file}, {"line", e.line}, {"message", e.message}});
    const auto& selectedItem = pauseMenu.items()[std::size_t(pauseMenu.selected())];
    nlohmann::json bindingButtons = nlohmann::json::array();
    if (BindingsMenu* bm = session ? session->bindings.get() : looseBindings.get())
      for (const BindingsMenu::ButtonRect& b : bm->lastLayout())
        bindingButtons.push_back({{"action", b.action}, {"slot", b.slot}, {"label", b.label}, {"x_px", b.x_px},
                                  {"y_px", b.y_px}, {"w_px", b.w_px}, {"h_px", b.h_px}});
    const QualityPreset preset = qualityPreset(quality);
    nlohmann::json vehicleDefinition = nullptr;
    if (session && offersVehicle(current.scenarioRef)) {
      auto set = current.sets.find(kVehicleParam);
      vehicleDefinition = set != current.sets.end() ? set->second : catalog.scenario(current.scenarioRef)->defaultVehicle;
    }
    nlohmann::json report = {
        {"scenario", session ? nlohmann::json(session->scene->name()) : nlohmann::json(nullptr)},
        {"title", session ? nlohmann::json(session->scene->host().title()) : nlohmann::json(nullptr)},
        {"frames", frameNo},
        {"steps", session ? session->step : 0},
        {"simulated_seconds", session ? session->time_s : 0.0},
        {"restarts", restarts},
        {"quit", controls.quitRequested},
        {"paused", controls.paused},
        {"menu", {{"page", MainMenu::pageName(mainMenu.page())},
                  {"open", mainMenu.isOpen()},
                  {"selected", mainMenu.isOpen() ? nlohmann::json(mainMenu.selectedLabel()) : nlohmann::json(nullptr)},
                  {"items", menuItems},
                  {"thumbnail", mainMenu.thumbnailStatus()}}},
        {"pause_menu", {{"open", pauseMenu.isOpen()}, {"selected", selectedItem.label}, {"items", items}}},
        {"bindings_menu_open", openBindingsMenu() != nullptr},
        {"debug_panel", controls.debugPanelVisible},
        {"camera", render::cameraModeName(renderer.camera().mode)},
        {"vehicle_definition", vehicleDefinition},
        {"vehicle", session ? session->vehicle.report(*session->scene) : nlohmann::json(nullptr)},
        {"window", {{"width_px", renderer.windowSize().first}, {"height_px", renderer.windowSize().second}}},
        {"quality", {{"preset", qualityName(quality)},
                     {"resolution_scale", preset.resolutionScale},
                     {"far_plane_m", preset.farPlane_m},
                     {"fog_start_m", preset.fogStart_m},
                     {"terrain_lod_pixels", preset.terrainLodPixels},
                     {"particle_budget", preset.particleBudget},
                     {"msaa_samples", preset.msaaSamples},
                     {"shadows", preset.shadows},
                     {"shadow_map_size", preset.shadowMapSize},
                     {"shadow_cascades", preset.shadowCascades},
                     {"lens_flare", preset.lensFlare}}},
        {"settings", {{"file", settingsFile},
                      {"problem", settingsProblem.empty() ? nlohmann::json(nullptr) : nlohmann::json(settingsProblem)},
                      {"width", settings.width},
                      {"height", settings.height},
                      {"fullscreen", settings.fullscreen},
                      {"quality", qualityName(settings.quality)},
                      {"volume_master", settings.volume_master},
                      {"volume_effects", settings.volume_effects},
                      {"volume_engine", settings.volume_engine}}},
        {"frame_ms", {{"p50", percentile(frameMs, 0.5)}, {"p95", percentile(frameMs, 0.95)},
                      {"max", frameMs.empty() ? 0.0 : *std::max_element(frameMs.begin(), frameMs.end())},
                      {"simulation_p50", percentile(simulationMs, 0.5)},
                      {"render_p50", percentile(renderMs, 0.5)}}},
        {"hud_messages", session ? nlohmann::json(hudStats(*session->scene, fps, frame, session->time_s).messages)
                                 : nlohmann::json::array()},
        {"hud", gameHud.report()},
        {"bindings_menu_buttons", bindingButtons},
        {"script_errors", errors},
        {"state_hash", session ? nlohmann::json(stateHashText(*session->scene)) : nlohmann::json(nullptr)},
        {"designer", designer ? designer->report() : nlohmann::json(nullptr)},
    };
    if (designer) report["designer"]["active"] = designerShown();
    if (auto st = writeReport(o.reportPath, report); !st) {
      log::error("report: " + st.error());
      if (session) session->scene->finish(session->time_s, session->step);
      return 1;
    }
  }
  if (session) session->scene->finish(session->time_s, session->step);
  return 0;
}

}  // namespace tumble::app
