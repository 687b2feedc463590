#pragma once
// The player's settings: window size, fullscreen, the quality preset and the
// volumes, in <config folder>/settings.json beside the bindings overrides
// (input/overrides_file.h):
//
//   {"format": "tumble-settings", "version": 1, "width": 1280, "height": 720,
//    "fullscreen": false, "quality": "medium",
//    "volume_master": 1.0, "volume_effects": 0.8, "volume_engine": 0.8}
//
// Every field is optional (a missing one keeps its default). Saved
// atomically (write beside, rename). A file that cannot be read is reported
// with its path, field and what is valid, and the defaults are used; it is
// left alone until the player saves again.
//
// Quality presets (low, medium, high) set what the renderer spends per
// frame; `play --quality NAME` overrides the saved one for one session.
#include <string>
#include <vector>

#include "core/result.h"

namespace tumble::render {
struct RenderQuality;
}

namespace tumble::app {

enum class QualityLevel { Low, Medium, High };

/// What a preset sets. Rendering only: the simulation is the same at every
/// level (same steps, same state hash).
struct QualityPreset {
  QualityLevel level = QualityLevel::Medium;
  /// The 3D scene is drawn at this fraction of the window's pixels in each
  /// direction and scaled up; the HUD and menus stay sharp. 0.25..1.
  float resolutionScale = 1.0f;
  float farPlane_m = 1000.0f;    ///< nothing is drawn beyond this distance
  float fogStart_m = 250.0f;     ///< distance fog reaches 63 %; the far plane sits where it is nearly opaque
  /// Terrain LOD: a chunk takes the coarsest level whose blocks are at most
  /// this many pixels wide on screen (render::WindowConfig::terrainLodPixels).
  float terrainLodPixels = 16.0f;
  bool terrainDetail = true;     ///< the ground lit per pixel with bump detail (off on low: lit per vertex; render::WindowConfig::terrainDetail)
  bool terrainBlend = false;     ///< painted surfaces blend across block edges (high only; render::WindowConfig::terrainBlend)
  int particleBudget = 20000;    ///< particles drawn per frame at most (evenly thinned beyond)
  int msaaSamples = 4;           ///< 1 = off
  bool shadows = true;           ///< cascaded sun shadows (off on low)
  int shadowMapSize = 1024;      ///< texels per cascade's depth map edge
  int shadowCascades = 3;        ///< slices of the view with their own shadow map
  bool lensFlare = true;         ///< the sun's flare (an occlusion query and 7 sprites)
};

const char* qualityName(QualityLevel level);
/// "low", "medium" or "high"; the error lists them.
Result<QualityLevel> parseQuality(const std::string& name);
QualityPreset qualityPreset(QualityLevel level);
/// The renderer's share of a preset, as `play` sets it (the storm's rain
/// is a quarter of the particle budget).
render::RenderQuality renderQuality(const QualityPreset& preset);

struct PlayerSettings {
  int width = 1280, height = 720;  ///< window size, px (64..16384)
  bool fullscreen = false;
  QualityLevel quality = QualityLevel::Medium;
  double volume_master = 1.0;   ///< 0..1
  double volume_effects = 0.8;  ///< 0..1, impacts, tyres, particles' sounds
  double volume_engine = 0.8;   ///< 0..1, vehicle engines
};

/// The window sizes the settings page offers (px).
const std::vector<std::pair<int, int>>& offeredResolutions();

/// <config folder>/settings.json (the folder of input::bindingsConfigPath()).
/// Empty when no config folder is known.
std::string settingsPath();

/// Reads the settings. A missing file gives the defaults and no error; a
/// broken one gives an error naming the file and field (the caller shows it
/// and goes on with PlayerSettings{}).
Result<PlayerSettings> loadPlayerSettings(const std::string& path);
Status savePlayerSettings(const std::string& path, const PlayerSettings& settings);

}  // namespace tumble::app
