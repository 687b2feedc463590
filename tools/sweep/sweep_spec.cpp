#include "tools/sweep/sweep_spec.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>

#include "app/physics_settings.h"
#include "app/terrain_scene.h"
#include "app/scene.h"
#include "core/file_util.h"
#include "core/random.h"
#include "physics/integrate.h"
#include "physics/joints/joint_system.h"
#include "script/lua_vm.h"
#include "script/sandbox.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace fs = std::filesystem;
using nlohmann::json;

namespace tumble::tools::sweep {

std::string numberText(double v) {
  // Whole numbers as such ("20", not "2e+01"); others the shortest text.
  if (v == std::floor(v) && std::fabs(v) < 1e15) {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f", v);
    return text;
  }
  for (int precision = 1; precision <= 17; ++precision) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*g", precision, v);
    if (std::strtod(text, nullptr) == v) return text;
  }
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

namespace {

const char* const kSpecFields[] = {"name", "scenarios", "mods", "seconds", "steps", "grid", "random", "set",
                                   "seeds", "integrators", "dt", "substeps", "collect", "error_metric"};

// Report fields a sweep can collect: exact paths, and prefixes whose
// second part names a parameter, tunable, expectation or mesh counter.
const char* const kReportFields[] = {
    "seed", "dt", "substeps", "steps", "simulated_seconds", "wall_seconds.total", "wall_seconds.startup",
    "wall_seconds.physics", "wall_seconds.script", "wall_seconds.particles", "wall_seconds.render", "step_ms.median",
    "step_ms.p99", "step_ms.max", "peak_rss_mb", "counts.bodies", "counts.joints", "counts.contacts_max",
    "counts.particles_max", "error.energy_rel_drift_max", "error.penetration_max_m", "error.joint_error_max_m",
    "error.momentum_rel_drift_max", "error.nan_events", "game.score"};
const char* const kReportPrefixes[] = {"params.", "tunables.", "expectations.", "mesh_collision."};

const std::vector<std::string> kDefaultCollect = {
    "wall_seconds.total",      "step_ms.median",           "peak_rss_mb",
    "error.energy_rel_drift_max", "error.penetration_max_m", "error.joint_error_max_m",
    "error.momentum_rel_drift_max"};

// A --set value's text from a JSON scalar; false if it is not one.
bool scalarText(const json& v, std::string* out) {
  if (v.is_number()) *out = numberText(v.get<double>());
  else if (v.is_boolean()) *out = v.get<bool>() ? "true" : "false";
  else if (v.is_string()) *out = v.get<std::string>();
  else return false;
  return true;
}

std::string where(const std::string& file, const std::string& field) { return file + ": field '" + field + "'"; }

// ---- Lua specs ----------------------------------------------------------------

Result<json> luaToJson(lua_State* L, int idx, const std::string& path, int depth) {
  idx = lua_absindex(L, idx);
  switch (lua_type(L, idx)) {
    case LUA_TNUMBER: return lua_isinteger(L, idx) ? json(lua_tointeger(L, idx)) : json(lua_tonumber(L, idx));
    case LUA_TBOOLEAN: return json(bool(lua_toboolean(L, idx)));
    case LUA_TSTRING: return json(std::string(lua_tostring(L, idx)));
    case LUA_TTABLE: break;
    default:
      return makeError("'" + path + "' is a " + luaL_typename(L, idx) +
                       "; a spec holds only numbers, booleans, strings and tables");
  }
  if (depth > 8) return makeError("'" + path + "' nests tables too deeply");
  const lua_Integer n = luaL_len(L, idx);
  json out = n > 0 ? json::array() : json::object();
  lua_pushnil(L);
  while (lua_next(L, idx) != 0) {
    std::string key;
    if (lua_type(L, -2) == LUA_TSTRING) key = lua_tostring(L, -2);
    else if (lua_isinteger(L, -2)) key = std::to_string(lua_tointeger(L, -2));
    else {
      lua_pop(L, 2);
      return makeError("'" + path + "' has a key that is neither a name nor a list index");
    }
    const std::string sub = path.empty() ? key : path + "." + key;
    auto v = luaToJson(L, -1, sub, depth + 1);
    lua_pop(L, 1);
    if (!v) {
      lua_pop(L, 1);
      return v;
    }
    if (out.is_array()) {
      if (!lua_isinteger(L, -1) || lua_tointeger(L, -1) < 1 || lua_tointeger(L, -1) > n) {
        lua_pop(L, 1);
        return makeError("'" + path + "' mixes a list with named fields");
      }
      out.get_ref<json::array_t&>().resize(std::size_t(n));
      out[std::size_t(lua_tointeger(L, -1) - 1)] = std::move(v.value());
    } else {
      out[key] = std::move(v.value());
    }
  }
  return out;
}

Result<json> readLuaSpec(const std::string& path) {
  script::LuaVm vm(script::VmLimits{64u << 20, 10'000'000});
  lua_State* L = vm.state();
  const std::string dir = fs::absolute(path).parent_path().string();
  int requireRef = 0;
  script::pushSandboxEnvironment(L, script::SandboxPaths{dir, ""}, 1, &requireRef);
  const int env = lua_gettop(L);
  script::guardEnvironment(L, env);
  if (luaL_loadfilex(L, path.c_str(), "t") != LUA_OK) {
    std::string msg = lua_tostring(L, -1);
    return makeError(msg);
  }
  lua_pushvalue(L, env);
  lua_setupvalue(L, -2, 1);
  script::ScriptError err;
  if (!vm.call(0, 1, "sweep", fs::path(path).filename().string(), "top level", &err))
    return makeError(path + ": " + err.message + (err.line > 0 ? " (line " + std::to_string(err.line) + ")" : ""));
  if (!lua_istable(L, -1)) return makeError(path + ": must return a table {scenarios = {...}, grid = {...}, ...}");
  auto j = luaToJson(L, -1, "", 0);
  if (!j) return makeError(path + ": " + j.error());
  if (j->is_array()) return makeError(path + ": must return a table of named fields, not a list");
  return j;
}

// ---- fields -------------------------------------------------------------------

Status readStringList(const json& j, const std::string& file, const char* field, std::vector<std::string>* out) {
  if (!j.contains(field)) return Ok{};
  const json& v = j[field];
  if (!v.is_array()) return makeError(where(file, field) + " must be a list of strings");
  if (v.empty()) return makeError(where(file, field) + " is empty: give at least one value or leave the field out");
  out->clear();
  for (const json& e : v) {
    if (!e.is_string()) return makeError(where(file, field) + " must be a list of strings; got " + e.dump());
    out->push_back(e.get<std::string>());
  }
  return Ok{};
}

Status readNumberList(const json& j, const std::string& file, const char* field, std::vector<double>* out) {
  if (!j.contains(field)) return Ok{};
  const json& v = j[field].is_number() ? json::array({j[field]}) : j[field];
  if (!v.is_array()) return makeError(where(file, field) + " must be a number or a list of numbers");
  if (v.empty()) return makeError(where(file, field) + " is empty: give at least one value or leave the field out");
  for (const json& e : v) {
    if (!e.is_number()) return makeError(where(file, field) + " must be a list of numbers; got " + e.dump());
    out->push_back(e.get<double>());
  }
  return Ok{};
}

Status readGrid(const json& j, const std::string& file, SweepSpec& spec) {
  if (!j.contains("grid")) return Ok{};
  const json& g = j["grid"];
  if (!g.is_object())
    return makeError(where(file, "grid") + " must be a table of KEY = {values...}, e.g. grid = {grip = {0.8, 1, 1.2}}");
  if (g.empty())
    return makeError(where(file, "grid") + " is empty: it names no parameter to sweep (give grid = {NAME = {values}} or leave it out)");
  for (const auto& [key, values] : g.items()) {
    const std::string field = "grid." + key;
    if (!values.is_array())
      return makeError(where(file, field) + " must be a list of values, e.g. {0.8, 1, 1.2}");
    if (values.empty()) return makeError(where(file, field) + " is an empty list: the grid would have no points");
    std::vector<std::string> texts;
    for (const json& v : values) {
      std::string t;
      if (!scalarText(v, &t)) return makeError(where(file, field) + ": each value must be a number, boolean or string; got " + v.dump());
      texts.push_back(t);
    }
    spec.grid.emplace_back(key, std::move(texts));
  }
  return Ok{};
}

Status readRandom(const json& j, const std::string& file, SweepSpec& spec) {
  if (!j.contains("random")) return Ok{};
  const json& r = j["random"];
  const std::string usage = "e.g. random = {samples = 20, seed = 7, ranges = {grip = {0.6, 1.4}}}";
  if (!r.is_object()) return makeError(where(file, "random") + " must be a table, " + usage);
  for (const auto& [k, v] : r.items())
    if (k != "samples" && k != "seed" && k != "ranges")
      return makeError(where(file, "random." + k) + " is not a field of random (samples, seed, ranges)");
  if (!r.contains("samples") || !r["samples"].is_number_integer() || r["samples"].get<long long>() < 1)
    return makeError(where(file, "random.samples") + " must be a whole number >= 1, " + usage);
  if (r["samples"].get<long long>() > 10'000'000) return makeError(where(file, "random.samples") + " is above 10 000 000");
  spec.random.samples = int(r["samples"].get<long long>());
  if (r.contains("seed")) {
    if (!r["seed"].is_number_integer() || r["seed"].get<long long>() < 0)
      return makeError(where(file, "random.seed") + " must be a whole number >= 0");
    spec.random.seed = r["seed"].get<std::uint64_t>();
  }
  if (!r.contains("ranges") || !r["ranges"].is_object() || r["ranges"].empty())
    return makeError(where(file, "random.ranges") + " must name at least one parameter with {min, max}, " + usage);
  for (const auto& [key, range] : r["ranges"].items()) {
    if (!range.is_array() || range.size() != 2 || !range[0].is_number() || !range[1].is_number() ||
        !(range[0].get<double>() <= range[1].get<double>()))
      return makeError(where(file, "random.ranges." + key) + " must be {min, max} with min <= max");
    spec.random.ranges[key] = {range[0].get<double>(), range[1].get<double>()};
  }
  return Ok{};
}

}  // namespace

Result<SweepSpec> specFromJson(const json& j, const std::string& file, const std::string& baseDir) {
  if (!j.is_object()) return makeError(file + ": a sweep spec is a table (JSON object) of fields");
  for (const auto& item : j.items()) {
    const std::string& k = item.key();
    bool known = std::any_of(std::begin(kSpecFields), std::end(kSpecFields), [&](const char* f) { return k == f; });
    if (!known) {
      std::string list;
      for (const char* f : kSpecFields) list += (list.empty() ? "" : ", ") + std::string(f);
      return makeError(where(file, k) + " is not a spec field (known: " + list + ")");
    }
  }
  SweepSpec spec;
  spec.file = file;
  spec.name = j.contains("name") && j["name"].is_string() ? j["name"].get<std::string>() : fs::path(file).stem().string();
  if (!j.contains("scenarios")) return makeError(where(file, "scenarios") + " is missing: name at least one MOD:SCENARIO");
  if (auto st = readStringList(j, file, "scenarios", &spec.scenarios); !st) return makeError(st.error());
  std::vector<std::string> mods;
  if (auto st = readStringList(j, file, "mods", &mods); !st) return makeError(st.error());
  for (const std::string& m : mods) spec.modDirs.push_back(fs::absolute(fs::path(baseDir) / m).lexically_normal().string());
  if (j.contains("seconds")) {
    if (!j["seconds"].is_number() || !(j["seconds"].get<double>() > 0))
      return makeError(where(file, "seconds") + " must be a number of simulated seconds > 0");
    spec.seconds = j["seconds"].get<double>();
  }
  if (j.contains("steps")) {
    if (!j["steps"].is_number_integer() || j["steps"].get<long long>() < 1)
      return makeError(where(file, "steps") + " must be a whole number of steps >= 1");
    if (spec.seconds > 0) return makeError(file + ": give 'seconds' or 'steps', not both");
    spec.steps = j["steps"].get<long long>();
  }
  if (auto st = readGrid(j, file, spec); !st) return makeError(st.error());
  if (auto st = readRandom(j, file, spec); !st) return makeError(st.error());
  if (j.contains("set")) {
    if (!j["set"].is_object()) return makeError(where(file, "set") + " must be a table of KEY = value given to every run");
    for (const auto& [k, v] : j["set"].items()) {
      std::string t;
      if (!scalarText(v, &t)) return makeError(where(file, "set." + k) + " must be a number, boolean or string");
      spec.fixed.push_back({k, t});
    }
  }
  if (j.contains("seeds")) {
    const json& s = j["seeds"];
    spec.seeds.clear();
    if (s.is_number_integer()) {  // seeds = N: 1 .. N
      if (s.get<long long>() < 1) return makeError(where(file, "seeds") + " as a count must be >= 1");
      for (long long i = 1; i <= s.get<long long>() && i <= 10'000'000; ++i) spec.seeds.push_back(std::uint64_t(i));
    } else if (s.is_array()) {
      if (s.empty()) return makeError(where(file, "seeds") + " is empty: give seeds or leave the field out (seed 1)");
      for (const json& e : s) {
        if (!e.is_number_integer() || e.get<long long>() < 0)
          return makeError(where(file, "seeds") + " must hold whole numbers >= 0; got " + e.dump());
        spec.seeds.push_back(e.get<std::uint64_t>());
      }
    } else {
      return makeError(where(file, "seeds") + " must be a list of seeds or a count N (seeds 1..N)");
    }
  }
  if (auto st = readStringList(j, file, "integrators", &spec.integrators); !st) return makeError(st.error());
  if (auto st = readNumberList(j, file, "dt", &spec.dts); !st) return makeError(st.error());
  std::vector<double> substeps;
  if (auto st = readNumberList(j, file, "substeps", &substeps); !st) return makeError(st.error());
  for (double s : substeps) {
    if (s != std::floor(s)) return makeError(where(file, "substeps") + " must hold whole numbers; got " + numberText(s));
    spec.substeps.push_back(int(std::clamp(s, -1.0, 1e6)));
  }
  spec.collect = kDefaultCollect;
  if (auto st = readStringList(j, file, "collect", &spec.collect); !st) return makeError(st.error());
  if (j.contains("error_metric")) {
    if (!j["error_metric"].is_string()) return makeError(where(file, "error_metric") + " must be a report field such as \"error.energy_rel_drift_max\"");
    spec.errorMetric = j["error_metric"].get<std::string>();
  }
  return spec;
}

Result<SweepSpec> readSpec(const std::string& path) {
  if (!fs::exists(path)) return makeError(path + ": no such file (a sweep spec is a .json or .lua file)");
  const std::string ext = fs::path(path).extension().string();
  const std::string base = fs::absolute(path).parent_path().string();
  json j;
  if (ext == ".lua") {
    auto r = readLuaSpec(path);
    if (!r) return makeError(r.error());
    j = std::move(r.value());
  } else if (ext == ".json") {
    auto text = readTextFile(path);
    if (!text) return makeError(text.error());
    try {
      j = json::parse(text.value());
    } catch (const json::parse_error& e) {
      return makeError(path + ": not valid JSON: " + e.what());
    }
  } else {
    return makeError(path + ": a sweep spec ends in .json or .lua");
  }
  return specFromJson(j, path, base);
}

std::size_t jobCount(const SweepSpec& spec) {
  // Saturating product, so a huge sweep is reported rather than overflowing.
  auto mul = [](std::size_t a, std::size_t b) { return b != 0 && a > SIZE_MAX / b ? SIZE_MAX : a * b; };
  std::size_t n = spec.scenarios.size();
  for (const auto& [key, values] : spec.grid) n = mul(n, values.size());
  if (spec.random.samples > 0) n = mul(n, std::size_t(spec.random.samples));
  n = mul(n, spec.seeds.size());
  n = mul(n, std::max<std::size_t>(1, spec.integrators.size()));
  n = mul(n, std::max<std::size_t>(1, spec.dts.size()));
  n = mul(n, std::max<std::size_t>(1, spec.substeps.size()));
  return n;
}

namespace {

// One key's value checked as the runtime would take it; "" when fine.
std::string checkSetting(const std::string& scenario, const script::ParamDecls& decls, const std::string& key,
                         const std::string& value) {
  if (key.rfind("physics.", 0) == 0) {
    if (key == "physics.joint_solver") {
      physics::JointSolverKind kind;
      return physics::parseJointSolver(value, &kind) ? "" : "--set " + key + "=" + value + ": expected lagrange or impulse";
    }
    physics::WorldSettings ws;
    auto st = app::applyPhysicsSetting(ws, key, value);
    return st ? "" : st.error();
  }
  if (key.rfind("terrain.", 0) == 0) {
    auto st = app::TerrainScene::checkSettings({{key, value}});
    return st ? "" : st.error();
  }
  if (key.rfind("tune.", 0) == 0)
    return key + ": a sweep takes scenario parameters (the scenario's params table), physics.* and terrain.* "
                 "settings; a tunable is declared while the scenario runs, so it cannot be checked before the sweep: "
                 "declare a scenario parameter that sets it";
  if (!decls)
    return scenario + " declares no parameters, so '" + key +
           "' cannot be checked before the sweep runs: add a params table to the scenario (docs/lua-api.md, Scenario.params)";
  auto st = script::checkParamValue(*decls, scenario, key, value);
  return st ? "" : st.error();
}

}  // namespace

Status validateSpec(const SweepSpec& spec, bool force) {
  std::vector<std::string> problems;
  const std::size_t n = jobCount(spec);
  if (n == 0) problems.push_back(spec.file + ": the sweep has no jobs");
  if (n > kMaxJobsWithoutForce && !force)
    problems.push_back(spec.file + ": the sweep has " + (n == SIZE_MAX ? std::string("more than 10^19") : std::to_string(n)) +
                       " jobs, more than " + std::to_string(kMaxJobsWithoutForce) +
                       "; check the grid, or pass --force to write it anyway");
  for (const std::string& integ : spec.integrators)
    if (auto m = physics::parseBodyIntegrator(integ); !m)
      problems.push_back(where(spec.file, "integrators") + ": " + m.error());
  for (double dt : spec.dts)
    if (!(dt > 0 && dt <= 1)) problems.push_back(where(spec.file, "dt") + ": " + numberText(dt) + " is not a time step in (0, 1] s");
  for (int s : spec.substeps)
    if (s < 1 || s > 1000) problems.push_back(where(spec.file, "substeps") + ": " + std::to_string(s) + " is not in 1..1000");
  for (const std::string& c : spec.collect) {
    bool known = std::any_of(std::begin(kReportFields), std::end(kReportFields), [&](const char* f) { return c == f; }) ||
                 std::any_of(std::begin(kReportPrefixes), std::end(kReportPrefixes), [&](const char* p) {
                   return c.size() > std::strlen(p) && c.rfind(p, 0) == 0;
                 });
    if (!known)
      problems.push_back(where(spec.file, "collect") + ": '" + c +
                         "' is not a number the run report has (e.g. error.energy_rel_drift_max, wall_seconds.total, "
                         "step_ms.median, params.NAME, expectations.NAME; docs in tools/sweep/README.md)");
  }
  if (std::find(spec.collect.begin(), spec.collect.end(), spec.errorMetric) == spec.collect.end())
    problems.push_back(where(spec.file, "error_metric") + ": '" + spec.errorMetric + "' must be one of the collected fields");
  std::set<std::string> keys;
  for (const auto& [k, v] : spec.grid) {
    if (!keys.insert(k).second) problems.push_back(spec.file + ": '" + k + "' is swept twice");
  }
  for (const auto& [k, r] : spec.random.ranges)
    if (!keys.insert(k).second) problems.push_back(spec.file + ": '" + k + "' is both in grid and random.ranges");
  for (const SetValue& f : spec.fixed)
    if (keys.count(f.key)) problems.push_back(spec.file + ": '" + f.key + "' is both swept and in set");
  for (const std::string& scenario : spec.scenarios) {
    app::SceneOptions options;
    options.scenarioRef = scenario;
    options.modDirs = spec.modDirs;
    auto decls = app::Scene::declaredParams(options);
    if (!decls) {
      problems.push_back(where(spec.file, "scenarios") + ": " + scenario + ": " + decls.error());
      continue;
    }
    auto check = [&](const std::string& key, const std::string& value) {
      if (std::string p = checkSetting(scenario, decls.value(), key, value); !p.empty()) problems.push_back(spec.file + ": " + p);
    };
    for (const auto& [key, values] : spec.grid)
      for (const std::string& v : values) check(key, v);
    for (const auto& [key, range] : spec.random.ranges) {
      check(key, numberText(range.first));
      check(key, numberText(range.second));
    }
    for (const SetValue& f : spec.fixed) check(f.key, f.text);
  }
  // The same message once (a bad key is reported for each of its values).
  std::vector<std::string> unique;
  for (const std::string& p : problems)
    if (std::find(unique.begin(), unique.end(), p) == unique.end()) unique.push_back(p);
  if (unique.empty()) return Ok{};
  std::string text;
  for (const std::string& p : unique) text += (text.empty() ? "" : "\n") + p;
  return makeError(text);
}

std::vector<std::string> sweptKeys(const SweepSpec& spec) {
  std::vector<std::string> keys;
  for (const auto& [k, v] : spec.grid)
    if (v.size() > 1) keys.push_back(k);
  for (const auto& [k, r] : spec.random.ranges) keys.push_back(k);
  if (spec.seeds.size() > 1) keys.push_back("seed");
  if (spec.integrators.size() > 1) keys.push_back("integrator");
  if (spec.dts.size() > 1) keys.push_back("dt");
  if (spec.substeps.size() > 1) keys.push_back("substeps");
  return keys;
}

std::vector<Job> expandJobs(const SweepSpec& spec) {
  // Design points: the grid's cross product, each combined with every random sample.
  std::vector<std::vector<SetValue>> points{{}};
  for (const auto& [key, values] : spec.grid) {
    std::vector<std::vector<SetValue>> next;
    for (const auto& p : points)
      for (const std::string& v : values) {
        next.push_back(p);
        next.back().push_back({key, v});
      }
    points = std::move(next);
  }
  if (spec.random.samples > 0) {
    std::uint64_t state = spec.random.seed;
    std::vector<std::vector<SetValue>> samples;
    for (int s = 0; s < spec.random.samples; ++s) {
      std::vector<SetValue> sample;
      for (const auto& [key, range] : spec.random.ranges) {
        // 53 random bits -> [0, 1): the same numbers on every machine.
        const double u = double(splitmix64(state) >> 11) * 0x1.0p-53;
        sample.push_back({key, numberText(range.first + (range.second - range.first) * u)});
      }
      samples.push_back(std::move(sample));
    }
    std::vector<std::vector<SetValue>> next;
    for (const auto& p : points)
      for (const auto& s : samples) {
        next.push_back(p);
        next.back().insert(next.back().end(), s.begin(), s.end());
      }
    points = std::move(next);
  }
  const std::vector<std::string> integrators = spec.integrators.empty() ? std::vector<std::string>{""} : spec.integrators;
  const std::vector<double> dts = spec.dts.empty() ? std::vector<double>{0} : spec.dts;
  const std::vector<int> substeps = spec.substeps.empty() ? std::vector<int>{0} : spec.substeps;
  std::vector<Job> jobs;
  const std::size_t total = jobCount(spec);
  const int width = std::max<int>(6, int(std::to_string(total).size()));
  for (const std::string& scenario : spec.scenarios)
    for (const auto& point : points)
      for (const std::string& integ : integrators)
        for (double dt : dts)
          for (int sub : substeps)
            for (std::uint64_t seed : spec.seeds) {
              Job job;
              char id[32];
              std::snprintf(id, sizeof id, "%0*zu", width, jobs.size());
              job.id = id;
              job.scenario = scenario;
              job.values = point;
              job.seed = seed;
              job.integrator = integ;
              job.dt_s = dt;
              job.substeps = sub;
              job.reportPath = "runs/" + job.id + "/report.json";
              auto& a = job.argv;
              a = {"tumble", "run", scenario};
              if (spec.steps > 0) a.insert(a.end(), {"--steps", std::to_string(spec.steps)});
              else if (spec.seconds > 0) a.insert(a.end(), {"--seconds", numberText(spec.seconds)});
              a.insert(a.end(), {"--seed", std::to_string(seed)});
              if (!integ.empty()) a.insert(a.end(), {"--integrator", integ});
              if (dt > 0) a.insert(a.end(), {"--dt", numberText(dt)});
              if (sub > 0) a.insert(a.end(), {"--substeps", std::to_string(sub)});
              for (const SetValue& f : spec.fixed) a.insert(a.end(), {"--set", f.key + "=" + f.text});
              for (const SetValue& v : point) a.insert(a.end(), {"--set", v.key + "=" + v.text});
              for (const std::string& m : spec.modDirs) a.insert(a.end(), {"--mods", m});
              a.insert(a.end(), {"--report", job.reportPath});
              jobs.push_back(std::move(job));
            }
  return jobs;
}

}  // namespace tumble::tools::sweep
