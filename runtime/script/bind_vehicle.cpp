// Lua module `vehicle` and type Vehicle: wheeled vehicles from mods'
// vehicles/*.lua (script/vehicle_defs.h), driven by Lua controllers at the
// fixed rate; the wheel physics runs in C++ in every substep
// (vehicle/vehicle_system.h).
//
//   local car = vehicle.spawn("base:hatchback", {position = {0, 0, 0}, heading = 0})
//   car:set_controls{throttle = 1, steer = -0.3}
//   print(car:speed(), car:rpm(), car:telemetry().wheels[1].slip_ratio)
#include <cstring>
#include <filesystem>
#include <map>


#include "physics/mass_properties.h"
#include "audio/clip.h"
#include "script/internal/bind_common.h"
#include "script/vehicle_defs.h"
#include "vehicle/vehicle_system.h"

namespace tumble::script {
namespace {

constexpr const char* kVehicleMeta = "tumble.Vehicle";

struct VehicleRef {
  std::uint32_t index, generation;
  float spawn[3];  ///< ground point it was spawned at (m), for reset()
  float heading;   ///< rad
  char name[96];   ///< "mod:vehicle"
};

VehicleRef* refOf(lua_State* L, int idx) {
  auto* ref = static_cast<VehicleRef*>(luaL_testudata(L, idx, kVehicleMeta));
  if (!ref) throw LuaArgError(std::string("expected a Vehicle, got ") + luaL_typename(L, idx));
  return ref;
}

vehicle::VehicleId checkVehicle(lua_State* L, int idx) {
  VehicleRef* ref = refOf(L, idx);
  vehicle::VehicleId id{ref->index, ref->generation};
  vehicle::VehicleSystem* sys = ScenarioHost::from(L)->scene().vehiclesIfAny();
  if (!sys || !sys->isValid(id)) throw LuaArgError("this Vehicle was removed; check car:is_valid() before using it");
  return id;
}

vehicle::VehicleSystem& systemOf(lua_State* L) { return ScenarioHost::from(L)->scene().vehicles(); }

/// The definition of "mod:name" (or "name": base), loaded once per run.
// chassis.inertia = "mesh": the chassis mesh as a uniform solid scaled to the
// chassis mass; its inertia diagonal along the chassis axes (the products of
// inertia of a left-right symmetric car are small and left out).
Vec3 meshInertia(ScenarioHost& host, const ModInfo& mod, const vehicle::VehicleDef& def, const std::string& ref) {
  const std::string where = "vehicle \"" + ref + "\": chassis.inertia = \"mesh\": ";
  const std::string file = (std::filesystem::path(mod.dir) / def.chassis.mesh).string();
  auto mesh = host.scene().modelTriangles(file);
  if (!mesh) throw LuaArgError(where + mesh.error());
  if (!physics::isClosedMesh(mesh->vertices_m, mesh->triangles))
    throw LuaArgError(where + file + " is not one closed surface; the inertia needs a closed mesh");
  const physics::MassProperties p = physics::massPropertiesOfMesh(mesh->vertices_m, mesh->triangles, 1);
  if (!p.valid) throw LuaArgError(where + file + " encloses no volume");
  return p.inertia_kgm2.diagonal() * (def.chassis.mass_kg / p.mass_kg);
}

const vehicle::VehicleDef& definition(lua_State* L, const std::string& ref) {
  ScenarioHost& host = *ScenarioHost::from(L);
  auto& cache = host.vehicleDefCache();
  if (auto it = cache.find(ref); it != cache.end()) return it->second;
  auto parsed = parseScenarioRef(ref);
  if (!parsed) throw LuaArgError("vehicle \"" + ref + "\": expected \"mod:vehicle\", e.g. \"base:hatchback\"");
  const auto& [modName, name] = parsed.value();
  const ModInfo* mod = nullptr;
  if (modName == host.mod().name) mod = &host.mod();
  for (const ModInfo& m : host.options().mods)
    if (!mod && m.name == modName) mod = &m;
  if (!mod) throw LuaArgError("vehicle \"" + ref + "\": no mod named \"" + modName + "\" is loaded");
  auto def = loadVehicleFile(*mod, name);
  if (!def) throw LuaArgError(def.error());
  if (def->chassis.inertiaFromMesh) def->chassis.inertia_kgm2 = meshInertia(host, *mod, *def, ref);
  if (!def->sound.engineSample.empty()) {  // checked now: a broken sample is an error at spawn, not silence
    const std::string file = (std::filesystem::path(mod->dir) / def->sound.engineSample).string();
    if (auto clip = audio::loadClip(file); !clip)
      throw LuaArgError("vehicle \"" + ref + "\": sound.engine_sample: " + clip.error());
    def->sound.engineSamplePath = file;
  }
  return cache.emplace(ref, std::move(def.value())).first->second;
}

/// @module vehicle
/// Wheeled vehicles. Definitions live in mods/<mod>/vehicles/<name>.lua
/// (docs/vehicles.md lists every field with its unit); controllers (an
/// automatic gearbox, traction control, an autopilot, the player) are Lua
/// in scripts/tumble/drive.lua and run at the fixed rate; suspension, tyres
/// and drivetrain run in C++ in every physics substep.

/// @class VehicleSpawn
/// @field position? Vec3Arg the ground point under the vehicle's centre, m (default {0, 0, 0}); the vehicle is placed resting on its springs
/// @field heading? number yaw, rad: 0 faces +Z, positive turns towards +X (default 0)

/// @function vehicle.spawn
/// Creates a vehicle from a definition file.
/// @param name string "mod:vehicle", e.g. "base:hatchback"
/// @param opts? VehicleSpawn where and which way
/// @return Vehicle the new vehicle
/// @example local car = vehicle.spawn("base:buggy", {position = {0, 0, 10}, heading = math.pi / 2})
int vehicleSpawn(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING)
    throw LuaArgError("vehicle.spawn: expected a name like \"base:hatchback\" as the first argument");
  const std::string name = lua_tostring(L, 1);
  Vec3 position = Vec3::Zero();
  double heading = 0;
  if (lua_istable(L, 2)) {
    try {
      optVec3Field(L, 2, "position", &position);
      heading = optNumberField(L, 2, "heading", 0);
    } catch (const LuaArgError& e) {
      throw LuaArgError(std::string("vehicle.spawn: ") + e.what());
    }
  } else if (!lua_isnoneornil(L, 2)) {
    throw LuaArgError("vehicle.spawn: the second argument must be a table {position = {x, y, z}, heading = rad}");
  }
  const vehicle::VehicleDef& def = definition(L, name);
  ScenarioHost::from(L)->countBodiesCreated(1, "vehicle.spawn");
  auto id = systemOf(L).spawn(def, position, Real(heading), name);
  if (!id) throw LuaArgError("vehicle.spawn: " + id.error());
  auto* ref = static_cast<VehicleRef*>(lua_newuserdatauv(L, sizeof(VehicleRef), 0));
  ref->index = id.value().index;
  ref->generation = id.value().generation;
  for (int i = 0; i < 3; ++i) ref->spawn[i] = float(position[i]);
  ref->heading = float(heading);
  std::snprintf(ref->name, sizeof ref->name, "%s", name.c_str());
  luaL_setmetatable(L, kVehicleMeta);
  ScenarioHost::from(L)->presentation().setColor(systemOf(L).chassis(id.value()), Eigen::Vector3f(0.8f, 0.25f, 0.2f));
  return 1;
}

// The VehicleDefinition classes of the reference come from the field tables
// (vehicle_defs.cpp, vehicleDefinitionDocBlocks).

/// @function vehicle.definition
/// The definition of a vehicle as a table in the file's format (every
/// field filled in), e.g. to read its parameters or to tune a copy.
/// @param name string "mod:vehicle"
/// @return VehicleDefinition the definition
int vehicleDefinition(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) throw LuaArgError("vehicle.definition: expected a name like \"base:hatchback\"");
  pushVehicleDef(L, definition(L, lua_tostring(L, 1)));
  return 1;
}

/// @function vehicle.surface
/// The terrain under (x, z): its height, its friction (the drag map:
/// mud 0.3, grass 0.6, rock 0.8) and its softness (the softness layer:
/// mud 0.7, grass 0.4, rock 0; rolling drag, see docs/vehicles.md).
/// Nothing when there is no terrain there.
/// @param x number m
/// @param z number m
/// @return number? height, m
/// @return number? friction coefficient
/// @return number? softness, unitless (0 hard)
int vehicleSurface(lua_State* L) {
  const double x = checkNumber(L, 1, "x"), z = checkNumber(L, 2, "z");
  const physics::HeightField* field = ScenarioHost::from(L)->world().heightField();
  Real h;
  Vec3 n;
  if (!field || !field->surfaceAt(Real(x), Real(z), &h, &n)) return 0;
  lua_pushnumber(L, h);
  lua_pushnumber(L, field->frictionAt(Real(x), Real(z)));
  const auto* soft = dynamic_cast<const vehicle::GroundSoftness*>(field);
  lua_pushnumber(L, soft ? soft->softnessAt(Real(x), Real(z)) : 0);
  return 3;
}

/// @function vehicle.set_softness
/// Makes a body's surface soft ground for tyres (a static box of mud, a
/// sand pit): rolling drag tyre.soft_ground_drag times the softness on top
/// of the tyre's rolling resistance. Bodies are hard (0) until set. The
/// body's friction stays what it is: set both for mud (friction 0.3,
/// softness 0.7); ice is a low friction with softness 0.
/// @param body Body the surface
/// @param softness number unitless, >= 0 (0 hard, 0.4 grass, 0.7 mud)
/// @example local pit = world.box{size = {6, 1, 20}, position = {0, -0.5, 30}, type = "static", friction = 0.3}
/// vehicle.set_softness(pit, 0.7)
int vehicleSetSoftness(lua_State* L) {
  const physics::BodyId body = checkBody(L, 1);
  const double s = checkNumber(L, 2, "softness");
  if (!systemOf(L).setSurfaceSoftness(body, Real(s)))
    throw LuaArgError("vehicle.set_softness: softness must be a finite number >= 0 (0 hard, 0.4 grass, 0.7 mud), got " +
                      std::to_string(s));
  return 0;
}

/// @class Vehicle
/// A handle to a vehicle made by vehicle.spawn. Methods refuse a removed
/// vehicle with a clear error.

/// @class VehicleControls
/// @field throttle? number 0..1
/// @field brake? number 0..1
/// @field steer? number -1 full left .. +1 full right
/// @field handbrake? number 0..1
/// @field gear? integer -1 reverse, 0 neutral, 1..N (clamped to the gearbox)

/// @function Vehicle:set_controls
/// Sets what the driver asks for; absent fields keep their value.
/// @param controls VehicleControls
/// @example car:set_controls{throttle = 0.8, steer = 0.2}
int vSetControls(lua_State* L) {
  const vehicle::VehicleId id = checkVehicle(L, 1);
  if (!lua_istable(L, 2)) throw LuaArgError("Vehicle:set_controls: expected a table {throttle=, brake=, steer=, ...}");
  vehicle::VehicleControls c = systemOf(L).controls(id);
  const char* fn = "Vehicle:set_controls";
  checkFields(L, 2, fn, {"throttle", "brake", "steer", "handbrake", "gear"});
  try {
    c.throttle = Real(optNumberField(L, 2, "throttle", c.throttle));
    c.brake = Real(optNumberField(L, 2, "brake", c.brake));
    c.steer = Real(optNumberField(L, 2, "steer", c.steer));
    c.handbrake = Real(optNumberField(L, 2, "handbrake", c.handbrake));
    c.gear = int(std::lround(optNumberField(L, 2, "gear", c.gear)));
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  systemOf(L).setControls(id, c);
  return 0;
}

/// @function Vehicle:controls
/// @return VehicleControls what the driver asks for now (clamped)
int vControls(lua_State* L) {
  const vehicle::VehicleControls& c = systemOf(L).controls(checkVehicle(L, 1));
  lua_createtable(L, 0, 5);
  lua_pushnumber(L, c.throttle);
  rawSetField(L, -2, "throttle");
  lua_pushnumber(L, c.brake);
  rawSetField(L, -2, "brake");
  lua_pushnumber(L, c.steer);
  rawSetField(L, -2, "steer");
  lua_pushnumber(L, c.handbrake);
  rawSetField(L, -2, "handbrake");
  lua_pushinteger(L, c.gear);
  rawSetField(L, -2, "gear");
  return 1;
}

/// @function Vehicle:speed
/// @return number speed along the vehicle's forward axis, m/s (negative backwards)
int vSpeed(lua_State* L) {
  lua_pushnumber(L, systemOf(L).telemetry(checkVehicle(L, 1)).speed_mps);
  return 1;
}

/// @function Vehicle:rpm
/// @return number engine speed, rpm
int vRpm(lua_State* L) {
  lua_pushnumber(L, systemOf(L).telemetry(checkVehicle(L, 1)).rpm);
  return 1;
}

/// @function Vehicle:gear
/// @return integer the gear engaged (-1 reverse, 0 neutral, 1..N)
/// @return integer the number of forward gears
int vGear(lua_State* L) {
  const vehicle::VehicleId id = checkVehicle(L, 1);
  lua_pushinteger(L, systemOf(L).telemetry(id).gear);
  lua_pushinteger(L, lua_Integer(systemOf(L).def(id).gearbox.ratios.size()));
  return 2;
}

/// @class WheelTelemetry
/// @field contact boolean the tyre touches something
/// @field load number suspension force on the tyre, N
/// @field slip_ratio number (w r - v) / max(|v|, 0.5 m/s); > 0 spinning, < 0 locking
/// @field slip_angle number rad, signed
/// @field slip_speed number speed of the contact patch over the ground, m/s (dust)
/// @field surface_friction number friction of what the tyre touches (terrain drag map or body)
/// @field surface_softness number softness of what the tyre touches, unitless (terrain softness layer or vehicle.set_softness; 0 hard, 0.4 grass, 0.7 mud)
/// @field spin number wheel angular velocity, rad/s (+ rolling forward)
/// @field drive_torque number torque the differential gives this wheel, N m (mean over the last step; 0 on an undriven axle). Open: the same on both wheels of an axle; limited slip: up to lsd_bias times the other's
/// @field steer number steering angle, rad (+ to the left)
/// @field spring_length number hub below full bump, m (0..travel)
/// @field static_length number spring length at rest on level ground (rest_length minus the static sag), m
/// @field position Vec3 hub, world, m
/// @field radius number m

/// @class VehicleTelemetry
/// @field speed number m/s along the forward axis
/// @field rpm number engine, rpm
/// @field gear integer engaged gear
/// @field shifting boolean clutch open for a gear change
/// @field engine_torque number at the crank, N m (negative: engine braking)
/// @field drive_torque number at the wheels, N m, total
/// @field wheels WheelTelemetry[] axle by axle, left then right

/// @function Vehicle:telemetry
/// @return VehicleTelemetry the state after the last step
int vTelemetry(lua_State* L) {
  const vehicle::VehicleId id = checkVehicle(L, 1);
  const vehicle::VehicleSystem& s = systemOf(L);
  const vehicle::VehicleTelemetry& t = s.telemetry(id);
  lua_createtable(L, 0, 7);
  lua_pushnumber(L, t.speed_mps);
  rawSetField(L, -2, "speed");
  lua_pushnumber(L, t.rpm);
  rawSetField(L, -2, "rpm");
  lua_pushinteger(L, t.gear);
  rawSetField(L, -2, "gear");
  lua_pushboolean(L, t.shifting);
  rawSetField(L, -2, "shifting");
  lua_pushnumber(L, t.engineTorque_Nm);
  rawSetField(L, -2, "engine_torque");
  lua_pushnumber(L, t.driveTorque_Nm);
  rawSetField(L, -2, "drive_torque");
  lua_createtable(L, s.wheelCount(id), 0);
  for (int i = 0; i < s.wheelCount(id); ++i) {
    const vehicle::WheelTelemetry& w = s.wheel(id, i);
    lua_createtable(L, 0, 14);
    lua_pushboolean(L, w.contact);
    rawSetField(L, -2, "contact");
    const std::pair<const char*, Real> numbers[] = {
        {"load", w.load_N},       {"slip_ratio", w.slipRatio},         {"slip_angle", w.slipAngle_rad},
        {"slip_speed", w.slipSpeed_mps}, {"surface_friction", w.surfaceFriction},
        {"surface_softness", w.surfaceSoftness}, {"spin", w.spin_radps},
        {"drive_torque", w.driveTorque_Nm},
        {"steer", w.steer_rad},   {"spring_length", w.springLength_m},
        {"static_length", w.staticLength_m}, {"radius", w.radius_m}};
    for (const auto& [k, v] : numbers) {
      lua_pushnumber(L, v);
      rawSetField(L, -2, k);
    }
    pushVec3(L, w.hub_m);
    rawSetField(L, -2, "position");
    lua_seti(L, -2, i + 1);
  }
  rawSetField(L, -2, "wheels");
  return 1;
}

/// @function Vehicle:body
/// @return Body the chassis (position, velocity, contacts like any body)
int vBody(lua_State* L) {
  pushBody(L, systemOf(L).chassis(checkVehicle(L, 1)));
  return 1;
}

/// @function Vehicle:position
/// @return Vec3 the chassis' centre of mass, m
int vPosition(lua_State* L) {
  const vehicle::VehicleId id = checkVehicle(L, 1);
  pushVec3(L, ScenarioHost::from(L)->world().body(systemOf(L).chassis(id)).position_m);
  return 1;
}

/// @function Vehicle:forward
/// @return Vec3 the unit forward axis of the chassis, world
int vForward(lua_State* L) {
  const vehicle::VehicleId id = checkVehicle(L, 1);
  pushVec3(L, ScenarioHost::from(L)->world().body(systemOf(L).chassis(id)).orientation * Vec3::UnitZ());
  return 1;
}

/// @function Vehicle:reset
/// Puts the vehicle upright, at rest, on the ground point given (default:
/// where it was spawned), engine idling.
/// @param opts? VehicleSpawn where and which way
int vReset(lua_State* L) {
  const vehicle::VehicleId id = checkVehicle(L, 1);
  VehicleRef* ref = refOf(L, 1);
  Vec3 p(ref->spawn[0], ref->spawn[1], ref->spawn[2]);
  double heading = ref->heading;
  if (lua_istable(L, 2)) {
    optVec3Field(L, 2, "position", &p);
    heading = optNumberField(L, 2, "heading", heading);
  }
  systemOf(L).reset(id, p, Real(heading));
  return 0;
}

/// @function Vehicle:definition
/// @return VehicleDefinition the vehicle's current definition, in the file's format
int vDefinition(lua_State* L) {
  pushVehicleDef(L, systemOf(L).def(checkVehicle(L, 1)));
  return 1;
}

/// Deep merge of the table at src into the table at dst (both absolute):
/// records and the `axles` list merge entry by entry; vectors, curves and
/// gear ratios (values, not records) are replaced whole.
void mergeInto(lua_State* L, int dst, int src, int depth) {
  static const char* kReplaced[] = {"size", "com", "position", "longitudinal", "lateral", "torque", "ratios"};
  if (depth > 8) throw LuaArgError("Vehicle:tune: the table is nested too deeply");
  lua_pushnil(L);
  while (lua_next(L, src) != 0) {  // key at -2, value at -1
    bool replace = true;
    if (lua_istable(L, -1)) {
      replace = false;
      if (lua_type(L, -2) == LUA_TSTRING)
        for (const char* k : kReplaced) replace = replace || std::strcmp(lua_tostring(L, -2), k) == 0;
    }
    if (!replace) {
      lua_pushvalue(L, -2);
      lua_rawget(L, dst);
      if (lua_istable(L, -1)) {
        mergeInto(L, lua_absindex(L, -1), lua_absindex(L, -2), depth + 1);
        lua_pop(L, 2);
        continue;
      }
      lua_pop(L, 1);
    }
    lua_pushvalue(L, -2);
    lua_insert(L, -2);
    lua_rawset(L, dst);  // pops key copy and value; the original key stays for lua_next
  }
}

/// @function Vehicle:tune
/// Changes parameters while running (for tunables): the table is merged
/// into the current definition (records merged field by field; lists such
/// as curves, gear ratios and `axles` entries by index), then validated
/// and applied without a restart. A bad value is an error naming the field;
/// the vehicle keeps its old parameters then.
/// @param changes VehicleDefinition part of a definition
/// @example car:tune{engine = {max_rpm = 7200}, axles = {[2] = {suspension = {frequency = 2.0}}}}
int vTune(lua_State* L) {
  const vehicle::VehicleId id = checkVehicle(L, 1);
  if (!lua_istable(L, 2)) throw LuaArgError("Vehicle:tune: expected a table, e.g. {engine = {max_rpm = 7000}}");
  pushVehicleDef(L, systemOf(L).def(id));
  const int dst = lua_gettop(L);
  mergeInto(L, dst, 2, 0);
  auto def = vehicleDefFromTable(L, dst, std::string("Vehicle:tune (") + refOf(L, 1)->name + ")");
  if (!def) throw LuaArgError(def.error());
  if (auto s = systemOf(L).setDef(id, def.value(), refOf(L, 1)->name); !s) throw LuaArgError(s.error());
  lua_settop(L, 2);
  return 0;
}

/// @function Vehicle:name
/// @return string "mod:vehicle" it was spawned from
int vName(lua_State* L) {
  lua_pushstring(L, refOf(L, 1)->name);
  return 1;
}

/// @function Vehicle:is_valid
/// @return boolean false once removed
int vIsValid(lua_State* L) {
  VehicleRef* ref = refOf(L, 1);
  vehicle::VehicleSystem* sys = ScenarioHost::from(L)->scene().vehiclesIfAny();
  lua_pushboolean(L, sys && sys->isValid(vehicle::VehicleId{ref->index, ref->generation}));
  return 1;
}

/// @function Vehicle:remove
/// Removes the vehicle and its chassis body.
int vRemove(lua_State* L) {
  systemOf(L).remove(checkVehicle(L, 1));
  return 0;
}

int vToString(lua_State* L) {
  VehicleRef* ref = static_cast<VehicleRef*>(luaL_checkudata(L, 1, kVehicleMeta));
  lua_pushfstring(L, "Vehicle(%s #%d)", ref->name, int(ref->index));
  return 1;
}

const luaL_Reg kMethods[] = {
    {"set_controls", guarded<vSetControls>}, {"controls", guarded<vControls>},
    {"speed", guarded<vSpeed>},              {"rpm", guarded<vRpm>},
    {"gear", guarded<vGear>},                {"telemetry", guarded<vTelemetry>},
    {"body", guarded<vBody>},                {"position", guarded<vPosition>},
    {"forward", guarded<vForward>},          {"reset", guarded<vReset>},
    {"definition", guarded<vDefinition>},    {"tune", guarded<vTune>},
    {"name", guarded<vName>},                {"is_valid", guarded<vIsValid>},
    {"remove", guarded<vRemove>},            {nullptr, nullptr},
};

const luaL_Reg kFunctions[] = {
    {"spawn", guarded<vehicleSpawn>},
    {"definition", guarded<vehicleDefinition>},
    {"surface", guarded<vehicleSurface>},
    {"set_softness", guarded<vehicleSetSoftness>},
    {nullptr, nullptr},
};

}  // namespace

void openVehicleBindings(lua_State* L, int envIndex) {
  registerType(L, {kVehicleMeta, kMethods, vToString});
  registerModule(L, envIndex, "vehicle", kFunctions);
}

}  // namespace tumble::script
