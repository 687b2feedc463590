#include "script/sandbox.h"
#include "script/vehicle_defs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <stdexcept>

#include "script/definition_fields.h"
#include "script/internal/lua_util.h"
#include "script/lua_vm.h"

namespace tumble::script {
namespace {

namespace fs = std::filesystem;
using vehicle::Curve;
using vehicle::VehicleDef;

// A path inside the mod: not absolute, no "..".
std::string insideMod(const std::string& path, const std::string& v) {
  const fs::path mesh(v);
  if (mesh.is_absolute() || std::any_of(mesh.begin(), mesh.end(), [](const fs::path& part) { return part == ".."; }))
    throw FieldError(path + ": \"" + v + "\" leaves the mod's folder; give a path inside it, e.g. \"assets/car.glb\"");
  return v;
}

const FieldTable<vehicle::ChassisDef> kChassis{
    "VehicleChassis", "body, mass, drag",
    {
        number("mass", &vehicle::ChassisDef::mass_kg, "kg", "whole vehicle"),
        vec3("size", &vehicle::ChassisDef::size_m, "m", "{width, height, length} of the collision box"),
        vec3("com", &vehicle::ChassisDef::centerOfMass_m, "m", "centre of mass from the box centre"),
        number("drag_area", &vehicle::ChassisDef::dragArea_m2, "m^2", "drag coefficient times frontal area"),
        number("air_density", &vehicle::ChassisDef::airDensity_kgpm3, "kg/m^3", "air density"),
        number("friction", &vehicle::ChassisDef::friction, "", "chassis contact friction"),
        number("restitution", &vehicle::ChassisDef::restitution, "", "0..1"),
        text("mesh", &vehicle::ChassisDef::mesh, "visual mesh, a path inside the mod",
             [](const std::string& path, const std::string& v) { insideMod(path, v); }),
        text("display_mesh", &vehicle::ChassisDef::displayMesh,
             "drawn instead of mesh (e.g. with wheel arches cut out); mesh stays the solid the inertia comes from",
             [](const std::string& path, const std::string& v) { insideMod(path, v); }),
        choice("inertia", &vehicle::ChassisDef::inertiaFromMesh, {{"box", false}, {"mesh", true}},
               "\"box\": a solid box of size and mass; \"mesh\": the visual mesh as a uniform solid of the chassis "
               "mass (needs mesh)"),
    },
    [](const std::string& path, const vehicle::ChassisDef& c) {
      if (c.inertiaFromMesh && c.mesh.empty())
        throw FieldError(path + ".inertia: \"mesh\" needs chassis.mesh, the closed mesh to take the inertia from");
    }};

const FieldTable<vehicle::SuspensionDef> kSuspension{
    "VehicleSuspension", "springs and dampers",
    {
        number("travel", &vehicle::SuspensionDef::travel_m, "m", "hub travel from full bump to full droop"),
        number("rest_length", &vehicle::SuspensionDef::restLength_m, "m", "spring length at zero force"),
        number("stiffness", &vehicle::SuspensionDef::stiffness_Npm, "N/m", "per wheel", "from frequency"),
        number("frequency", &vehicle::SuspensionDef::frequency_hz, "Hz", "natural frequency with the static load"),
        number("bump", &vehicle::SuspensionDef::bumpDamping_Nspm, "N s/m", "compression damping", "from bump_ratio"),
        number("rebound", &vehicle::SuspensionDef::reboundDamping_Nspm, "N s/m", "extension damping",
               "from rebound_ratio"),
        number("bump_ratio", &vehicle::SuspensionDef::bumpRatio, "", "fraction of critical damping"),
        number("rebound_ratio", &vehicle::SuspensionDef::reboundRatio, "", "fraction of critical damping"),
        number("anti_roll", &vehicle::SuspensionDef::antiRoll_Npm, "N/m",
               "anti-roll bar, per metre of compression difference"),
    }};

const FieldTable<vehicle::AxleDef> kAxle{
    "VehicleAxle", "two wheels at (+x, y, z) (left) and (-x, y, z) (right), chassis frame",
    {
        vec3("position", &vehicle::AxleDef::position_m, "m", "left hub at full bump {x, y, z}; x is half the track"),
        number("radius", &vehicle::AxleDef::wheelRadius_m, "m", "wheel radius"),
        number("width", &vehicle::AxleDef::wheelWidth_m, "m", "wheel width"),
        number("inertia", &vehicle::AxleDef::wheelInertia_kgm2, "kg m^2", "one wheel"),
        boolean("steered", &vehicle::AxleDef::steered, "the wheels steer"),
        boolean("driven", &vehicle::AxleDef::driven, "the engine drives the wheels"),
        number("brake", &vehicle::AxleDef::brakeTorque_Nm, "N m", "per wheel at full brake"),
        number("handbrake", &vehicle::AxleDef::handbrakeTorque_Nm, "N m", "per wheel at full handbrake"),
        number("drive_share", &vehicle::AxleDef::driveShare, "", "fraction of the drive torque, 0..1",
               "0: equal among driven axles"),
        choice("differential", &vehicle::AxleDef::differential,
               {{"open", vehicle::Differential::Open}, {"limited_slip", vehicle::Differential::LimitedSlip}},
               "how the two wheels share the torque"),
        number("lsd_bias", &vehicle::AxleDef::lsdBias, "", "limited slip: largest torque ratio between the wheels, >= 1"),
        table("suspension", &vehicle::AxleDef::suspension, kSuspension, "springs and dampers"),
    }};

const FieldTable<vehicle::TyreDef> kTyre{
    "VehicleTyre", "slip curves and rolling resistance",
    {
        curve("longitudinal", &vehicle::TyreDef::longitudinal, "slip ratio", "friction",
              "on a surface of friction 1"),
        curve("lateral", &vehicle::TyreDef::lateral, "slip angle rad", "friction", ""),
        number("rolling_resistance", &vehicle::TyreDef::rollingResistance, "", "C_rr"),
        number("soft_ground_drag", &vehicle::TyreDef::softGroundDrag, "",
               "extra C_rr per unit of surface softness (terrain softness layer or vehicle.set_softness; mud 0.7, "
               "grass 0.4, ice 0)"),
    }};

const FieldTable<vehicle::EngineDef> kEngine{
    "VehicleEngine", "torque curve and speeds",
    {
        curve("torque", &vehicle::EngineDef::torque, "rpm", "N m", "at full throttle"),
        number("idle_rpm", &vehicle::EngineDef::idleRpm, "rpm", "idle speed"),
        number("max_rpm", &vehicle::EngineDef::maxRpm, "rpm", "rev limiter"),
        number("launch_rpm", &vehicle::EngineDef::launchRpm, "rpm",
               "the automatic clutch holds about this pulling away"),
        number("inertia", &vehicle::EngineDef::inertia_kgm2, "kg m^2", "crank, flywheel and clutch"),
        number("braking_torque", &vehicle::EngineDef::brakingTorque_Nm, "N m", "engine braking at max rpm"),
    }};

const FieldTable<vehicle::GearboxDef> kGearbox{
    "VehicleGearbox", "ratios and shift points",
    {
        numbers("ratios", &vehicle::GearboxDef::ratios, "forward gear ratios"),
        number("reverse", &vehicle::GearboxDef::reverseRatio, "", "reverse gear ratio"),
        number("final_drive", &vehicle::GearboxDef::finalDrive, "", "final drive ratio"),
        number("efficiency", &vehicle::GearboxDef::efficiency, "", "fraction of engine torque reaching the wheels, 0..1"),
        number("shift_up_rpm", &vehicle::GearboxDef::shiftUpRpm, "rpm", "for the automatic gearbox"),
        number("shift_down_rpm", &vehicle::GearboxDef::shiftDownRpm, "rpm", "for the automatic gearbox"),
        number("shift_time", &vehicle::GearboxDef::shiftTime_s, "s", "clutch open during a shift"),
    }};

const FieldTable<vehicle::SteeringDef> kSteering{
    "VehicleSteering", "angles and rate",
    {
        number("max_angle", &vehicle::SteeringDef::maxAngle_rad, "rad", "at standstill"),
        number("speed_sensitivity", &vehicle::SteeringDef::speedSensitivity_spm, "s/m",
               "the largest angle is max / (1 + this * v)"),
        number("rate", &vehicle::SteeringDef::rate_radps, "rad/s", "how fast the wheels turn"),
    }};

const FieldTable<vehicle::SoundDef> kSound{
    "VehicleSound", "engine note and tyre noise",
    {
        number("cylinders", &vehicle::SoundDef::cylinders, "",
               "whole number 1..16: the engine note's fundamental is rpm / 60 * cylinders / 2 Hz"),
        number("volume", &vehicle::SoundDef::volume, "", "engine gain, 0..4"),
        text("engine_sample", &vehicle::SoundDef::engineSample,
             "a loop (WAV or Ogg Vorbis) inside the mod played at pitch rpm / sample_rpm instead of the "
             "synthesised note",
             [](const std::string& path, const std::string& v) { insideMod(path, v); }),
        number("sample_rpm", &vehicle::SoundDef::sampleRpm, "rpm", "rpm the engine sample was recorded at"),
        number("tyre_slip_threshold", &vehicle::SoundDef::tyreSlipThreshold_mps, "m/s",
               "contact-patch slip speed where tyre noise starts"),
    }};

const FieldTable<vehicle::ViewDef> kView{
    "VehicleView", "cameras that ride in the car; eyes in the drawn model's frame (origin on the ground under "
    "its middle, +Z forward, +Y up, +X left)",
    {
        vec3("hood_eye", &vehicle::ViewDef::hoodEye_m, "m", "hood camera eye, just above the bonnet"),
        vec3("cockpit_eye", &vehicle::ViewDef::cockpitEye_m, "m", "cockpit camera eye, the driver's head"),
        text("interior", &vehicle::ViewDef::interior,
             "model drawn around the cockpit eye (origin at the eye, +Z forward), a path inside the mod; "
             "default: the base mod's generic interior",
             [](const std::string& path, const std::string& v) { insideMod(path, v); }),
        boolean("open", &vehicle::ViewDef::open,
                "an open car: the cockpit view draws the car's own model (roll cage, seat) and no interior"),
    },
    [](const std::string& path, const vehicle::ViewDef& v) {
      if (v.open && !v.interior.empty())
        throw FieldError(path + ".interior: an open car (open = true) draws its own model in the cockpit view, "
                                "not an interior; give one or the other");
    }};

// Later axles start from the one before, so a file need only say what
// differs; steered, driven, handbrake and drive_share are not copied.
vehicle::AxleDef nextAxle(const std::vector<vehicle::AxleDef>& before) {
  if (before.empty()) return vehicle::AxleDef{};
  vehicle::AxleDef a = before.back();
  a.steered = a.driven = false;
  a.handbrakeTorque_Nm = 0;
  a.driveShare = 0;
  return a;
}

const FieldTable<VehicleDef> kVehicle{
    "VehicleDefinition",
    "What mods/<mod>/vehicles/<name>.lua returns (docs/vehicles.md explains\n"
    "each field). Every field is optional; a misspelt one is an error.\n"
    "Chassis frame: origin at the box centre, +Z forward, +Y up, +X left.",
    {
        text("name", &VehicleDef::name, "shown to the player"),
        text("description", &VehicleDef::description, "the feel, in a sentence"),
        table("chassis", &VehicleDef::chassis, kChassis, "body, mass, drag"),
        list("axles", &VehicleDef::axles, kAxle,
             "2 to 8 axles, front first; an axle copies the fields it leaves out from the one before (except "
             "steered, driven, handbrake, drive_share)",
             std::function<vehicle::AxleDef(const std::vector<vehicle::AxleDef>&)>(nextAxle)),
        table("tyre", &VehicleDef::tyre, kTyre, "slip curves and rolling resistance"),
        table("engine", &VehicleDef::engine, kEngine, "torque curve and speeds"),
        table("gearbox", &VehicleDef::gearbox, kGearbox, "ratios and shift points"),
        table("steering", &VehicleDef::steering, kSteering, "angles and rate"),
        table("sound", &VehicleDef::sound, kSound, "engine note and tyre noise"),
        table("view", &VehicleDef::view, kView, "hood and cockpit cameras"),
    }};

}  // namespace

std::string vehicleDefinitionDocBlocks() {
  std::string out;
  for (const std::string& block : {kVehicle.docBlock(), kChassis.docBlock(), kAxle.docBlock(), kSuspension.docBlock(),
                                   kTyre.docBlock(), kEngine.docBlock(), kGearbox.docBlock(), kSteering.docBlock(),
                                   kSound.docBlock(), kView.docBlock()})
    out += block + "\n";
  return out;
}

Result<VehicleDef> vehicleDefFromTable(lua_State* L, int idx, const std::string& where) {
  VehicleDef d;
  const int top = lua_gettop(L);
  lua_pushvalue(L, idx);
  try {
    kVehicle.read(L, "", d);
  } catch (const FieldError& e) {
    lua_settop(L, top);
    return makeError(where + ": " + e.what());
  }
  lua_settop(L, top);
  if (auto s = vehicle::validateVehicleDef(d, where); !s) return makeError(s.error());
  return d;
}

void pushVehicleDef(lua_State* L, const VehicleDef& d) { kVehicle.push(L, d); }

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
  if (LuaVm::loadFile(L, std::string(file.c_str())) != LUA_OK) {
    ScriptError e = LuaVm::parseError(mod.name, lua_tostring(L, -1), "");
    return makeError(e.summary());
  }
  // A vehicle file is data: its own copies of math, string and table, no world.
  pushDataEnvironment(L);  // private math, string and table: data, no world
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
