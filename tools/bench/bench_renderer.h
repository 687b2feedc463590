#pragma once
// The renderer the render benchmarks draw with: 1280 x 720 on SDL's
// offscreen driver (Mesa), no HUD, with a quality preset's settings.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>

#include "app/player_settings.h"
#include "render/renderer.h"

namespace tumble::bench {

/// Null (and the benchmark skipped with the reason) if no GL context can be made.
inline std::unique_ptr<render::Renderer> offscreenRenderer(benchmark::State& state, app::QualityLevel level) {
  ::setenv("SDL_VIDEODRIVER", "offscreen", 1);
  render::WindowConfig config;
  config.width = 1280;
  config.height = 720;
  config.hud = false;
  config.forceOffscreen = true;
  auto renderer = render::Renderer::create(config);
  if (!renderer) {
    state.SkipWithError(renderer.error().c_str());
    return nullptr;
  }
  (*renderer)->setQuality(app::renderQuality(app::qualityPreset(level)));
  return std::move(*renderer);
}

}  // namespace tumble::bench
