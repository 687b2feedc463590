#pragma once
// Shared by the fuzz targets that need a running scene (save files, the
// scenario fuzzer): an app::Scene built headless, as `tumble run` builds
// it (no window, no GL context, silent audio), for a scenario written into
// the scratch mod "fuzzmod" (fuzz_util.h).
#include <cstdio>
#include <memory>
#include <string>

#include "app/fixed_step.h"
#include "app/scene.h"
#include "core/log.h"
#include "fuzz_util.h"

namespace tumble::fuzz {

/// Writes fuzzmod/scenarios/NAME.lua with `source` and builds a scene for it
/// (saves go to the scratch folder's saves/). Null when the scene could not
/// be made (the scenario did not load: its error is the loader's job).
inline std::unique_ptr<app::Scene> sceneFor(const std::string& name, const std::string& source,
                                            const script::VmLimits& limits = {}) {
  // Scripts' print() and the warnings of refused calls would be most of the
  // run's time and output; errors (and sanitizer reports) still show.
  log::setLevel(log::Level::Error);
  fuzzMod();
  writeScratch("fuzzmod/scenarios/" + name + ".lua", reinterpret_cast<const std::uint8_t*>(source.data()),
               source.size());
  app::SceneOptions options;
  options.scenarioRef = "fuzzmod:" + name;
  options.modDirs = {scratchDir().string()};
  options.saveDir = (scratchDir() / "saves").string();
  options.limits = limits;
  auto scene = app::Scene::create(options);
  if (!scene) {
    std::fprintf(stderr, "fuzz: the scene did not load: %s\n", scene.error().c_str());
    return nullptr;
  }
  return std::move(scene.value());
}

/// start, `steps` fixed steps (app::stepScene, as `tumble run` takes them), finish.
inline void runSteps(app::Scene& scene, int steps) {
  scene.start();
  app::RunTimings timings;
  double t = 0;
  for (int i = 0; i < steps; ++i) {
    app::stepScene(scene, app::StepTime{t, i}, timings);
    t = double(i + 1) * scene.dt_s();
  }
  scene.finish(t, steps);
}

}  // namespace tumble::fuzz
