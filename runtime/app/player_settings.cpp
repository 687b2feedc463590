#include "app/player_settings.h"

#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/file_util.h"
#include "core/json_depth.h"
#include "input/overrides_file.h"
#include "render/renderer.h"

namespace tumble::app {

namespace fs = std::filesystem;

const char* qualityName(QualityLevel level) {
  switch (level) {
    case QualityLevel::Low: return "low";
    case QualityLevel::Medium: return "medium";
    case QualityLevel::High: return "high";
  }
  return "medium";
}

Result<QualityLevel> parseQuality(const std::string& name) {
  for (QualityLevel l : {QualityLevel::Low, QualityLevel::Medium, QualityLevel::High})
    if (name == qualityName(l)) return l;
  return makeError("unknown quality \"" + name + "\"; expected low, medium or high");
}

// Measured in base:drive at 1280x720 on Mesa llvmpipe (README.md, "Quality
// presets"): the terrain's fill and triangle count dominate there, so low
// draws the scene at a lower resolution, culls the terrain sooner (fog and
// far plane) and uses coarser terrain levels.
QualityPreset qualityPreset(QualityLevel level) {
  QualityPreset p;
  p.level = level;
  switch (level) {
    case QualityLevel::Low:
      p.resolutionScale = 0.5f;
      p.farPlane_m = 300.0f;
      p.fogStart_m = 90.0f;
      p.terrainLodPixels = 40.0f;
      p.terrainDetail = false;
      p.particleBudget = 2000;
      p.msaaSamples = 1;
      p.shadows = false;
      p.lensFlare = false;
      break;
    case QualityLevel::Medium:
      p.resolutionScale = 0.75f;
      p.farPlane_m = 600.0f;
      p.fogStart_m = 170.0f;
      p.terrainLodPixels = 24.0f;
      p.particleBudget = 8000;
      p.msaaSamples = 1;
      p.shadows = true;
      p.shadowMapSize = 512;
      p.shadowCascades = 2;
      break;
    case QualityLevel::High:
      p.resolutionScale = 1.0f;
      p.farPlane_m = 1000.0f;
      p.fogStart_m = 250.0f;
      p.terrainLodPixels = 16.0f;
      p.particleBudget = 20000;
      p.msaaSamples = 4;
      p.shadows = true;
      p.terrainBlend = true;
      break;
  }
  return p;
}

render::RenderQuality renderQuality(const QualityPreset& p) {
  render::RenderQuality q;
  q.resolutionScale = p.resolutionScale;
  q.farPlane_m = p.farPlane_m;
  q.fogDistance_m = p.fogStart_m;
  q.terrainLodPixels = p.terrainLodPixels;
  q.terrainDetail = p.terrainDetail;
  q.terrainBlend = p.terrainBlend;
  q.msaaSamples = p.msaaSamples;
  q.shadows = p.shadows;
  q.shadowMapSize = p.shadowMapSize;
  q.shadowCascades = p.shadowCascades;
  q.lensFlare = p.lensFlare;
  q.rainDrops = p.particleBudget / 4;
  return q;
}

const std::vector<std::pair<int, int>>& offeredResolutions() {
  static const std::vector<std::pair<int, int>> sizes = {
      {960, 540}, {1280, 720}, {1366, 768}, {1600, 900}, {1920, 1080}, {2560, 1440}};
  return sizes;
}

std::string settingsPath() {
  const std::string bindings = input::bindingsConfigPath();
  if (bindings.empty()) return {};
  return (fs::path(bindings).parent_path() / "settings.json").string();
}

namespace {

constexpr const char* kFormat = "tumble-settings";

// Reads an optional field of the given JSON type into out; a wrong type is
// an error naming the field and what is expected.
template <class T>
Status readField(const nlohmann::json& j, const char* field, const std::string& path, const char* expected, T& out,
                 bool (nlohmann::json::*is)() const noexcept) {
  auto it = j.find(field);
  if (it == j.end()) return Ok{};
  if (!((*it).*is)()) return makeError(path + ": field '" + field + "': expected " + expected + ", got " + it->dump());
  out = it->get<T>();
  return Ok{};
}

Status checkRange(const std::string& path, const char* field, double v, double lo, double hi) {
  if (std::isfinite(v) && v >= lo && v <= hi) return Ok{};
  return makeError(path + ": field '" + field + "': expected a number in " + nlohmann::json(lo).dump() + ".." +
                   nlohmann::json(hi).dump() + ", got " + nlohmann::json(v).dump());
}

}  // namespace

Result<PlayerSettings> loadPlayerSettings(const std::string& path) {
  PlayerSettings s;
  std::error_code ec;
  if (path.empty() || !fs::exists(path, ec)) return s;
  auto text = readTextFile(path);
  if (!text) return makeError(text.error());
  // The settings nest one level; deeper is refused while parsing (core/json_depth.h).
  auto parsed = parseJsonWithDepth(*text, 8);
  if (!parsed) return makeError(path + ": " + parsed.error() + "; expected {\"format\": \"tumble-settings\", ...}");
  nlohmann::json j = std::move(*parsed);
  if (!j.is_object()) return makeError(path + ": expected a JSON object {\"format\": \"tumble-settings\", ...}");
  if (auto f = j.find("format"); f != j.end() && *f != kFormat)
    return makeError(path + ": field 'format': expected \"tumble-settings\", got " + f->dump());
  std::string quality = qualityName(s.quality);
  Status st = readField(j, "width", path, "a whole number of pixels", s.width, &nlohmann::json::is_number_integer);
  if (st) st = readField(j, "height", path, "a whole number of pixels", s.height, &nlohmann::json::is_number_integer);
  if (st) st = readField(j, "fullscreen", path, "true or false", s.fullscreen, &nlohmann::json::is_boolean);
  if (st) st = readField(j, "quality", path, "\"low\", \"medium\" or \"high\"", quality, &nlohmann::json::is_string);
  if (st) st = readField(j, "volume_master", path, "a number in 0..1", s.volume_master, &nlohmann::json::is_number);
  if (st) st = readField(j, "volume_effects", path, "a number in 0..1", s.volume_effects, &nlohmann::json::is_number);
  if (st) st = readField(j, "volume_engine", path, "a number in 0..1", s.volume_engine, &nlohmann::json::is_number);
  if (!st) return makeError(st.error());
  for (auto [field, v, lo, hi] : {std::tuple{"width", double(s.width), 64.0, 16384.0},
                                  std::tuple{"height", double(s.height), 64.0, 16384.0},
                                  std::tuple{"volume_master", s.volume_master, 0.0, 1.0},
                                  std::tuple{"volume_effects", s.volume_effects, 0.0, 1.0},
                                  std::tuple{"volume_engine", s.volume_engine, 0.0, 1.0}})
    if (Status r = checkRange(path, field, v, lo, hi); !r) return makeError(r.error());
  auto level = parseQuality(quality);
  if (!level) return makeError(path + ": field 'quality': " + level.error());
  s.quality = *level;
  return s;
}

Status savePlayerSettings(const std::string& path, const PlayerSettings& s) {
  if (path.empty()) return makeError("no config folder: set TUMBLE_CONFIG_DIR, XDG_CONFIG_HOME or HOME");
  nlohmann::json j = {{"format", kFormat},
                      {"version", 1},
                      {"width", s.width},
                      {"height", s.height},
                      {"fullscreen", s.fullscreen},
                      {"quality", qualityName(s.quality)},
                      {"volume_master", s.volume_master},
                      {"volume_effects", s.volume_effects},
                      {"volume_engine", s.volume_engine}};
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  if (ec) return makeError(path + ": cannot create the folder: " + ec.message());
  if (Status st = writeFileAtomic(path, j.dump(2) + "\n"); !st) return makeError(st.error());
  return Ok{};
}

}  // namespace tumble::app
