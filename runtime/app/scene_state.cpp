#include "app/scene_state.h"

#include <bit>
#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

#include "app/replay.h"
#include "app/run_report.h"
#include "core/file_util.h"
#include "core/hash.h"
#include "physics/joints/joint_system.h"
#include "script/presentation.h"

namespace tumble::app {

namespace {

constexpr const char* kFormat = "tumble-scene-state";
constexpr std::size_t kMaxFileBytes = std::size_t(1) << 30;

std::string toHex(const std::string& bytes) {
  static const char* kDigits = "0123456789abcdef";
  std::string out(bytes.size() * 2, '0');
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const auto b = static_cast<unsigned char>(bytes[i]);
    out[2 * i] = kDigits[b >> 4];
    out[2 * i + 1] = kDigits[b & 15];
  }
  return out;
}

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

bool fromHex(const std::string& hex, std::string& out) {
  if (hex.size() % 2) return false;
  out.assign(hex.size() / 2, '\0');
  for (std::size_t i = 0; i < out.size(); ++i) {
    const int hi = hexDigit(hex[2 * i]), lo = hexDigit(hex[2 * i + 1]);
    if (hi < 0 || lo < 0) return false;
    out[i] = char(hi * 16 + lo);
  }
  return true;
}

/// A double as its 64 bits in hex: read back bit for bit.
std::string bitsOf(double v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(v)));
  return buf;
}

bool doubleOf(const nlohmann::json& j, double& out) {
  if (!j.is_string() || j.get<std::string>().size() != 16) return false;
  std::string bytes;
  if (!fromHex(j.get<std::string>(), bytes)) return false;
  std::uint64_t bits = 0;
  for (char c : bytes) bits = (bits << 8) | static_cast<unsigned char>(c);
  out = std::bit_cast<double>(bits);
  return std::isfinite(out);
}

std::string fieldError(const std::string& path, const std::string& field, const std::string& expected) {
  return path + ": field \"" + field + "\": expected " + expected;
}

}  // namespace

Status saveSceneState(Scene& scene, const RunClock& clock, const std::string& path) {
  auto script = scene.host().saveState();
  if (!script) return makeError("--save-state: " + script.error());
  const SceneOptions& o = scene.options();
  const script::SystemsState systems = script::saveSystems(scene);
  nlohmann::json mods = nlohmann::json::object();
  for (const script::ModInfo& m : scene.host().options().mods) mods[m.name] = m.version;
  nlohmann::json doc = {
      {"format", kFormat},
      {"version", SceneStateFile::kFormatVersion},
      {"scenario", scene.name()},
      {"seed", o.seed},
      {"dt_s", bitsOf(o.dt_s)},
      {"substeps", o.substeps},
      {"integrator", o.integrator},
      {"sets", o.sets},
      {"engine_build", engineBuildId()},
      {"mods", mods},
      {"step", clock.step},
      {"time_s", bitsOf(clock.time_s)},
      {"base_time_s", bitsOf(clock.baseTime_s)},
      {"base_step", clock.baseStep},
      {"step_dt_s", bitsOf(clock.stepDt_s)},
      {"requested_dt_s", bitsOf(scene.dt_s() == o.dt_s ? 0.0 : scene.dt_s())},
      {"state_hash", stateHashText(scene)},
      {"joint_solver", systems.jointSolver},
      {"world", toHex(systems.world)},
      {"joints", toHex(systems.joints)},
      {"vehicles", toHex(systems.vehicles)},
      {"ropes_and_cloth", toHex(systems.ropesAndCloth)},
      {"particles", toHex(systems.particles)},
      {"script", toHex(*script)},
  };
  doc["checksum"] = checksumOf(doc);
  if (Status st = writeFileAtomic(path, doc.dump(1)); !st) return makeError("--save-state " + path + ": " + st.error());
  return Ok{};
}

Result<SceneStateFile> loadSceneState(const std::string& path) {
  auto text = readTextFile(path, kMaxFileBytes);
  if (!text) return makeError("--load-state: " + text.error());
  nlohmann::json doc = nlohmann::json::parse(*text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object())
    return makeError(path + ": not a scene snapshot (expected a JSON object written by `tumble run --save-state`)");
  if (!doc.contains("format") || doc["format"] != kFormat)
    return makeError(path + ": not a scene snapshot (its \"format\" is not \"" + kFormat + "\")");
  if (!doc["version"].is_number_integer() || doc["version"] != SceneStateFile::kFormatVersion)
    return makeError(path + ": field \"version\": snapshot format " + doc["version"].dump() + "; this build reads " +
                     std::to_string(SceneStateFile::kFormatVersion));
  if (!doc["checksum"].is_string()) return makeError(fieldError(path, "checksum", "a string (16 hex digits)"));
  if (const std::string sum = checksumOf(doc); doc["checksum"] != sum)
    return makeError(path + ": field \"checksum\": does not match the content (saved " +
                     doc["checksum"].get<std::string>() + ", content gives " + sum +
                     "): the file was changed or damaged after it was written");
  SceneStateFile s;
  for (auto [f, out] : {std::pair<const char*, std::string*>{"scenario", &s.scenario}, {"integrator", &s.integrator},
                        {"engine_build", &s.engineBuild}, {"state_hash", &s.stateHash},
                        {"joint_solver", &s.systems.jointSolver}}) {
    if (!doc[f].is_string()) return makeError(fieldError(path, f, "a string"));
    *out = doc[f].get<std::string>();
  }
  if (!doc["seed"].is_number_unsigned()) return makeError(fieldError(path, "seed", "a non-negative integer"));
  s.seed = doc["seed"].get<std::uint64_t>();
  if (!doc["substeps"].is_number_integer() || doc["substeps"].get<long long>() < 0 ||
      doc["substeps"].get<long long>() > 1000)
    return makeError(fieldError(path, "substeps", "an integer 0..1000"));
  s.substeps = doc["substeps"].get<int>();
  for (auto [f, out] : {std::pair<const char*, long long*>{"step", &s.clock.step}, {"base_step", &s.clock.baseStep}}) {
    if (!doc[f].is_number_unsigned()) return makeError(fieldError(path, f, "a step count >= 0"));
    *out = doc[f].get<long long>();
  }
  for (auto [f, out] : {std::pair<const char*, double*>{"dt_s", &s.dt_s}, {"time_s", &s.clock.time_s},
                        {"base_time_s", &s.clock.baseTime_s}, {"step_dt_s", &s.clock.stepDt_s},
                        {"requested_dt_s", &s.requestedDt_s}})
    if (!doubleOf(doc[f], *out)) return makeError(fieldError(path, f, "a finite number as 16 hex digits (its bits)"));
  if (!(s.dt_s > 0)) return makeError(fieldError(path, "dt_s", "a positive step"));
  for (const char* f : {"sets", "mods"}) {
    if (!doc[f].is_object()) return makeError(fieldError(path, f, "an object of strings"));
    for (auto& [k, v] : doc[f].items()) {
      if (!v.is_string()) return makeError(fieldError(path, std::string(f) + "." + k, "a string"));
      (std::strcmp(f, "sets") == 0 ? s.sets : s.modVersions)[k] = v.get<std::string>();
    }
  }
  if (physics::JointSolverKind kind; !physics::parseJointSolver(s.systems.jointSolver, &kind))
    return makeError(fieldError(path, "joint_solver", "\"lagrange\" or \"impulse\""));
  for (auto [f, out] : {std::pair<const char*, std::string*>{"world", &s.systems.world}, {"script", &s.script},
                        {"joints", &s.systems.joints}, {"vehicles", &s.systems.vehicles},
                        {"ropes_and_cloth", &s.systems.ropesAndCloth}, {"particles", &s.systems.particles}})
    if (!doc[f].is_string() || !fromHex(doc[f].get<std::string>(), *out))
      return makeError(fieldError(path, f, "hex digits (the saved state's bytes)"));
  return s;
}

void applySceneStateOptions(const SceneStateFile& s, SceneOptions& o) {
  o.scenarioRef = s.scenario;
  o.seed = s.seed;
  o.dt_s = s.dt_s;
  o.substeps = s.substeps;
  o.integrator = s.integrator;
  o.sets = s.sets;
}

Status restoreSceneState(Scene& scene, const SceneStateFile& s, const std::string& path) {
  if (s.engineBuild != engineBuildId())
    return makeError(path + ": field \"engine_build\": saved by engine build " + s.engineBuild + ", this is build " +
                     engineBuildId() + " (a snapshot holds exact bits of one build's state)");
  std::map<std::string, std::string> here;
  for (const script::ModInfo& m : scene.host().options().mods) here[m.name] = m.version;
  for (const auto& [name, version] : s.modVersions) {
    auto it = here.find(name);
    if (it == here.end()) return makeError(path + ": field \"mods\": mod " + name + " " + version + " is not here");
    if (it->second != version)
      return makeError(path + ": field \"mods\": saved with mod " + name + " " + version + ", here it is " + it->second);
  }
  for (const auto& [name, version] : here)
    if (!s.modVersions.count(name))
      return makeError(path + ": field \"mods\": mod " + name + " " + version + " was not there when saved");
  std::string part;
  const std::map<std::string, std::string>& modDirs = scene.host().options().modDirs;
  if (Status st = script::restoreSystems(
          scene, s.systems, [&](const std::string& file) { return script::isFileInMods(file, modDirs); }, &part);
      !st)
    return makeError(path + ": field \"" + part + "\": " + st.error());
  if (s.requestedDt_s > 0) scene.requestDt(s.requestedDt_s);
  if (Status st = scene.host().restoreState(s.script, s.clock.time_s, s.clock.step); !st)
    return makeError(path + ": field \"script\": " + st.error());
  if (const std::string hash = stateHashText(scene); hash != s.stateHash)
    return makeError(path + ": field \"state_hash\": the restored scene hashes to " + hash + ", the saved one to " +
                     s.stateHash + " (part of the state was not restored)");
  return Ok{};
}

}  // namespace tumble::app
