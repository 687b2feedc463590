#include "terrain/terrain_desc.h"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/file_util.h"

namespace tumble::terrain {

namespace {

constexpr const char* kValidFields =
    "spacing_m, height_scale_m, base_height_m, origin_x_m, origin_z_m";

// Limits that keep every terrain coordinate a float can hold usefully: the
// world stores float, whose step at 1e6 m is 6 cm (1e39 m overflows float to
// inf). Origins and base height within +-1e6 m; 1000 m between samples;
// 15 m per unit gives 65535 * 15 = 983 km, still below 1e6 m.
constexpr double kMaxCoordinate_m = 1e6;
constexpr double kMaxSpacing_m = 1000.0;
constexpr double kMaxHeightScale_m = 15.0;

}  // namespace

std::string sidecarPath(const std::string& pngPath) { return pngPath + ".json"; }

Result<TerrainDesc> parseTerrainDesc(const std::string& jsonText, const std::string& fileName) {
  nlohmann::json j = nlohmann::json::parse(jsonText, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return makeError(fileName + ": not valid JSON (expected an object with " + kValidFields + ")");
  if (!j.is_object()) return makeError(fileName + ": expected a JSON object with " + kValidFields);
  TerrainDesc d;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    double* field = nullptr;
    if (key == "spacing_m") field = &d.spacing_m;
    else if (key == "height_scale_m") field = &d.heightScale_m;
    else if (key == "base_height_m") field = &d.baseHeight_m;
    else if (key == "origin_x_m") field = &d.originX_m;
    else if (key == "origin_z_m") field = &d.originZ_m;
    else return makeError(fileName + ": unknown field \"" + key + "\" (valid: " + kValidFields + ")");
    if (!it.value().is_number() || !std::isfinite(it.value().get<double>()))
      return makeError(fileName + ": field \"" + key + "\" must be a finite number");
    *field = it.value().get<double>();
  }
  if (!(d.spacing_m > 0) || d.spacing_m > kMaxSpacing_m)
    return makeError(fileName + ": \"spacing_m\" must be > 0 and at most 1000 metres, got " + std::to_string(d.spacing_m));
  if (!(d.heightScale_m > 0) || d.heightScale_m > kMaxHeightScale_m)
    return makeError(fileName + ": \"height_scale_m\" must be > 0 and at most 15 metres per unit (65535 units stay "
                     "below 1e6 m), got " + std::to_string(d.heightScale_m));
  for (auto [name, value] : {std::pair<const char*, double>{"base_height_m", d.baseHeight_m},
                             {"origin_x_m", d.originX_m}, {"origin_z_m", d.originZ_m}})
    if (std::abs(value) > kMaxCoordinate_m)
      return makeError(fileName + ": \"" + name + "\" must be within -1e6 and 1e6 metres (the world stores float), got " +
                       std::to_string(value));
  return d;
}

Result<TerrainDesc> loadSidecar(const std::string& pngPath, const TerrainDesc& defaults) {
  const std::string path = sidecarPath(pngPath);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return defaults;
  auto text = readTextFile(path, 1u << 20);  // a sidecar is five numbers
  if (!text) return makeError(text.error());
  return parseTerrainDesc(*text, path);
}

std::string terrainDescToJson(const TerrainDesc& d) {
  nlohmann::json j = {{"spacing_m", d.spacing_m},     {"height_scale_m", d.heightScale_m},
                      {"base_height_m", d.baseHeight_m}, {"origin_x_m", d.originX_m},
                      {"origin_z_m", d.originZ_m}};
  return j.dump(2) + "\n";
}

Status saveSidecar(const std::string& pngPath, const TerrainDesc& desc) {
  return writeFileAtomic(sidecarPath(pngPath), terrainDescToJson(desc));
}

}  // namespace tumble::terrain
