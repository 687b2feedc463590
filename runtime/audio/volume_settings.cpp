#include "audio/volume_settings.h"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/file_util.h"

namespace tumble::audio {

Result<AudioVolumes> readVolumes(const std::string& path) {
  AudioVolumes v;
  std::error_code ec;
  if (path.empty() || !std::filesystem::exists(path, ec)) return v;
  auto text = readTextFile(path, std::size_t(1) << 20);
  if (!text) return makeError(text.error());
  nlohmann::json j = nlohmann::json::parse(*text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return makeError(path + ": not a JSON object; volumes left at 1");
  for (auto [key, field] : {std::pair{"volume_master", &v.master}, std::pair{"volume_effects", &v.effects},
                            std::pair{"volume_engine", &v.engine}}) {
    if (!j.contains(key)) continue;
    const auto& x = j[key];
    if (!x.is_number() || !std::isfinite(x.get<double>()) || x.get<double>() < 0 || x.get<double>() > 1)
      return makeError(path + ": '" + key + "' must be a number from 0 to 1, got " + x.dump());
    *field = x.get<float>();
  }
  return v;
}

}  // namespace tumble::audio
