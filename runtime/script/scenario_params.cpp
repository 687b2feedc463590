#include "script/scenario_params.h"

#include "script/internal/raw_access.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

extern "C" {
#include <lauxlib.h>
#include <lua.h>
}

namespace tumble::script {

/// @class ParamDeclaration
/// One entry of a scenario's `params` table: `params = {speed = {default = 16, unit = "m/s", description = "..."}}`.
/// The vehicle picker: a scenario that declares a string parameter `car` (default: a vehicle definition, MOD:NAME) is a driving scenario. The main menu (`tumble play` without a scenario) then lets the player pick one of the vehicle definitions of base, of the scenario's mod and of its dependencies, with mass, power, drive and grip, and starts the scenario with `--set car=MOD:NAME`; spawn it with `vehicle.spawn(param("car"), ...)`. The pause menu's "Change vehicle" does the same and restarts. The menu lists the scenario by its `title` with the first paragraph of the `--` comment at the top of its file as description.
/// @field default number|boolean|string the value when --set does not give one; its type is the parameter's type
/// @field unit string? the unit of a number, e.g. "m/s" (leave out for counts and ratios)
/// @field description string? what the parameter changes, for designers and sweeps

const char* paramTypeName(ParamDecl::Type type) {
  switch (type) {
    case ParamDecl::Type::Number: return "number";
    case ParamDecl::Type::Boolean: return "boolean";
    default: return "string";
  }
}

namespace {

std::string numberText(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  // The shortest text that reads back as the same double.
  for (int precision = 1; precision <= 17; ++precision) {
    char shorter[64];
    std::snprintf(shorter, sizeof shorter, "%.*g", precision, v);
    if (std::strtod(shorter, nullptr) == v) return shorter;
  }
  return buf;
}

}  // namespace

Result<ParamDecls> readParamDecls(lua_State* L, int tableIndex, const std::string& where) {
  tableIndex = lua_absindex(L, tableIndex);
  rawGetField(L, tableIndex, "params");
  if (lua_isnil(L, -1)) {
    lua_pop(L, 1);
    return ParamDecls{};
  }
  const std::string usage = "e.g. params = {speed = {default = 16, unit = \"m/s\", description = \"cruising speed\"}}";
  if (!lua_istable(L, -1)) {
    lua_pop(L, 1);
    return makeError(where + ": field 'params' must be a table of name = {default = ..., unit = ..., description = ...}, " + usage);
  }
  std::vector<ParamDecl> decls;
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    if (lua_type(L, -2) != LUA_TSTRING || !lua_istable(L, -1)) {
      lua_pop(L, 3);
      return makeError(where + ": field 'params': each entry must be name = {default = ...}, " + usage);
    }
    ParamDecl d;
    d.name = lua_tostring(L, -2);
    const std::string field = where + ": params." + d.name;
    rawGetField(L, -1, "default");
    switch (lua_type(L, -1)) {
      case LUA_TNUMBER:
        d.type = ParamDecl::Type::Number;
        d.defaultText = numberText(lua_tonumber(L, -1));
        break;
      case LUA_TBOOLEAN:
        d.type = ParamDecl::Type::Boolean;
        d.defaultText = lua_toboolean(L, -1) ? "true" : "false";
        break;
      case LUA_TSTRING:
        d.type = ParamDecl::Type::String;
        d.defaultText = lua_tostring(L, -1);
        break;
      default:
        lua_pop(L, 4);
        return makeError(field + ": 'default' must be a number, a boolean or a string (it sets the parameter's type)");
    }
    lua_pop(L, 1);
    for (auto [key, out] : {std::pair{"unit", &d.unit}, std::pair{"description", &d.description}}) {
      rawGetField(L, -1, key);
      if (lua_type(L, -1) == LUA_TSTRING) *out = lua_tostring(L, -1);
      else if (!lua_isnil(L, -1)) {
        lua_pop(L, 4);
        return makeError(field + ": '" + key + "' must be a string");
      }
      lua_pop(L, 1);
    }
    decls.push_back(std::move(d));
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::sort(decls.begin(), decls.end(), [](const ParamDecl& a, const ParamDecl& b) { return a.name < b.name; });
  return ParamDecls{std::move(decls)};
}

Status checkParamValue(const std::vector<ParamDecl>& decls, const std::string& scenario, const std::string& name,
                       const std::string& value) {
  auto it = std::find_if(decls.begin(), decls.end(), [&](const ParamDecl& d) { return d.name == name; });
  if (it == decls.end()) {
    std::string known;
    for (const ParamDecl& d : decls) known += (known.empty() ? "" : ", ") + d.name;
    return makeError("--set " + name + "=" + value + ": " + scenario + " has no parameter '" + name +
                     "' (its parameters: " + (known.empty() ? "none" : known) +
                     "; physics.*, terrain.* and tune.* settings are the others)");
  }
  if (it->type == ParamDecl::Type::Number) {
    char* end = nullptr;
    double v = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(v))
      return makeError("--set " + name + "=" + value + ": " + scenario + "'s parameter '" + name +
                       "' is a number" + (it->unit.empty() ? "" : " in " + it->unit) + " (default " +
                       it->defaultText + ")");
  } else if (it->type == ParamDecl::Type::Boolean && value != "true" && value != "false") {
    return makeError("--set " + name + "=" + value + ": " + scenario + "'s parameter '" + name +
                     "' is true or false (default " + it->defaultText + ")");
  }
  return Ok{};
}

}  // namespace tumble::script
