#include "script/presentation.h"

#include <filesystem>

#include "script/mods.h"

namespace tumble::script {

namespace fs = std::filesystem;

Result<std::string> resolveModFile(const std::string& ref, const ModInfo& caller,
                                   const std::map<std::string, std::string>& modDirs) {
  std::string modName = caller.name, relative = ref;
  std::string modDir = caller.dir;
  if (const auto colon = ref.find(':'); colon != std::string::npos) {
    modName = ref.substr(0, colon);
    relative = ref.substr(colon + 1);
    if (modName != caller.name) {
      auto it = modDirs.find(modName);
      if (it == modDirs.end()) {
        return makeError("\"" + ref + "\": no mod named \"" + modName + "\" is installed (write \"MOD:path\", e.g. "
                         "\"base:assets/models/rock.obj\")");
      }
      modDir = it->second;
    }
  }
  if (relative.empty()) return makeError("\"" + ref + "\": the path inside the mod is empty");
  if (fs::path(relative).is_absolute()) {
    return makeError("\"" + ref + "\": absolute paths are not allowed; give a path inside a mod");
  }
  const fs::path root = fs::weakly_canonical(fs::path(modDir));
  const fs::path path = fs::weakly_canonical(root / relative);
  const fs::path rel = path.lexically_relative(root);
  if (rel.empty() || *rel.begin() == "..") {
    return makeError("\"" + ref + "\" leaves the folder of mod \"" + modName + "\"; paths stay inside it");
  }
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    return makeError("\"" + ref + "\": no such file in mod \"" + modName + "\" (looked for " + path.string() + ")");
  }
  return path.string();
}

}  // namespace tumble::script
