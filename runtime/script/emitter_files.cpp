#include "script/sandbox.h"
#include "script/emitter_files.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <cstring>
#include <set>

#include "script/internal/emitter_table.h"
#include "script/internal/lua_util.h"
#include "script/lua_vm.h"

extern "C" {
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
}

namespace fs = std::filesystem;

namespace tumble::script {

namespace {

using particles::EmitterDef;

const std::vector<std::string> kFields = [] {
  std::vector<std::string> f = {"rate",  "bursts", "duration", "lifetime", "max_count", "shape", "box_size",
                                "radius", "cone_angle", "direction", "spread", "speed", "inherit_velocity",
                                "gravity", "acceleration", "drag", "spin", "size", "color", "alpha", "blend",
                                "space", "stretch", "description"};
  std::sort(f.begin(), f.end());
  return f;
}();

// Reads one table's fields; each reader pops what it pushed and records a
// problem instead of throwing, so every problem is found in one pass.
class Reader {
 public:
  Reader(lua_State* L, int t, std::vector<std::string>& problems) : m_L(L), m_t(lua_absindex(L, t)), m_problems(problems) {}

  void problem(const std::string& field, const std::string& text) {
    m_problems.push_back("field '" + field + "': " + text);
  }

  // Pushes the field; false (nothing pushed) when absent.
  bool get(const char* key) {
    if (rawGetField(m_L, m_t, key) == LUA_TNIL) {
      lua_pop(m_L, 1);
      return false;
    }
    return true;
  }

  std::string typeName(int idx) { return luaL_typename(m_L, idx); }

  bool toNumber(int idx, double* out) {
    int isnum = 0;
    double v = lua_tonumberx(m_L, idx, &isnum);
    if (!isnum || !std::isfinite(v)) return false;
    *out = v;
    return true;
  }

  void number(const char* key, float* out, const char* expected) {
    if (!get(key)) return;
    double v;
    if (toNumber(-1, &v)) *out = float(v);
    else problem(key, "expected " + std::string(expected) + ", got " + typeName(-1));
    lua_pop(m_L, 1);
  }

  void integer(const char* key, int* out, const char* expected) {
    if (!get(key)) return;
    if (lua_isinteger(m_L, -1) && lua_tointeger(m_L, -1) >= 0 && lua_tointeger(m_L, -1) <= (1ll << 30))
      *out = int(lua_tointeger(m_L, -1));
    else problem(key, "expected " + std::string(expected) + ", got " + (lua_isnumber(m_L, -1) ? std::string(lua_tostring(m_L, -1)) : typeName(-1)));
    lua_pop(m_L, 1);
  }

  // A number or {min, max}.
  void range(const char* key, float* lo, float* hi, const char* unit) {
    if (!get(key)) return;
    double a, b;
    if (toNumber(-1, &a)) {
      *lo = *hi = float(a);
    } else if (lua_istable(m_L, -1) && lua_rawlen(m_L, -1) == 2) {
      lua_rawgeti(m_L, -1, 1);
      lua_rawgeti(m_L, -2, 2);
      if (toNumber(-2, &a) && toNumber(-1, &b)) *lo = float(a), *hi = float(b);
      else problem(key, std::string("expected {min, max} in ") + unit + ", both numbers");
      lua_pop(m_L, 2);
    } else {
      problem(key, std::string("expected a number or {min, max} in ") + unit + ", got " + typeName(-1));
    }
    lua_pop(m_L, 1);
  }

  bool vec3At(int idx, Eigen::Vector3f* out) {
    idx = lua_absindex(m_L, idx);
    if (!lua_istable(m_L, idx)) return false;
    static const char* names[3] = {"x", "y", "z"};
    Eigen::Vector3f v;
    for (int i = 0; i < 3; ++i) {
      if (lua_rawgeti(m_L, idx, i + 1) == LUA_TNIL) {
        lua_pop(m_L, 1);
        rawGetField(m_L, idx, names[i]);
      }
      double c;
      bool ok = toNumber(-1, &c);
      lua_pop(m_L, 1);
      if (!ok) return false;
      v[i] = float(c);
    }
    *out = v;
    return true;
  }

  void vec3(const char* key, Eigen::Vector3f* out, const char* unit) {
    if (!get(key)) return;
    if (!vec3At(-1, out)) problem(key, std::string("expected a vector {x, y, z} in ") + unit + ", got " + typeName(-1));
    lua_pop(m_L, 1);
  }

  template <typename E>
  void choice(const char* key, E* out, std::initializer_list<std::pair<const char*, E>> options) {
    if (!get(key)) return;
    std::string valid;
    for (const auto& [name, value] : options) valid += (valid.empty() ? "\"" : ", \"") + std::string(name) + "\"";
    if (lua_type(m_L, -1) == LUA_TSTRING) {
      std::string s = lua_tostring(m_L, -1);
      bool found = false;
      for (const auto& [name, value] : options)
        if (s == name) *out = value, found = true;
      if (!found) problem(key, "\"" + s + "\" is not one of " + valid);
    } else {
      problem(key, "expected one of " + valid + ", got " + typeName(-1));
    }
    lua_pop(m_L, 1);
  }

  void bursts(std::vector<particles::Burst>* out) {
    if (!get("bursts")) return;
    const char* form = "expected a list like {{time = 0, count = 30}, ...} (time in s after spawn, count >= 0)";
    if (!lua_istable(m_L, -1)) {
      problem("bursts", std::string(form) + ", got " + typeName(-1));
      lua_pop(m_L, 1);
      return;
    }
    out->clear();
    const lua_Integer n = lua_Integer(lua_rawlen(m_L, -1));
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_rawgeti(m_L, -1, i);
      particles::Burst b;
      double t = -1;
      bool ok = lua_istable(m_L, -1);
      if (ok) {
        rawGetField(m_L, -1, "time");
        ok = toNumber(-1, &t);
        rawGetField(m_L, -2, "count");
        ok = ok && lua_isinteger(m_L, -1);
        if (ok) b.count = int(std::clamp<lua_Integer>(lua_tointeger(m_L, -1), -1, 1 << 30));
        lua_pop(m_L, 2);
      }
      if (ok) {
        b.time_s = float(t);
        out->push_back(b);
      } else {
        problem("bursts", "entry " + std::to_string(i) + ": " + form);
      }
      lua_pop(m_L, 1);
    }
    lua_pop(m_L, 1);
  }

  // A number (constant) or {{t, value}, ...}.
  void curve1(const char* key, particles::Curve1* out, const char* unit) {
    if (!get(key)) return;
    double v;
    const std::string form = std::string("expected a number (") + unit + ") or keys over life {{t, value}, ...} with t 0..1";
    if (toNumber(-1, &v)) {
      *out = particles::Curve1::constant(float(v));
    } else if (lua_istable(m_L, -1) && lua_rawlen(m_L, -1) > 0) {
      particles::Curve1 c;
      const lua_Integer n = lua_Integer(lua_rawlen(m_L, -1));
      bool ok = true;
      for (lua_Integer i = 1; i <= n && ok; ++i) {
        lua_rawgeti(m_L, -1, i);
        double t, value;
        ok = lua_istable(m_L, -1) && lua_rawlen(m_L, -1) == 2;
        if (ok) {
          lua_rawgeti(m_L, -1, 1);
          lua_rawgeti(m_L, -2, 2);
          ok = toNumber(-2, &t) && toNumber(-1, &value);
          lua_pop(m_L, 2);
        }
        if (ok) c.keys.push_back({float(t), float(value)});
        else problem(key, "key " + std::to_string(i) + ": " + form);
        lua_pop(m_L, 1);
      }
      if (ok) *out = c;
    } else {
      problem(key, form + ", got " + typeName(-1));
    }
    lua_pop(m_L, 1);
  }

  // {r, g, b} (constant) or {{t, {r, g, b}}, ...}.
  void curve3(const char* key, particles::Curve3* out) {
    if (!get(key)) return;
    const std::string form = "expected a colour {r, g, b} (linear 0..1) or keys over life {{t, {r, g, b}}, ...} with t 0..1";
    Eigen::Vector3f rgb;
    bool listOfKeys = false;
    if (lua_istable(m_L, -1)) {
      listOfKeys = lua_rawgeti(m_L, -1, 1) == LUA_TTABLE;
      lua_pop(m_L, 1);
    }
    if (!listOfKeys && vec3At(-1, &rgb)) {
      *out = particles::Curve3::constant(rgb);
    } else if (listOfKeys) {
      particles::Curve3 c;
      const lua_Integer n = lua_Integer(lua_rawlen(m_L, -1));
      bool ok = true;
      for (lua_Integer i = 1; i <= n && ok; ++i) {
        lua_rawgeti(m_L, -1, i);
        double t;
        ok = lua_istable(m_L, -1) && lua_rawlen(m_L, -1) == 2;
        if (ok) {
          lua_rawgeti(m_L, -1, 1);
          lua_rawgeti(m_L, -2, 2);
          ok = toNumber(-2, &t) && vec3At(-1, &rgb);
          lua_pop(m_L, 2);
        }
        if (ok) c.keys.push_back({float(t), rgb});
        else problem(key, "key " + std::to_string(i) + ": " + form);
        lua_pop(m_L, 1);
      }
      if (ok) *out = c;
    } else {
      problem(key, form + ", got " + typeName(-1));
    }
    lua_pop(m_L, 1);
  }

  void unknownFields() {
    lua_pushnil(m_L);
    while (lua_next(m_L, m_t) != 0) {
      lua_pop(m_L, 1);
      if (lua_type(m_L, -1) != LUA_TSTRING) {
        m_problems.push_back("fields must be named (key = value); found a value at a " +
                             std::string(luaL_typename(m_L, -1)) + " key");
        continue;
      }
      std::string key = lua_tostring(m_L, -1);
      if (!std::binary_search(kFields.begin(), kFields.end(), key))
        m_problems.push_back(unknownFieldMessage(key, std::set<std::string>(kFields.begin(), kFields.end())));
    }
  }

 private:
  lua_State* m_L;
  int m_t;
  std::vector<std::string>& m_problems;
};

// The line of the field a problem names ("field 'x': ..." or "unknown field 'x' ...").
int lineFromProblem(const std::string& path, const std::string& problem) {
  for (const char* prefix : {"field '", "unknown field '"}) {
    if (problem.rfind(prefix, 0) != 0) continue;
    const std::size_t begin = std::strlen(prefix), end = problem.find('\'', begin);
    if (end != std::string::npos) return lineOfField(path, problem.substr(begin, end - begin));
  }
  return 0;
}

}  // namespace

const std::vector<std::string>& emitterFieldNames() { return kFields; }

void readEmitterTable(lua_State* L, int idx, EmitterDef& d, std::vector<std::string>& problems) {
  using particles::BlendMode;
  using particles::EmitterShape;
  using particles::SimSpace;
  const std::size_t before = problems.size();
  Reader r(L, idx, problems);
  r.unknownFields();
  r.number("rate", &d.rate_per_s, "particles per second (a number >= 0)");
  r.bursts(&d.bursts);
  r.number("duration", &d.duration_s, "seconds >= 0 (0: until stopped)");
  r.range("lifetime", &d.lifetimeMin_s, &d.lifetimeMax_s, "seconds");
  r.integer("max_count", &d.maxCount, "an integer count of particles >= 1");
  r.choice<EmitterShape>("shape", &d.shape, {{"point", EmitterShape::Point}, {"box", EmitterShape::Box},
                                            {"sphere", EmitterShape::Sphere}, {"cone", EmitterShape::Cone}});
  r.vec3("box_size", &d.boxSize_m, "metres");
  r.number("radius", &d.radius_m, "metres >= 0");
  r.number("cone_angle", &d.coneAngle_rad, "radians 0..pi/2, e.g. math.rad(20)");
  r.vec3("direction", &d.direction, "the emitter's frame");
  r.number("spread", &d.spread_rad, "radians 0..pi, e.g. math.rad(15)");
  r.range("speed", &d.speedMin_mps, &d.speedMax_mps, "m/s");
  r.number("inherit_velocity", &d.inheritVelocity, "a share 0..1 of the emitter's velocity");
  r.number("gravity", &d.gravityScale, "a multiple of the world's gravity (1: falls, -0.1: rises slowly)");
  r.vec3("acceleration", &d.acceleration_mps2, "m/s^2");
  r.number("drag", &d.drag_per_s, "1/s >= 0");
  r.range("spin", &d.spinMin_radps, &d.spinMax_radps, "rad/s");
  r.curve1("size", &d.size_m, "billboard width, m");
  r.curve3("color", &d.color);
  r.curve1("alpha", &d.alpha, "opacity 0..1");
  r.number("stretch", &d.stretch_s, "seconds >= 0 (streak length = speed x stretch; 0: round)");
  r.choice<BlendMode>("blend", &d.blend, {{"alpha", BlendMode::Alpha}, {"additive", BlendMode::Additive}});
  r.choice<SimSpace>("space", &d.space, {{"world", SimSpace::World}, {"local", SimSpace::Local}});
  if (rawGetField(L, lua_absindex(L, idx), "description"), !lua_isnil(L, -1) && lua_type(L, -1) != LUA_TSTRING)
    problems.push_back("field 'description': expected a string");
  lua_pop(L, 1);
  // Ranges and consistency, once the types are right.
  if (problems.size() == before)
    if (Status s = particles::validate(d); !s) problems.push_back(s.error());
}

bool runEmitterChunk(LuaVm& vm, const std::string& path, const std::string& modName, std::string* error, int* line) {
  lua_State* L = vm.state();
  *line = 0;
  if (LuaVm::loadFile(L, std::string(path.c_str())) != LUA_OK) {
    ScriptError e = LuaVm::parseError(modName, lua_tostring(L, -1), "");
    lua_pop(L, 1);
    *error = e.message;
    *line = e.line;
    return false;
  }
  // A data chunk: its own copies of math, string and table; no world, no io.
  pushDataEnvironment(L);  // private math, string and table: data, no world
  lua_setupvalue(L, -2, 1);
  ScriptError err;
  if (!vm.call(0, 1, modName, fs::path(path).filename().string(), "top level", &err)) {
    *error = err.message;
    *line = err.line;
    return false;
  }
  if (!lua_istable(L, -1)) {
    *error = std::string("must return a table of emitter fields, e.g. return {rate = 20, lifetime = 1}; got ") +
             luaL_typename(L, -1);
    lua_pop(L, 1);
    return false;
  }
  return true;
}

int lineOfField(const std::string& path, const std::string& field) {
  if (field.empty()) return 0;
  auto isWord = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  // `field` at the start of a word, then optional blanks and '='.
  auto assigns = [&](const std::string& line) {
    for (std::size_t at = line.find(field); at != std::string::npos; at = line.find(field, at + 1)) {
      if (at > 0 && isWord(line[at - 1])) continue;
      std::size_t i = at + field.size();
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i < line.size() && line[i] == '=' && (i + 1 == line.size() || line[i + 1] != '=')) return true;
    }
    return false;
  };
  std::ifstream in(path);
  std::string text;
  for (int n = 1; std::getline(in, text); ++n)
    if (assigns(text)) return n;
  return 0;
}

std::vector<ModProblem> checkEmitterFile(const std::string& path, const std::string& modName) {
  std::vector<ModProblem> out;
  LuaVm vm(VmLimits{8u << 20, 1'000'000});
  std::string error;
  int line = 0;
  if (!runEmitterChunk(vm, path, modName, &error, &line)) {
    out.push_back({path, line, error, modName});
    return out;
  }
  particles::EmitterDef def;
  std::vector<std::string> problems;
  readEmitterTable(vm.state(), -1, def, problems);
  for (const std::string& p : problems) out.push_back({path, lineFromProblem(path, p), p, modName});
  return out;
}

Result<particles::EmitterDef> loadEmitterFile(const std::string& path, const std::string& modName) {
  std::vector<ModProblem> problems;
  LuaVm vm(VmLimits{8u << 20, 1'000'000});
  std::string error;
  int line = 0;
  if (!runEmitterChunk(vm, path, modName, &error, &line)) return makeError(ModProblem{path, line, error, modName}.text());
  particles::EmitterDef def;
  std::vector<std::string> found;
  readEmitterTable(vm.state(), -1, def, found);
  if (found.empty()) return def;
  std::string msg;
  for (const std::string& p : found) {
    if (!msg.empty()) msg += '\n';
    msg += ModProblem{path, lineFromProblem(path, p), p, modName}.text();
  }
  return makeError(msg);
}

}  // namespace tumble::script
