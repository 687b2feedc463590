#include "app/game_catalog.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "app/scene.h"
#include "core/file_util.h"
#include "script/vehicle_defs.h"
#include "vehicle/vehicle_def.h"

namespace tumble::app {

namespace fs = std::filesystem;

GameCatalog::GameCatalog(std::vector<std::string> modSearchDirs)
    : m_dirs(std::move(modSearchDirs)), m_registry(script::ModRegistry::discover(m_dirs)) {}

std::string GameCatalog::leadingComment(const std::string& luaText) {
  std::istringstream lines(luaText);
  std::string line, out;
  while (std::getline(lines, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("--", 0) != 0) break;  // the comment block ends
    std::string text = line.substr(2);
    if (!text.empty() && text[0] == '[') break;  // a --[[ block: not a plain description
    const auto start = text.find_first_not_of(" \t");
    if (start == std::string::npos) {  // an empty comment line ends the first paragraph
      if (out.empty()) continue;
      break;
    }
    if (!out.empty()) out += ' ';
    out.append(text, start, std::string::npos);
  }
  return out;
}

std::string GameCatalog::driveLayout(const std::vector<bool>& driven, const std::vector<double>& axleZ_m) {
  const int n = int(driven.size());
  const int nDriven = int(std::count(driven.begin(), driven.end(), true));
  if (nDriven == 0) return "no driven axle";
  if (nDriven == n) return n <= 2 ? "all-wheel drive" : "all " + std::to_string(n) + " axles driven";
  double front = -1e30, rear = 1e30;
  for (double z : axleZ_m) front = std::max(front, z), rear = std::min(rear, z);
  bool allFront = true, allRear = true;
  for (int i = 0; i < n; ++i) {
    if (!driven[std::size_t(i)]) continue;
    if (axleZ_m[std::size_t(i)] != front) allFront = false;
    if (axleZ_m[std::size_t(i)] != rear) allRear = false;
  }
  if (n == 2 && allFront) return "front-wheel drive";
  if (n == 2 && allRear) return "rear-wheel drive";
  return std::to_string(nDriven) + " of " + std::to_string(n) + " axles driven";
}

const std::vector<ScenarioEntry>& GameCatalog::scenarios(const std::string& modName) {
  auto it = m_scenarios.find(modName);
  if (it != m_scenarios.end()) return it->second;
  std::vector<ScenarioEntry>& list = m_scenarios[modName];
  const script::ModInfo* mod = m_registry.find(modName);
  if (!mod) return list;
  for (const std::string& name : script::ModRegistry::listLua(*mod, "scenarios")) {
    ScenarioEntry e;
    e.ref = modName + ":" + name;
    e.name = name;
    e.title = name;
    e.file = (fs::path(mod->dir) / "scenarios" / (name + ".lua")).string();
    if (auto text = readTextFile(e.file)) e.description = leadingComment(*text);
    SceneOptions o;
    o.scenarioRef = e.ref;
    o.modDirs = m_dirs;
    auto summary = Scene::summarize(o);
    if (!summary) {
      e.problem = summary.error();
    } else {
      if (!summary->title.empty()) e.title = summary->title;
      if (summary->params) {
        for (const script::ParamDecl& p : *summary->params)
          if (p.name == kVehicleParam && p.type == script::ParamDecl::Type::String) {
            e.takesVehicle = true;
            e.defaultVehicle = p.defaultText;
          }
      }
    }
    list.push_back(std::move(e));
  }
  return list;
}

const ScenarioEntry* GameCatalog::scenario(const std::string& ref) {
  auto parsed = script::parseScenarioRef(ref);
  if (!parsed) return nullptr;
  for (const ScenarioEntry& e : scenarios(parsed->first))
    if (e.name == parsed->second) return &e;
  return nullptr;
}

const std::vector<VehicleEntry>& GameCatalog::vehiclesOf(const script::ModInfo& mod) {
  auto it = m_vehiclesOfMod.find(mod.name);
  if (it != m_vehiclesOfMod.end()) return it->second;
  std::vector<VehicleEntry>& list = m_vehiclesOfMod[mod.name];
  for (const std::string& name : script::ModRegistry::listLua(mod, "vehicles")) {
    VehicleEntry v;
    v.ref = mod.name + ":" + name;
    v.name = name;
    auto def = script::loadVehicleFile(mod, name);
    if (!def) {
      v.problem = def.error();
      list.push_back(std::move(v));
      continue;
    }
    const vehicle::VehicleDef& d = *def;
    v.name = d.name;
    v.description = d.description;
    v.mass_kg = double(d.chassis.mass_kg);
    v.peakPower_kW = double(vehicle::peakPower_W(d.engine)) / 1000.0;
    std::vector<bool> driven;
    std::vector<double> z;
    for (const vehicle::AxleDef& a : d.axles) {
      driven.push_back(a.driven);
      z.push_back(double(a.position_m.z()));
    }
    v.drive = driveLayout(driven, z);
    v.grip = double(d.tyre.lateral.maxY());
    v.gripLongitudinal = double(d.tyre.longitudinal.maxY());
    list.push_back(std::move(v));
  }
  return list;
}

const std::vector<VehicleEntry>& GameCatalog::vehiclesFor(const std::string& modName) {
  auto it = m_vehiclesFor.find(modName);
  if (it != m_vehiclesFor.end()) return it->second;
  std::vector<VehicleEntry>& list = m_vehiclesFor[modName];
  const script::ModInfo* mod = m_registry.find(modName);
  auto visible = [&](const script::ModInfo& m) {
    if (m.name == "base" || m.name == modName) return true;
    if (!mod) return false;
    for (const script::ModDependency& d : mod->depends)
      if (d.name == m.name) return true;
    return false;
  };
  for (const script::ModInfo& m : m_registry.mods())  // load order
    if (visible(m))
      for (const VehicleEntry& v : vehiclesOf(m)) list.push_back(v);
  return list;
}

}  // namespace tumble::app
