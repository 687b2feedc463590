#include "app/replay.h"

#include <link.h>

#include <cmath>
#include <cstring>

#include "app/run_report.h"
#include "core/file_util.h"
#include "core/hash.h"
#include "core/json_depth.h"
#include "script/tunables.h"

namespace tumble::app {

namespace {

constexpr const char* kFormat = "tumble-replay";
// A replay holds at most this many input changes (a change is one action's
// state in one step; 60 steps/s with every action changing every step for an
// hour of a mod with 20 actions is 4.3 million).
constexpr std::size_t kMaxChanges = 5'000'000;
constexpr long long kMaxSteps = 60LL * 60 * 60 * 24;  // a day at 60 steps/s
constexpr std::size_t kMaxReplayBytes = std::size_t(512) << 20;
// A replay nests 3 levels (its action changes), its recorded tunable
// overrides a few more; deeper is refused while parsing (core/json_depth.h).
constexpr int kMaxReplayDepth = 32;

int flagsOf(const input::InputSystem::StepState& s) { return (s.down ? 1 : 0) | (s.pressed ? 2 : 0) | (s.released ? 4 : 0); }

int noteCallback(dl_phdr_info* info, std::size_t, void* out) {
  // The first object is the executable itself.
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const ElfW(Phdr)& ph = info->dlpi_phdr[i];
    if (ph.p_type != PT_NOTE) continue;
    const char* p = reinterpret_cast<const char*>(info->dlpi_addr + ph.p_vaddr);
    const char* end = p + ph.p_memsz;
    while (p + sizeof(ElfW(Nhdr)) <= end) {
      const auto* n = reinterpret_cast<const ElfW(Nhdr)*>(p);
      const char* name = p + sizeof(ElfW(Nhdr));
      const char* desc = name + ((n->n_namesz + 3) & ~3u);
      if (desc + n->n_descsz > end) break;
      if (n->n_type == NT_GNU_BUILD_ID && n->n_namesz == 4 && std::memcmp(name, "GNU", 4) == 0) {
        std::string hex;
        for (std::uint32_t k = 0; k < n->n_descsz; ++k) {
          char b[3];
          std::snprintf(b, sizeof b, "%02x", unsigned(static_cast<unsigned char>(desc[k])));
          hex += b;
        }
        *static_cast<std::string*>(out) = hex;
        return 1;
      }
      p = desc + ((n->n_descsz + 3) & ~3u);
    }
  }
  return 1;  // only the executable
}

// Field readers for loadReplay: each names the file and the field.
struct Reader {
  const std::string& file;
  std::string fail(const std::string& field, const std::string& expected) const {
    return file + ": field \"" + field + "\": expected " + expected;
  }
};

}  // namespace

std::string checksumOf(nlohmann::json doc) {
  doc.erase("checksum");
  Hasher h;
  const std::string text = doc.dump();
  h.bytes(text.data(), text.size());
  return h.hex();
}

std::string engineBuildId() {
  static const std::string id = [] {
    std::string hex;
    dl_iterate_phdr(&noteCallback, &hex);
    return hex.empty() ? std::string("unknown") : hex;
  }();
  return id;
}

void ReplayRecorder::start(Scene& scene, const SceneOptions& options) {
  m_replay = Replay{};
  Replay& r = m_replay;
  r.scenario = scene.name();
  r.seed = options.seed;
  r.dt_s = options.dt_s;
  r.substeps = options.substeps;
  r.integrator = options.integrator;
  r.sets = options.sets;
  r.engineBuild = engineBuildId();
  for (const script::ModInfo& m : scene.host().options().mods) r.modVersions[m.name] = m.version;
  const input::InputSystem& in = scene.input();
  for (int a = 0; a < in.actionCount(); ++a) r.actions.push_back(in.action(a).name);
  // The player's saved tunable values, as the scene read them at start.
  r.tuneOverrides = nullptr;
  if (options.tuneOverrides) {
    auto text = readTextFile(script::tuneOverridesPath(scene.host().mod().name), std::size_t(4) << 20);
    if (text) {
      if (auto parsed = parseJsonWithDepth(*text, kMaxReplayDepth)) r.tuneOverrides = std::move(*parsed);
    }
  }
}

void ReplayRecorder::afterStep(Scene& scene) {
  const input::InputSystem& in = scene.input();
  ReplayStep s;
  s.actions = in.stepStates();
  s.pointer = in.pointer();
  if (auto ray = in.pointerRay())
    s.pointerRay = std::array<double, 6>{double(ray->origin_m.x()),  double(ray->origin_m.y()),
                                         double(ray->origin_m.z()),  double(ray->direction.x()),
                                         double(ray->direction.y()), double(ray->direction.z())};
  m_replay.steps.push_back(std::move(s));
}

Status ReplayRecorder::write(Scene& scene, double simulatedSeconds, const std::string& path) {
  m_replay.stateHash = stateHashText(scene);
  m_replay.simulatedSeconds = simulatedSeconds;
  const std::string text = replayToJson(m_replay).dump() + "\n";
  if (Status st = writeFileAtomic(path, text); !st) return makeError("--record " + path + ": " + st.error());
  return Ok{};
}

nlohmann::json replayToJson(const Replay& r) {
  // Only changes are written: an action's state when it differs from the
  // step before (all released and 0 before the first step), the pointer and
  // its ray when they change ([step] alone: none from then on).
  nlohmann::json changes = nlohmann::json::array(), pointer = nlohmann::json::array(),
                 rays = nlohmann::json::array();
  const ReplayStep none;
  const ReplayStep* prev = &none;
  for (std::size_t i = 0; i < r.steps.size(); ++i) {
    const ReplayStep& s = r.steps[i];
    for (std::size_t a = 0; a < s.actions.size(); ++a) {
      const input::InputSystem::StepState before =
          a < prev->actions.size() ? prev->actions[a] : input::InputSystem::StepState{};
      if (s.actions[a] != before) changes.push_back({i, a, s.actions[a].value, flagsOf(s.actions[a])});
    }
    if (s.pointer != prev->pointer) {
      nlohmann::json e = nlohmann::json::array({i});
      if (s.pointer)
        for (float v : *s.pointer) e.push_back(v);
      pointer.push_back(e);
    }
    if (s.pointerRay != prev->pointerRay) {
      nlohmann::json e = nlohmann::json::array({i});
      if (s.pointerRay)
        for (double v : *s.pointerRay) e.push_back(v);
      rays.push_back(e);
    }
    prev = &s;
  }
  nlohmann::json doc = {
      {"format", kFormat},
      {"version", Replay::kFormatVersion},
      {"scenario", r.scenario},
      {"seed", r.seed},
      {"dt_s", r.dt_s},
      {"substeps", r.substeps},
      {"integrator", r.integrator},
      {"sets", r.sets},
      {"tune_overrides", r.tuneOverrides},
      {"engine_build", r.engineBuild},
      {"mods", r.modVersions},
      {"actions", r.actions},
      {"steps", r.steps.size()},
      {"simulated_seconds", r.simulatedSeconds},
      {"state_hash", r.stateHash},
      {"action_changes", changes},
      {"pointer_changes", pointer},
      {"pointer_ray_changes", rays},
  };
  doc["checksum"] = checksumOf(doc);
  return doc;
}

Result<Replay> loadReplay(const std::string& path) {
  auto text = readTextFile(path, kMaxReplayBytes);
  if (!text) return makeError("replay: " + text.error());
  auto parsed = parseJsonWithDepth(*text, kMaxReplayDepth);
  if (!parsed || !parsed->is_object())
    return makeError(path + ": not a replay (" + (parsed ? std::string("not a JSON object") : parsed.error()) +
                     "; expected a JSON object written by `tumble play --record`)");
  nlohmann::json doc = std::move(*parsed);
  const Reader rd{path};
  if (!doc.contains("format") || doc["format"] != kFormat)
    return makeError(path + ": not a replay (its \"format\" is not \"" + kFormat + "\"; replays are written by "
                     "`tumble play --record FILE`)");
  if (!doc["version"].is_number_integer() || doc["version"] != Replay::kFormatVersion)
    return makeError(path + ": replay format version " + doc["version"].dump() + "; this build reads version " +
                     std::to_string(Replay::kFormatVersion));
  if (!doc["checksum"].is_string()) return makeError(rd.fail("checksum", "a string (16 hex digits)"));
  if (const std::string sum = checksumOf(doc); doc["checksum"] != sum)
    return makeError(path + ": the checksum does not match the content (recorded " + doc["checksum"].get<std::string>() +
                     ", content gives " + sum + "): the file was changed or damaged after it was recorded");
  Replay r;
  auto str = [&](const char* f, std::string& out) -> Status {
    if (!doc[f].is_string()) return makeError(rd.fail(f, "a string"));
    out = doc[f].get<std::string>();
    return Ok{};
  };
  const std::initializer_list<std::pair<const char*, std::string*>> strings = {
      {"scenario", &r.scenario}, {"integrator", &r.integrator}, {"engine_build", &r.engineBuild},
      {"state_hash", &r.stateHash}};
  for (auto [f, out] : strings)
    if (Status st = str(f, *out); !st) return makeError(st.error());
  if (!doc["seed"].is_number_unsigned()) return makeError(rd.fail("seed", "a non-negative integer"));
  r.seed = doc["seed"].get<std::uint64_t>();
  if (!doc["dt_s"].is_number() || !(doc["dt_s"].get<double>() > 0) || !std::isfinite(doc["dt_s"].get<double>()))
    return makeError(rd.fail("dt_s", "a positive number of seconds"));
  r.dt_s = doc["dt_s"].get<double>();
  if (!doc["substeps"].is_number_integer() || doc["substeps"].get<long long>() < 0 || doc["substeps"].get<long long>() > 1000)
    return makeError(rd.fail("substeps", "an integer 0..1000 (0: the world's default)"));
  r.substeps = doc["substeps"].get<int>();
  if (!doc["simulated_seconds"].is_number()) return makeError(rd.fail("simulated_seconds", "a number"));
  r.simulatedSeconds = doc["simulated_seconds"].get<double>();
  for (const char* f : {"sets", "mods"}) {
    if (!doc[f].is_object()) return makeError(rd.fail(f, "an object of strings"));
    for (auto& [k, v] : doc[f].items()) {
      if (!v.is_string()) return makeError(rd.fail(std::string(f) + "." + k, "a string"));
      (std::strcmp(f, "sets") == 0 ? r.sets : r.modVersions)[k] = v.get<std::string>();
    }
  }
  r.tuneOverrides = doc["tune_overrides"];
  if (!r.tuneOverrides.is_null() && !r.tuneOverrides.is_object())
    return makeError(rd.fail("tune_overrides", "null or an object (a tunables overrides file)"));
  if (!doc["actions"].is_array()) return makeError(rd.fail("actions", "an array of action names"));
  for (const auto& a : doc["actions"]) {
    if (!a.is_string()) return makeError(rd.fail("actions", "an array of action names"));
    r.actions.push_back(a.get<std::string>());
  }
  if (!doc["steps"].is_number_unsigned() || doc["steps"].get<long long>() > kMaxSteps)
    return makeError(rd.fail("steps", "a step count 0.." + std::to_string(kMaxSteps)));
  const long long steps = doc["steps"].get<long long>();
  r.steps.assign(std::size_t(steps), ReplayStep{});
  // Changes, in step order: each holds until the next change.
  const nlohmann::json& changes = doc["action_changes"];
  if (!changes.is_array() || changes.size() > kMaxChanges)
    return makeError(rd.fail("action_changes", "an array of at most " + std::to_string(kMaxChanges) +
                                                   " [step, action, value, flags] entries"));
  std::vector<input::InputSystem::StepState> current(r.actions.size());
  std::size_t next = 0;
  long long lastStep = -1;
  for (long long i = 0; i < steps; ++i) {
    for (; next < changes.size(); ++next) {
      const auto& c = changes[next];
      const std::string at = "action_changes[" + std::to_string(next) + "]";
      if (!c.is_array() || c.size() != 4 || !c[0].is_number_unsigned() || !c[1].is_number_unsigned() ||
          !c[2].is_number() || !c[3].is_number_unsigned() || c[3].get<unsigned>() > 7)
        return makeError(rd.fail(at, "[step, action index, value, flags 0..7]"));
      const long long step = c[0].get<long long>();
      if (step < lastStep || step >= steps) return makeError(rd.fail(at, "a step in order, below \"steps\""));
      if (c[1].get<std::size_t>() >= r.actions.size()) return makeError(rd.fail(at, "an action index below the number of actions"));
      if (!std::isfinite(c[2].get<double>())) return makeError(rd.fail(at, "a finite value"));
      if (step != i) break;
      lastStep = step;
      const unsigned flags = c[3].get<unsigned>();
      current[c[1].get<std::size_t>()] = {c[2].get<double>(), (flags & 1) != 0, (flags & 2) != 0, (flags & 4) != 0};
    }
    r.steps[std::size_t(i)].actions = current;
  }
  if (next != changes.size()) return makeError(rd.fail("action_changes", "steps below \"steps\" in order"));
  // Pointer and ray changes: [step] or [step, values...].
  auto readChanges = [&](const char* f, std::size_t width, auto assign) -> Status {
    const nlohmann::json& list = doc[f];
    if (!list.is_array() || list.size() > kMaxChanges) return makeError(rd.fail(f, "an array of changes"));
    long long prevStep = -1;
    for (std::size_t k = 0; k < list.size(); ++k) {
      const auto& c = list[k];
      const std::string at = std::string(f) + "[" + std::to_string(k) + "]";
      if (!c.is_array() || (c.size() != 1 && c.size() != 1 + width) || !c[0].is_number_unsigned())
        return makeError(rd.fail(at, "[step] or [step, " + std::to_string(width) + " numbers]"));
      const long long step = c[0].get<long long>();
      if (step <= prevStep || step >= steps) return makeError(rd.fail(at, "a step in order, below \"steps\""));
      std::vector<double> v;
      for (std::size_t j = 1; j < c.size(); ++j) {
        if (!c[j].is_number() || !std::isfinite(c[j].get<double>())) return makeError(rd.fail(at, "finite numbers"));
        v.push_back(c[j].get<double>());
      }
      const long long until = k + 1 < list.size() && list[k + 1].is_array() && !list[k + 1].empty() &&
                                      list[k + 1][0].is_number_unsigned()
                                  ? std::min(steps, list[k + 1][0].get<long long>())
                                  : steps;
      for (long long i = step; i < until; ++i) assign(r.steps[std::size_t(i)], v);
      prevStep = step;
    }
    return Ok{};
  };
  if (Status st = readChanges("pointer_changes", 2, [](ReplayStep& s, const std::vector<double>& v) {
        if (v.empty()) s.pointer.reset();
        else s.pointer = std::array<float, 2>{float(v[0]), float(v[1])};
      });
      !st)
    return makeError(st.error());
  if (Status st = readChanges("pointer_ray_changes", 6, [](ReplayStep& s, const std::vector<double>& v) {
        if (v.empty()) s.pointerRay.reset();
        else s.pointerRay = std::array<double, 6>{v[0], v[1], v[2], v[3], v[4], v[5]};
      });
      !st)
    return makeError(st.error());
  return r;
}

std::vector<std::string> replayVersionWarnings(const Replay& r, const Scene& scene) {
  std::vector<std::string> out;
  if (r.engineBuild != engineBuildId())
    out.push_back("recorded by engine build " + r.engineBuild + ", this is build " + engineBuildId() +
                  ": the run may end in another state");
  std::map<std::string, std::string> now;
  for (const script::ModInfo& m : scene.host().options().mods) now[m.name] = m.version;
  for (const auto& [name, version] : r.modVersions) {
    auto it = now.find(name);
    if (it == now.end()) out.push_back("mod " + name + " " + version + " was present when recording and is not now");
    else if (it->second != version)
      out.push_back("mod " + name + " was version " + version + " when recording, now " + it->second);
  }
  for (const auto& [name, version] : now)
    if (!r.modVersions.count(name)) out.push_back("mod " + name + " " + version + " was not present when recording");
  for (const std::string& a : r.actions)
    if (const_cast<Scene&>(scene).input().find(a) < 0)
      out.push_back("input action \"" + a + "\" was recorded but no mod defines it now: it is left out");
  return out;
}

void playBackStep(const Replay& r, long long index, Scene& scene) {
  input::InputSystem& in = scene.input();
  const ReplayStep& s = r.steps[std::size_t(index)];
  // Map the recorded action order onto this scene's (the same names unless
  // a bindings file changed; an action the scene lacks is dropped).
  std::vector<input::InputSystem::StepState> states(std::size_t(in.actionCount()));
  for (std::size_t a = 0; a < r.actions.size() && a < s.actions.size(); ++a) {
    const int here = in.find(r.actions[a]);
    if (here >= 0) states[std::size_t(here)] = s.actions[a];
  }
  in.playBack(std::move(states));
  if (s.pointer) in.setPointer((*s.pointer)[0], (*s.pointer)[1]);
  if (s.pointerRay) {
    const auto& v = *s.pointerRay;
    in.setPointerRay(Vec3(Real(v[0]), Real(v[1]), Real(v[2])), Vec3(Real(v[3]), Real(v[4]), Real(v[5])));
  }
}

}  // namespace tumble::app
