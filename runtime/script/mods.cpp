#include "script/mods.h"

#include <algorithm>
#include <filesystem>
#include <regex>

#include "script/lua_vm.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace fs = std::filesystem;

namespace tumble::script {

std::string ModProblem::text() const {
  return file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + message;
}

namespace {

bool isSemver(const std::string& v) {
  static const std::regex re(R"(^\d+\.\d+(\.\d+)?([-+][0-9A-Za-z.-]+)?$)");
  return std::regex_match(v, re);
}

Result<ModDependency> parseDependency(const std::string& text) {
  static const std::regex re(R"(^\s*([A-Za-z0-9_\-]+)\s*(?:(>=|<=|=|==|>|<)\s*([0-9][0-9A-Za-z.\-+]*))?\s*$)");
  std::smatch m;
  if (!std::regex_match(text, m, re))
    return makeError("dependency \"" + text + "\" is not of the form \"name\" or \"name >= 1.0\"");
  return ModDependency{m[1], m[2], m[3]};
}

// Runs mod.lua in an empty environment under a small budget and reads the
// returned table. Problems are appended; returns true if a table came back.
bool readManifest(const std::string& dir, ModInfo& info, std::vector<ModProblem>& problems) {
  std::string path = (fs::path(dir) / "mod.lua").string();
  auto problem = [&](int line, std::string msg) { problems.push_back({path, line, std::move(msg)}); };
  if (!fs::exists(path)) {
    problem(0, "missing: every mod folder needs a mod.lua manifest returning {name, version, title, api}");
    return false;
  }
  VmLimits limits;
  limits.memoryBytes = 8u << 20;
  limits.instructionsPerCall = 1'000'000;
  LuaVm vm(limits);
  lua_State* L = vm.state();
  if (luaL_loadfilex(L, path.c_str(), "t") != LUA_OK) {
    ScriptError e = LuaVm::parseError(fs::path(dir).filename().string(), lua_tostring(L, -1), "");
    problem(e.line, e.message);
    return false;
  }
  lua_newtable(L);  // empty _ENV: a manifest is data
  lua_setupvalue(L, -2, 1);
  ScriptError err;
  if (!vm.call(0, 1, fs::path(dir).filename().string(), "mod.lua", &err)) {
    problem(err.line, err.message);
    return false;
  }
  if (!lua_istable(L, -1)) {
    problem(0, "must return a table {name = ..., version = ..., title = ..., api = ...}");
    return false;
  }
  auto str = [&](const char* key, bool required) -> std::string {
    lua_getfield(L, -1, key);
    std::string v;
    if (lua_type(L, -1) == LUA_TSTRING) v = lua_tostring(L, -1);
    else if (!lua_isnil(L, -1) || required)
      problem(0, std::string("field '") + key + "' must be a string" + (required ? " (required)" : ""));
    lua_pop(L, 1);
    return v;
  };
  info.name = str("name", true);
  info.version = str("version", true);
  info.title = str("title", false);
  lua_getfield(L, -1, "api");
  if (lua_isinteger(L, -1)) info.api = int(lua_tointeger(L, -1));
  else problem(0, "field 'api' must be an integer (the Lua API version, now " + std::to_string(kApiVersion) + ")");
  lua_pop(L, 1);
  if (!info.version.empty() && !isSemver(info.version))
    problem(0, "field 'version' must be semver like \"1.2.0\", got \"" + info.version + "\"");
  if (info.api > kApiVersion)
    problem(0, "field 'api' is " + std::to_string(info.api) + " but this Tumble provides API " +
                   std::to_string(kApiVersion) + "; update Tumble");
  std::string folder = fs::path(dir).filename().string();
  if (!info.name.empty() && info.name != folder)
    problem(0, "field 'name' is \"" + info.name + "\" but the folder is \"" + folder + "\"; they must match");
  lua_getfield(L, -1, "depends");
  if (lua_istable(L, -1)) {
    lua_Integer n = luaL_len(L, -1);
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_rawgeti(L, -1, i);
      if (lua_type(L, -1) == LUA_TSTRING) {
        auto dep = parseDependency(lua_tostring(L, -1));
        if (dep) info.depends.push_back(*dep);
        else problem(0, "field 'depends': " + dep.error());
      } else {
        problem(0, "field 'depends' must be a list of strings like \"base >= 1.0\"");
      }
      lua_pop(L, 1);
    }
  } else if (!lua_isnil(L, -1)) {
    problem(0, "field 'depends' must be a list of strings like \"base >= 1.0\"");
  }
  lua_pop(L, 2);
  info.dir = fs::absolute(dir).lexically_normal().string();
  return true;
}

}  // namespace

Result<ModInfo> loadManifest(const std::string& dir) {
  ModInfo info;
  std::vector<ModProblem> problems;
  readManifest(dir, info, problems);
  if (!problems.empty()) {
    std::string msg;
    for (auto& p : problems) msg += (msg.empty() ? "" : "\n") + p.text();
    return makeError(msg);
  }
  return info;
}

std::vector<ModProblem> checkMod(const std::string& dir) {
  std::vector<ModProblem> problems;
  if (!fs::is_directory(dir)) {
    problems.push_back({dir, 0, "not a folder"});
    return problems;
  }
  ModInfo info;
  readManifest(dir, info, problems);
  // Every Lua file must compile (syntax), scenarios must return a table.
  std::vector<fs::path> files;
  for (auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".lua") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    if (file.filename() == "mod.lua" && file.parent_path() == fs::path(dir)) continue;
    LuaVm vm(VmLimits{8u << 20, 1'000'000});
    lua_State* L = vm.state();
    if (luaL_loadfilex(L, file.c_str(), "t") != LUA_OK) {
      ScriptError e = LuaVm::parseError(info.name, lua_tostring(L, -1), "");
      problems.push_back({file.string(), e.line, e.message});
    }
  }
  return problems;
}

ModRegistry ModRegistry::discover(const std::vector<std::string>& searchDirs) {
  ModRegistry reg;
  for (const std::string& root : searchDirs) {
    std::error_code ec;
    if (!fs::is_directory(root, ec)) continue;
    std::vector<fs::path> dirs;
    for (auto& entry : fs::directory_iterator(root, ec))
      if (entry.is_directory() && fs::exists(entry.path() / "mod.lua")) dirs.push_back(entry.path());
    std::sort(dirs.begin(), dirs.end());
    for (const fs::path& d : dirs) {
      ModInfo info;
      std::size_t before = reg.m_problems.size();
      bool ok = readManifest(d.string(), info, reg.m_problems);
      if (!ok || reg.m_problems.size() != before) continue;
      auto it = std::find_if(reg.m_mods.begin(), reg.m_mods.end(), [&](const ModInfo& m) { return m.name == info.name; });
      if (it != reg.m_mods.end()) *it = info;
      else reg.m_mods.push_back(info);
    }
  }
  return reg;
}

const ModInfo* ModRegistry::find(const std::string& name) const {
  for (const ModInfo& m : m_mods)
    if (m.name == name) return &m;
  return nullptr;
}

std::vector<std::string> ModRegistry::listLua(const ModInfo& mod, const std::string& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (auto& entry : fs::directory_iterator(fs::path(mod.dir) / folder, ec))
    if (entry.is_regular_file() && entry.path().extension() == ".lua") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

Result<std::pair<std::string, std::string>> parseScenarioRef(const std::string& ref) {
  static const std::regex re(R"(^(?:([A-Za-z0-9_\-]+):)?([A-Za-z0-9_\-]+)$)");
  std::smatch m;
  if (!std::regex_match(ref, m, re))
    return makeError("scenario \"" + ref + "\" is not of the form MOD:SCENARIO (for example base:drop)");
  std::string mod = m[1].matched ? std::string(m[1]) : std::string("base");
  return std::make_pair(mod, std::string(m[2]));
}

}  // namespace tumble::script
