#include "input/overrides_file.h"

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <system_error>

#include "core/file_util.h"

namespace tumble::input {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "tumble-bindings";
constexpr int kVersion = 1;

// Line of a byte offset, for parse errors (nlohmann reports the offset).
int lineOf(const std::string& text, std::size_t offset) {
  int line = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) line += text[i] == '\n';
  return line;
}

}  // namespace

std::string bindingsConfigPath() {
  if (const char* dir = std::getenv("TUMBLE_CONFIG_DIR"); dir && *dir) return (fs::path(dir) / "bindings.json").string();
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg)
    return (fs::path(xdg) / "tumble" / "bindings.json").string();
  if (const char* home = std::getenv("HOME"); home && *home)
    return (fs::path(home) / ".config" / "tumble" / "bindings.json").string();
  return {};
}

Result<Overrides> loadOverrides(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return Overrides{};
  auto text = readTextFile(path);
  if (!text) return makeError(text.error());
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(*text);
  } catch (const nlohmann::json::parse_error& e) {
    return makeError(path + ":" + std::to_string(lineOf(*text, e.byte ? e.byte - 1 : 0)) +
                     ": not valid JSON (" + e.what() + ")");
  } catch (const nlohmann::json::exception& e) {  // 1e400: number overflow (out_of_range)
    return makeError(path + ": not valid JSON: a number is out of range (" + e.what() +
                     "); numbers must fit a double");
  }
  const std::string expected = "; expected {\"format\": \"tumble-bindings\", \"version\": 1, \"overrides\": "
                               "{\"ACTION\": [\"key:W\", ...]}}";
  if (!j.is_object()) return makeError(path + ": the top level is not an object" + expected);
  if (!j.contains("format") || j["format"] != kFormat)
    return makeError(path + ": field \"format\" must be \"tumble-bindings\"" + expected);
  if (!j.contains("version") || !j["version"].is_number_integer())
    return makeError(path + ": field \"version\" must be an integer" + expected);
  if (j["version"].get<int>() > kVersion)
    return makeError(path + ": version " + std::to_string(j["version"].get<int>()) +
                     " is newer than this Tumble reads (" + std::to_string(kVersion) + ")");
  Overrides out;
  if (!j.contains("overrides")) return out;
  if (!j["overrides"].is_object()) return makeError(path + ": field \"overrides\" must be an object" + expected);
  for (const auto& [action, list] : j["overrides"].items()) {
    if (!list.is_array())
      return makeError(path + ": overrides." + action + " must be a list of bindings like [\"key:W\"]");
    std::vector<std::string> texts;
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (!list[i].is_string())
        return makeError(path + ": overrides." + action + "[" + std::to_string(i + 1) +
                         "] must be a string like \"key:W\" or \"pad:a\"");
      texts.push_back(list[i].get<std::string>());
    }
    out[action] = std::move(texts);
  }
  return out;
}

Status saveOverrides(const std::string& path, const Overrides& overrides) {
  if (path.empty()) return makeError("no config folder: set TUMBLE_CONFIG_DIR, XDG_CONFIG_HOME or HOME");
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["overrides"] = nlohmann::json::object();
  for (const auto& [action, texts] : overrides) j["overrides"][action] = texts;
  std::error_code ec;
  fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (ec) return makeError(path + ": cannot create the folder " + parent.string() + ": " + ec.message());
  return writeFileAtomic(path, j.dump(2) + "\n");
}

}  // namespace tumble::input
