// Lua table `camera`: how the scene is looked at.
//
//   camera.set_mode("chase", {target = car})                 -- spring-damped, behind and above
//   camera.set_mode("hood", {target = car})                  -- fixed on the bonnet
//   camera.set_mode("cockpit", {target = car, interior = "base:assets/models/cockpit.obj"})
//   camera.set_mode("orbit")                                 -- free orbit (mouse)
//
// The app applies the request to the renderer's camera each frame; the
// camera key (C) still cycles the modes in play.
#include <set>

#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module camera
/// The view of the scene: free orbit, following a body, a chase camera, a
/// hood camera or a cockpit view with its interior drawn as a model. Body
/// frames are Y up with the front at +Z (as the shipped vehicle models).

namespace {

const std::set<std::string> kModes = {"orbit", "follow", "chase", "hood", "cockpit"};

/// @class CameraOptions
/// @field target? Body the body followed (required for "follow", "chase", "hood" and "cockpit")
/// @field offset? Vec3Arg chase: eye position in the target's frame, m (default {0, 2.2, -6.5})
/// @field look_at? Vec3Arg chase: point looked at, target's frame, m (default {0, 1, 2})
/// @field stiffness? number chase: spring rate of the critically damped follow, 1/s (default 4; larger is stiffer)
/// @field eye? Vec3Arg hood / cockpit: eye position in the target's frame, m
/// @field hood_eye? Vec3Arg hood: eye position in the target's frame, m (wins over eye for the hood view, so one call can place both)
/// @field distance? number orbit / follow: distance of the eye from the target, m
/// @field interior? string cockpit: interior model ("MOD:path"), drawn with the body; placed at the eye
/// @field speed_gauge? Vec3Arg cockpit: centre of a speedometer dial in the interior's frame (origin at the eye, +Z forward), m; its needle sweeps 270 degrees for 0..200 km/h of the followed vehicle
/// @field rpm_gauge? Vec3Arg cockpit: centre of a rev counter dial, as speed_gauge; 0 to the vehicle's max_rpm
/// @field gauge_radius? number cockpit: dial radius, m (default 0.05; 0.01..0.5)

/// @function camera.set_mode
/// Switches the camera. Options not given keep the mode's defaults.
/// @param mode string "orbit", "follow", "chase", "hood" or "cockpit"
/// @param options? CameraOptions target body and placement
/// @example camera.set_mode("chase", {target = car, stiffness = 6})
/// @example camera.set_mode("cockpit", {target = car, eye = {0.35, 1.15, -0.1}, interior = "base:assets/models/cockpit.obj"})
int cameraSetMode(lua_State* L) {
  const char* fn = "camera.set_mode";
  if (lua_type(L, 1) != LUA_TSTRING || kModes.count(lua_tostring(L, 1)) == 0) {
    throw LuaArgError(std::string(fn) + ": mode must be \"orbit\", \"follow\", \"chase\", \"hood\" or \"cockpit\", got " +
                      (lua_type(L, 1) == LUA_TSTRING ? "\"" + std::string(lua_tostring(L, 1)) + "\""
                                                     : std::string(luaL_typename(L, 1))));
  }
  ScenarioHost* host = ScenarioHost::from(L);
  CameraRequest r;
  r.mode = lua_tostring(L, 1);
  if (!lua_isnoneornil(L, 2)) {
    if (!lua_istable(L, 2)) throw LuaArgError(std::string(fn) + ": options must be a table {target = body, ...}");
    checkFields(L, 2, fn, {"target", "offset", "look_at", "stiffness", "eye", "hood_eye", "distance", "interior",
                           "speed_gauge", "rpm_gauge", "gauge_radius"});
    try {
      if (rawGetField(L, 2, "target") != LUA_TNIL) r.target = checkBody(L, -1);
      lua_pop(L, 1);
      Vec3 v;
      if (optVec3Field(L, 2, "offset", &v)) r.offset_m = v;
      if (optVec3Field(L, 2, "look_at", &v)) r.lookAt_m = v;
      if (optVec3Field(L, 2, "eye", &v)) r.eye_m = v;
      if (optVec3Field(L, 2, "hood_eye", &v)) r.hoodEye_m = v;
      if (optVec3Field(L, 2, "speed_gauge", &v)) r.speedGauge_m = v;
      if (optVec3Field(L, 2, "rpm_gauge", &v)) r.rpmGauge_m = v;
      if (rawGetField(L, 2, "gauge_radius") != LUA_TNIL) {
        const double g = checkNumber(L, -1, "option 'gauge_radius'");
        if (!(g >= 0.01 && g <= 0.5)) throw LuaArgError("option 'gauge_radius' must be 0.01..0.5 m");
        r.gaugeRadius_m = Real(g);
      }
      lua_pop(L, 1);
      if (rawGetField(L, 2, "stiffness") != LUA_TNIL) {
        const double k = checkNumber(L, -1, "option 'stiffness'");
        if (!(k > 0)) throw LuaArgError("option 'stiffness' must be > 0 (1/s)");
        r.stiffness_per_s = Real(k);
      }
      lua_pop(L, 1);
      if (rawGetField(L, 2, "distance") != LUA_TNIL) {
        const double d = checkNumber(L, -1, "option 'distance'");
        if (!(d > 0)) throw LuaArgError("option 'distance' must be > 0 m");
        r.distance_m = Real(d);
      }
      lua_pop(L, 1);
      if (rawGetField(L, 2, "interior") != LUA_TNIL) {
        if (lua_type(L, -1) != LUA_TSTRING) throw LuaArgError("option 'interior' must be a model path string");
        auto file = resolveModFile(lua_tostring(L, -1), host->mod(), host->options().modDirs);
        if (!file) throw LuaArgError("option 'interior': " + file.error());
        if (auto box = host->scene().modelBounds(*file); !box) throw LuaArgError("option 'interior': " + box.error());
        r.interiorFile = *file;
      }
      lua_pop(L, 1);
    } catch (const LuaArgError& e) {
      throw LuaArgError(std::string(fn) + ": " + e.what());
    }
  }
  if (r.mode != "orbit" && !r.target) {
    throw LuaArgError(std::string(fn) + ": mode \"" + r.mode + "\" needs a body to follow: {target = body}");
  }
  r.revision = host->presentation().camera.revision + 1;
  host->presentation().camera = r;
  return 0;
}

/// @function camera.mode
/// @return string the mode last set by camera.set_mode ("orbit" before any)
int cameraMode(lua_State* L) {
  lua_pushstring(L, ScenarioHost::from(L)->presentation().camera.mode.c_str());
  return 1;
}

const luaL_Reg kCamera[] = {
    {"set_mode", guarded<cameraSetMode>},
    {"mode", guarded<cameraMode>},
    {nullptr, nullptr},
};

}  // namespace

void openCameraBindings(lua_State* L, int envIndex) {
  registerModule(L, envIndex, "camera", kCamera);
}

}  // namespace tumble::script
