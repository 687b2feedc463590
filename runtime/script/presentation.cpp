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

void Presentation::setColor(physics::BodyId id, const Eigen::Vector3f& rgb) {
  if (m_colors.size() <= id.index) m_colors.resize(id.index + 1, Eigen::Vector3f(-1, -1, -1));
  m_colors[id.index] = rgb;
}

Eigen::Vector3f Presentation::colorOf(physics::BodyId id) const {
  if (id.index < m_colors.size() && m_colors[id.index].x() >= 0) return m_colors[id.index];
  return Eigen::Vector3f(0.75f, 0.75f, 0.78f);
}

void Presentation::setGroundTexture(physics::BodyId id, int layer) {
  if (m_groundTextures.size() <= id.index) m_groundTextures.resize(id.index + 1, -1);
  m_groundTextures[id.index] = layer;
}

int Presentation::groundTextureOf(physics::BodyId id) const {
  return id.index < m_groundTextures.size() ? m_groundTextures[id.index] : -1;
}

Eigen::Vector3f Presentation::deformableColor(int id) const {
  auto it = m_deformableColors.find(id);
  return it == m_deformableColors.end() ? Eigen::Vector3f(0.9f, 0.6f, 0.2f) : it->second;
}

void Presentation::addScriptLine(const ScriptLine& line) {
  if (m_scriptLines.size() < kMaxScriptLines) m_scriptLines.push_back(line);
}

}  // namespace tumble::script
