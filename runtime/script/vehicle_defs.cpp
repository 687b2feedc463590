#include "script/vehicle_defs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <stdexcept>

#include "script/internal/lua_util.h"
#include "script/lua_vm.h"

namespace tumble::script {
namespace {

namespace fs = std::filesystem;
using vehicle::Curve;
using vehicle::VehicleDef;

struct DefError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Reads the fields of one Lua table (at the top of the stack while alive),
/// remembering which keys it knew, so that finish() can refuse the rest.
class Fields {
 public:
  Fields(lua_State* L, std::string path) : m_L(L), m_path(std::move(path)) {
    if (!lua_istable(L, -1)) throw DefError(name("") + "expected a table");
  }
  std::string name(const char* key) const {
    std::string p = m_path.empty() ? key : (*key ? m_path + "." + key : m_path);
    return p.empty() ? "" : p + ": ";
  }
  std::string path(const char* key) const { return m_path.empty() ? key : m_path + "." + key; }

  /// Pushes the field; true if present (then the caller pops it).
  bool get(const char* key) {
    m_known.push_back(key);
    lua_getfield(m_L, -1, key);
    if (lua_isnil(m_L, -1)) {
      lua_pop(m_L, 1);
      return false;
    }
    return true;
  }
  void number(const char* key, Real* out, const char* unit) {
    if (!get(key)) return;
    if (!lua_isnumber(m_L, -1) || !std::isfinite(lua_tonumber(m_L, -1)))
      throw DefError(name(key) + "expected a finite number (" + unit + ")");
    *out = Real(lua_tonumber(m_L, -1));
    lua_pop(m_L, 1);
  }
  void boolean(const char* key, bool* out) {
    if (!get(key)) return;
    if (!lua_isboolean(m_L, -1)) throw DefError(name(key) + "expected true or false");
    *out = lua_toboolean(m_L, -1);
    lua_pop(m_L, 1);
  }
  void string(const char* key, std::string* out) {
    if (!get(key)) return;
    if (lua_type(m_L, -1) != LUA_TSTRING) throw DefError(name(key) + "expected a string");
    *out = lua_tostring(m_L, -1);
    lua_pop(m_L, 1);
  }
  void vec3(const char* key, Vec3* out, const char* unit) {
    if (!get(key)) return;
    std::vector<Real> v = list(key);
    if (v.size() != 3) throw DefError(name(key) + "expected three numbers {x, y, z} (" + unit + ")");
    *out = Vec3(v[0], v[1], v[2]);
    lua_pop(m_L, 1);
  }
  void numbers(const char* key, std::vector<Real>* out) {
    if (!get(key)) return;
    *out = list(key);
    lua_pop(m_L, 1);
  }
  void curve(const char* key, Curve* out, const char* xUnit, const char* yUnit) {
    if (!get(key)) return;
    const std::string form = std::string("expected a list of points {{x, y}, ...} with x in ") + xUnit +
                             " and y in " + yUnit;
    if (!lua_istable(m_L, -1)) throw DefError(name(key) + form);
    std::vector<std::pair<Real, Real>> pts;
    const lua_Integer n = luaL_len(m_L, -1);
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_geti(m_L, -1, i);
      if (!lua_istable(m_L, -1) || luaL_len(m_L, -1) != 2)
        throw DefError(name(key) + "point " + std::to_string(i) + ": " + form);
      lua_geti(m_L, -1, 1);
      lua_geti(m_L, -2, 2);
      if (!lua_isnumber(m_L, -1) || !lua_isnumber(m_L, -2))
        throw DefError(name(key) + "point " + std::to_string(i) + ": " + form);
      pts.emplace_back(Real(lua_tonumber(m_L, -2)), Real(lua_tonumber(m_L, -1)));
      lua_pop(m_L, 3);
    }
    *out = Curve(std::move(pts));
    lua_pop(m_L, 1);
  }
  /// Runs fn with the sub-table on top (if present).
  void table(const char* key, const std::function<void(Fields&)>& fn) {
    if (!get(key)) return;
    Fields sub(m_L, path(key));
    fn(sub);
    sub.finish();
    lua_pop(m_L, 1);
  }
  void finish() {
    lua_pushnil(m_L);
    while (lua_next(m_L, -2) != 0) {
      lua_pop(m_L, 1);
      std::string key = lua_type(m_L, -1) == LUA_TSTRING ? lua_tostring(m_L, -1) : "(a non-string key)";
      if (std::find(m_known.begin(), m_known.end(), key) == m_known.end()) {
        lua_pop(m_L, 1);
        std::string known;
        for (const auto& k : m_known) known += (known.empty() ? "" : ", ") + k;
        throw DefError(name(key.c_str()) + "unknown field; known here: " + known);
      }
    }
  }

 private:
  std::vector<Real> list(const char* key) {
    if (!lua_istable(m_L, -1)) throw DefError(name(key) + "expected a list of numbers");
    std::vector<Real> v;
    const lua_Integer n = luaL_len(m_L, -1);
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_geti(m_L, -1, i);
      if (!lua_isnumber(m_L, -1)) throw DefError(name(key) + "item " + std::to_string(i) + " is not a number");
      v.push_back(Real(lua_tonumber(m_L, -1)));
      lua_pop(m_L, 1);
    }
    return v;
  }
  lua_State* m_L;
  std::string m_path;
  std::vector<std::string> m_known;
};

void readAxle(Fields& f, vehicle::AxleDef& a) {
  f.vec3("position", &a.position_m, "m, left hub at full bump, chassis frame");
  f.number("radius", &a.wheelRadius_m, "m");
  f.number("width", &a.wheelWidth_m, "m");
  f.number("inertia", &a.wheelInertia_kgm2, "kg m^2");
  f.boolean("steered", &a.steered);
  f.boolean("driven", &a.driven);
  f.number("brake", &a.brakeTorque_Nm, "N m per wheel");
  f.number("handbrake", &a.handbrakeTorque_Nm, "N m per wheel");
  f.number("drive_share", &a.driveShare, "fraction 0..1");
  std::string diff = a.differential == vehicle::Differential::Open ? "open" : "limited_slip";
  f.string("differential", &diff);
  if (diff == "open") a.differential = vehicle::Differential::Open;
  else if (diff == "limited_slip") a.differential = vehicle::Differential::LimitedSlip;
  else throw DefError(f.name("differential") + "expected \"open\" or \"limited_slip\", got \"" + diff + "\"");
  f.number("lsd_bias", &a.lsdBias, "torque ratio >= 1");
  f.table("suspension", [&](Fields& s) {
    vehicle::SuspensionDef& d = a.suspension;
    s.number("travel", &d.travel_m, "m");
    s.number("rest_length", &d.restLength_m, "m");
    s.number("stiffness", &d.stiffness_Npm, "N/m");
    s.number("frequency", &d.frequency_hz, "Hz");
    s.number("bump", &d.bumpDamping_Nspm, "N s/m");
    s.number("rebound", &d.reboundDamping_Nspm, "N s/m");
    s.number("bump_ratio", &d.bumpRatio, "fraction of critical damping");
    s.number("rebound_ratio", &d.reboundRatio, "fraction of critical damping");
    s.number("anti_roll", &d.antiRoll_Npm, "N/m");
  });
}

void readDef(lua_State* L, VehicleDef& d) {
  Fields f(L, "");
  f.string("name", &d.name);
  f.string("description", &d.description);
  f.table("chassis", [&](Fields& c) {
    c.number("mass", &d.chassis.mass_kg, "kg");
    c.vec3("size", &d.chassis.size_m, "m, width height length");
    c.vec3("com", &d.chassis.centerOfMass_m, "m from the box centre");
    c.number("drag_area", &d.chassis.dragArea_m2, "m^2, Cd times frontal area");
    c.number("air_density", &d.chassis.airDensity_kgpm3, "kg/m^3");
    c.number("friction", &d.chassis.friction, "Coulomb coefficient");
    c.number("restitution", &d.chassis.restitution, "0..1");
    c.string("mesh", &d.chassis.mesh);
    std::string inertia = d.chassis.inertiaFromMesh ? "mesh" : "box";
    c.string("inertia", &inertia);
    if (inertia != "box" && inertia != "mesh")
      throw DefError("chassis.inertia: \"" + inertia + "\" is not \"box\" (a solid box of size and mass) or \"mesh\" "
                     "(the visual mesh as a uniform solid of the chassis mass)");
    if (inertia == "mesh" && d.chassis.mesh.empty())
      throw DefError("chassis.inertia: \"mesh\" needs chassis.mesh, the closed mesh to take the inertia from");
    d.chassis.inertiaFromMesh = inertia == "mesh";
    const fs::path mesh(d.chassis.mesh);
    if (!d.chassis.mesh.empty() && (mesh.is_absolute() || std::any_of(mesh.begin(), mesh.end(), [](const fs::path& part) {
                                      return part == "..";
                                    })))
      throw DefError("chassis.mesh: \"" + d.chassis.mesh + "\" leaves the mod's folder; give a path inside it, e.g. "
                     "\"assets/car.glb\"");
  });
  if (f.get("axles")) {
    if (!lua_istable(L, -1)) throw DefError("axles: expected a list of axle tables, front first");
    const lua_Integer n = luaL_len(L, -1);
    // Later axles start from the previous one, so a file need only say what differs.
    std::vector<vehicle::AxleDef> axles;
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_geti(L, -1, i);
      vehicle::AxleDef a = axles.empty() ? vehicle::AxleDef{} : axles.back();
      if (!axles.empty()) a.steered = a.driven = false, a.handbrakeTorque_Nm = 0, a.driveShare = 0;
      Fields af(L, "axles[" + std::to_string(i) + "]");
      readAxle(af, a);
      af.finish();
      axles.push_back(a);
      lua_pop(L, 1);
    }
    d.axles = std::move(axles);
    lua_pop(L, 1);
  }
  f.table("tyre", [&](Fields& t) {
    t.curve("longitudinal", &d.tyre.longitudinal, "slip ratio", "friction coefficient");
    t.curve("lateral", &d.tyre.lateral, "slip angle (rad)", "friction coefficient");
    t.number("rolling_resistance", &d.tyre.rollingResistance, "C_rr");
    t.number("soft_ground_drag", &d.tyre.softGroundDrag, "C_rr per unit of softness");
  });
  f.table("engine", [&](Fields& e) {
    e.curve("torque", &d.engine.torque, "rpm", "N m");
    e.number("idle_rpm", &d.engine.idleRpm, "rpm");
    e.number("max_rpm", &d.engine.maxRpm, "rpm");
    e.number("launch_rpm", &d.engine.launchRpm, "rpm");
    e.number("inertia", &d.engine.inertia_kgm2, "kg m^2");
    e.number("braking_torque", &d.engine.brakingTorque_Nm, "N m");
  });
  f.table("gearbox", [&](Fields& g) {
    g.numbers("ratios", &d.gearbox.ratios);
    g.number("reverse", &d.gearbox.reverseRatio, "ratio");
    g.number("final_drive", &d.gearbox.finalDrive, "ratio");
    g.number("efficiency", &d.gearbox.efficiency, "fraction");
    g.number("shift_up_rpm", &d.gearbox.shiftUpRpm, "rpm");
    g.number("shift_down_rpm", &d.gearbox.shiftDownRpm, "rpm");
    g.number("shift_time", &d.gearbox.shiftTime_s, "s");
  });
  f.table("steering", [&](Fields& s) {
    s.number("max_angle", &d.steering.maxAngle_rad, "rad");
    s.number("speed_sensitivity", &d.steering.speedSensitivity_spm, "s/m");
    s.number("rate", &d.steering.rate_radps, "rad/s");
  });
  f.finish();
}

void setNumber(lua_State* L, const char* key, double v) {
  lua_pushnumber(L, v);
  lua_setfield(L, -2, key);
}
void setVec3(lua_State* L, const char* key, const Vec3& v) {
  lua_createtable(L, 3, 0);
  for (int i = 0; i < 3; ++i) {
    lua_pushnumber(L, v[i]);
    lua_seti(L, -2, i + 1);
  }
  lua_setfield(L, -2, key);
}
void setCurve(lua_State* L, const char* key, const Curve& c) {
  lua_createtable(L, int(c.points().size()), 0);
  int i = 1;
  for (const auto& [x, y] : c.points()) {
    lua_createtable(L, 2, 0);
    lua_pushnumber(L, x);
    lua_seti(L, -2, 1);
    lua_pushnumber(L, y);
    lua_seti(L, -2, 2);
    lua_seti(L, -2, i++);
  }
  lua_setfield(L, -2, key);
}

}  // namespace

Result<VehicleDef> vehicleDefFromTable(lua_State* L, int idx, const std::string& where) {
  VehicleDef d;
  const int top = lua_gettop(L);
  lua_pushvalue(L, idx);
  try {
    readDef(L, d);
  } catch (const DefError& e) {
    lua_settop(L, top);
    return makeError(where + ": " + e.what());
  }
  lua_settop(L, top);
  if (auto s = vehicle::validateVehicleDef(d, where); !s) return makeError(s.error());
  return d;
}

void pushVehicleDef(lua_State* L, const VehicleDef& d) {
  lua_newtable(L);
  lua_pushstring(L, d.name.c_str());
  lua_setfield(L, -2, "name");
  lua_pushstring(L, d.description.c_str());
  lua_setfield(L, -2, "description");
  lua_newtable(L);
  setNumber(L, "mass", d.chassis.mass_kg);
  setVec3(L, "size", d.chassis.size_m);
  setVec3(L, "com", d.chassis.centerOfMass_m);
  setNumber(L, "drag_area", d.chassis.dragArea_m2);
  setNumber(L, "air_density", d.chassis.airDensity_kgpm3);
  setNumber(L, "friction", d.chassis.friction);
  setNumber(L, "restitution", d.chassis.restitution);
  if (!d.chassis.mesh.empty()) {
    lua_pushstring(L, d.chassis.mesh.c_str());
    lua_setfield(L, -2, "mesh");
  }
  lua_pushstring(L, d.chassis.inertiaFromMesh ? "mesh" : "box");
  lua_setfield(L, -2, "inertia");
  lua_setfield(L, -2, "chassis");
  lua_createtable(L, int(d.axles.size()), 0);
  for (std::size_t i = 0; i < d.axles.size(); ++i) {
    const vehicle::AxleDef& a = d.axles[i];
    lua_newtable(L);
    setVec3(L, "position", a.position_m);
    setNumber(L, "radius", a.wheelRadius_m);
    setNumber(L, "width", a.wheelWidth_m);
    setNumber(L, "inertia", a.wheelInertia_kgm2);
    lua_pushboolean(L, a.steered);
    lua_setfield(L, -2, "steered");
    lua_pushboolean(L, a.driven);
    lua_setfield(L, -2, "driven");
    setNumber(L, "brake", a.brakeTorque_Nm);
    setNumber(L, "handbrake", a.handbrakeTorque_Nm);
    setNumber(L, "drive_share", a.driveShare);
    lua_pushstring(L, a.differential == vehicle::Differential::Open ? "open" : "limited_slip");
    lua_setfield(L, -2, "differential");
    setNumber(L, "lsd_bias", a.lsdBias);
    const vehicle::SuspensionDef& s = a.suspension;
    lua_newtable(L);
    setNumber(L, "travel", s.travel_m);
    setNumber(L, "rest_length", s.restLength_m);
    setNumber(L, "stiffness", s.stiffness_Npm);
    setNumber(L, "frequency", s.frequency_hz);
    setNumber(L, "bump", s.bumpDamping_Nspm);
    setNumber(L, "rebound", s.reboundDamping_Nspm);
    setNumber(L, "bump_ratio", s.bumpRatio);
    setNumber(L, "rebound_ratio", s.reboundRatio);
    setNumber(L, "anti_roll", s.antiRoll_Npm);
    lua_setfield(L, -2, "suspension");
    lua_seti(L, -2, lua_Integer(i + 1));
  }
  lua_setfield(L, -2, "axles");
  lua_newtable(L);
  setCurve(L, "longitudinal", d.tyre.longitudinal);
  setCurve(L, "lateral", d.tyre.lateral);
  setNumber(L, "rolling_resistance", d.tyre.rollingResistance);
  setNumber(L, "soft_ground_drag", d.tyre.softGroundDrag);
  lua_setfield(L, -2, "tyre");
  lua_newtable(L);
  setCurve(L, "torque", d.engine.torque);
  setNumber(L, "idle_rpm", d.engine.idleRpm);
  setNumber(L, "max_rpm", d.engine.maxRpm);
  setNumber(L, "launch_rpm", d.engine.launchRpm);
  setNumber(L, "inertia", d.engine.inertia_kgm2);
  setNumber(L, "braking_torque", d.engine.brakingTorque_Nm);
  lua_setfield(L, -2, "engine");
  lua_newtable(L);
  lua_createtable(L, int(d.gearbox.ratios.size()), 0);
  for (std::size_t i = 0; i < d.gearbox.ratios.size(); ++i) {
    lua_pushnumber(L, d.gearbox.ratios[i]);
    lua_seti(L, -2, lua_Integer(i + 1));
  }
  lua_setfield(L, -2, "ratios");
  setNumber(L, "reverse", d.gearbox.reverseRatio);
  setNumber(L, "final_drive", d.gearbox.finalDrive);
  setNumber(L, "efficiency", d.gearbox.efficiency);
  setNumber(L, "shift_up_rpm", d.gearbox.shiftUpRpm);
  setNumber(L, "shift_down_rpm", d.gearbox.shiftDownRpm);
  setNumber(L, "shift_time", d.gearbox.shiftTime_s);
  lua_setfield(L, -2, "gearbox");
  lua_newtable(L);
  setNumber(L, "max_angle", d.steering.maxAngle_rad);
  setNumber(L, "speed_sensitivity", d.steering.speedSensitivity_spm);
  setNumber(L, "rate", d.steering.rate_radps);
  lua_setfield(L, -2, "steering");
}

Result<VehicleDef> loadVehicleFile(const ModInfo& mod, const std::string& name) {
  const std::string rel = "vehicles/" + name + ".lua";
  const std::string where = "mod " + mod.name + ": " + rel;
  const fs::path file = fs::path(mod.dir) / rel;
  if (!fs::exists(file)) {
    std::string known;
    for (const auto& v : ModRegistry::listLua(mod, "vehicles")) known += (known.empty() ? "" : ", ") + v;
    return makeError(where + ": no such vehicle (this mod has: " + (known.empty() ? "none" : known) + ")");
  }
  VmLimits limits;
  limits.memoryBytes = 16u << 20;
  limits.instructionsPerCall = 10'000'000;
  LuaVm vm(limits);
  lua_State* L = vm.state();
  if (luaL_loadfilex(L, file.c_str(), "t") != LUA_OK) {
    ScriptError e = LuaVm::parseError(mod.name, lua_tostring(L, -1), "");
    return makeError(e.summary());
  }
  // A vehicle file is data: its environment has only math.
  lua_newtable(L);
  lua_getglobal(L, "math");
  lua_setfield(L, -2, "math");
  lua_setupvalue(L, -2, 1);
  ScriptError err;
  if (!vm.call(0, 1, mod.name, rel, "top level", &err)) return makeError(err.summary());
  if (!lua_istable(L, -1)) return makeError(where + ": must return a table {chassis = {...}, axles = {...}, ...}");
  return vehicleDefFromTable(L, -1, where);
}

std::vector<ModProblem> checkVehicles(const ModInfo& mod) {
  std::vector<ModProblem> problems;
  for (const std::string& name : ModRegistry::listLua(mod, "vehicles")) {
    auto def = loadVehicleFile(mod, name);
    if (def) continue;
    // The message starts "mod M: vehicles/N.lua: "; the problem names the file itself.
    const std::string prefix = "mod " + mod.name + ": vehicles/" + name + ".lua: ";
    std::string message = def.error();
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
    problems.push_back({mod.dir + "/vehicles/" + name + ".lua", 0, message, mod.name});
  }
  return problems;
}

}  // namespace tumble::script
