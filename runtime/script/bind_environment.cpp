// Lua table `environment`: the sky, sun, fog, clouds and weather a scenario
// is seen in (drawn only; physics never reads it).
//
//   environment.set{time_of_day = 18.5, weather = "cloudy"}   -- evening, overcast
//   environment.set{fog = 60, clouds = 1}                      -- fog hides 63 % at 60 m
//   environment.set{sun = {0.3, 0.5, 0.8}, fog = false}        -- a fixed sun, no fog
//   local e = environment.get()                                -- what is set now
//
// Fields not given keep their value; false clears time_of_day, sun and fog
// (fog = false: no fog; fog = "auto": the weather's own distance).
#include <cmath>
#include <set>

#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module environment
/// The sky, sun, fog, clouds and weather of the scene. Only drawn: physics,
/// state hashes and expectations do not change with it.

namespace {

const std::set<std::string> kWeathers = {"clear", "cloudy", "storm"};

/// @class EnvironmentSettings
/// @field time_of_day? number|false local solar time, hours 0..24: the sun rises in +X at 6, stands highest towards +Z at 12, sets in -X at 18; false: the fixed lab sun
/// @field sun? Vec3Arg|false direction towards the sun (any length > 0), wins over time_of_day; false: clears it
/// @field fog? number|false|string distance where fog hides 63 %, m (> 0); false: no fog; "auto": the weather's (clear 250, cloudy 180, storm 70)
/// @field clouds? number|false cloud cover 0..1 (false: 0); cloudy weather raises it to at least 0.75, a storm to 1
/// @field weather? string "clear", "cloudy" or "storm" (darker sky, denser fog, lightning)
/// @field wind? table {x, z} wind moving the clouds, m/s

/// @function environment.set
/// Changes the named settings; the others keep their values.
/// @param settings EnvironmentSettings
/// @example environment.set{time_of_day = 19, clouds = 0.6}
/// @example environment.set{weather = "storm"}
int environmentSet(lua_State* L) {
  const char* fn = "environment.set";
  if (!lua_istable(L, 1)) {
    throw LuaArgError(std::string(fn) + ": expects a table {time_of_day =, sun =, fog =, clouds =, weather =, wind =}, got " +
                      luaL_typename(L, 1));
  }
  checkFields(L, 1, fn, {"time_of_day", "sun", "fog", "clouds", "weather", "wind"});
  EnvironmentRequest r = ScenarioHost::from(L)->presentation().environment;
  try {
    if (rawGetField(L, 1, "time_of_day") != LUA_TNIL) {
      if (lua_isboolean(L, -1) && !lua_toboolean(L, -1)) {
        r.timeOfDay_h.reset();
      } else {
        const double t = checkNumber(L, -1, "field 'time_of_day'");
        if (t < 0 || t > 24) throw LuaArgError("field 'time_of_day' must be hours 0..24 (or false), got " + std::to_string(t));
        r.timeOfDay_h = t;
      }
    }
    lua_pop(L, 1);
    if (rawGetField(L, 1, "sun") != LUA_TNIL) {
      if (lua_isboolean(L, -1) && !lua_toboolean(L, -1)) {
        r.sunDirection.reset();
      } else {
        const Vec3 v = checkVec3(L, -1, "field 'sun'");
        if (!(v.norm() > 1e-9)) throw LuaArgError("field 'sun' must be a direction {x, y, z} of non-zero length (or false)");
        r.sunDirection = v.normalized();
      }
    }
    lua_pop(L, 1);
    if (rawGetField(L, 1, "fog") != LUA_TNIL) {
      if (lua_isboolean(L, -1) && !lua_toboolean(L, -1)) {
        r.fogDistance_m = 0.0;
      } else if (lua_type(L, -1) == LUA_TSTRING && std::string(lua_tostring(L, -1)) == "auto") {
        r.fogDistance_m.reset();
      } else {
        if (lua_type(L, -1) != LUA_TNUMBER) {
          throw LuaArgError(std::string("field 'fog' must be a distance in m (> 0), false or \"auto\", got ") +
                            luaL_typename(L, -1));
        }
        const double d = checkNumber(L, -1, "field 'fog'");
        if (!(d > 0)) throw LuaArgError("field 'fog' must be a distance > 0 m (false: no fog), got " + std::to_string(d));
        r.fogDistance_m = d;
      }
    }
    lua_pop(L, 1);
    if (rawGetField(L, 1, "clouds") != LUA_TNIL) {
      if (lua_isboolean(L, -1) && !lua_toboolean(L, -1)) {
        r.cloudCover = 0.0;
      } else {
        const double c = checkNumber(L, -1, "field 'clouds'");
        if (c < 0 || c > 1) throw LuaArgError("field 'clouds' must be a cover fraction 0..1 (or false), got " + std::to_string(c));
        r.cloudCover = c;
      }
    }
    lua_pop(L, 1);
    if (rawGetField(L, 1, "weather") != LUA_TNIL) {
      if (lua_type(L, -1) != LUA_TSTRING || kWeathers.count(lua_tostring(L, -1)) == 0) {
        throw LuaArgError("field 'weather' must be \"clear\", \"cloudy\" or \"storm\", got " +
                          (lua_type(L, -1) == LUA_TSTRING ? "\"" + std::string(lua_tostring(L, -1)) + "\""
                                                          : std::string(luaL_typename(L, -1))));
      }
      r.weather = lua_tostring(L, -1);
    }
    lua_pop(L, 1);
    if (rawGetField(L, 1, "wind") != LUA_TNIL) {
      if (!lua_istable(L, -1)) throw LuaArgError("field 'wind' must be a table {x, z} in m/s");
      lua_rawgeti(L, -1, 1);
      lua_rawgeti(L, -2, 2);
      const double x = checkNumber(L, -2, "field 'wind' [1] (x, m/s)");
      const double z = checkNumber(L, -1, "field 'wind' [2] (z, m/s)");
      lua_pop(L, 2);
      r.wind_mps = Eigen::Vector2d(x, z);
    }
    lua_pop(L, 1);
  } catch (const LuaArgError& e) {
    throw LuaArgError(std::string(fn) + ": " + e.what());
  }
  r.revision += 1;
  ScenarioHost::from(L)->presentation().environment = r;
  return 0;
}

/// @function environment.get
/// @return table the current settings: {time_of_day, sun, fog, clouds, weather, wind}; unset ones are nil (fog 0: none)
int environmentGet(lua_State* L) {
  const EnvironmentRequest& r = ScenarioHost::from(L)->presentation().environment;
  lua_createtable(L, 0, 6);
  if (r.timeOfDay_h) {
    lua_pushnumber(L, *r.timeOfDay_h);
    lua_setfield(L, -2, "time_of_day");
  }
  if (r.sunDirection) {
    pushVec3(L, *r.sunDirection);
    lua_setfield(L, -2, "sun");
  }
  if (r.fogDistance_m) {
    lua_pushnumber(L, *r.fogDistance_m);
    lua_setfield(L, -2, "fog");
  }
  lua_pushnumber(L, r.cloudCover);
  lua_setfield(L, -2, "clouds");
  lua_pushstring(L, r.weather.c_str());
  lua_setfield(L, -2, "weather");
  lua_createtable(L, 2, 0);
  lua_pushnumber(L, r.wind_mps.x());
  lua_rawseti(L, -2, 1);
  lua_pushnumber(L, r.wind_mps.y());
  lua_rawseti(L, -2, 2);
  lua_setfield(L, -2, "wind");
  return 1;
}

const luaL_Reg kEnvironment[] = {
    {"set", guarded<environmentSet>},
    {"get", guarded<environmentGet>},
    {nullptr, nullptr},
};

}  // namespace

void openEnvironmentBindings(lua_State* L, int envIndex) {
  registerModule(L, envIndex, "environment", kEnvironment);
}

}  // namespace tumble::script
