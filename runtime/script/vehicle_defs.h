#pragma once
// Vehicle definitions in Lua: mods/<mod>/vehicles/<name>.lua returns a
// table with every parameter (docs/vehicles.md lists them with units;
// vehicle/vehicle_def.h is the C++ side). These read and write such tables.
//
// One field table per part of a definition (vehicle_defs.cpp, using
// definition_fields.h) drives reading, pushing back, refusing unknown or
// mistyped fields and the generated reference. A misspelt field is an error
// that names the file and the field path ("vehicles/hatchback.lua:
// axles[2].suspension: unknown field 'frequncy' (did you mean: frequency?)
// (valid: ...)"), as every mod data error does.
#include <string>
#include <vector>

#include "core/result.h"
#include "script/mods.h"
#include "vehicle/vehicle_def.h"

struct lua_State;

namespace tumble::script {

/// The table at idx as a VehicleDef, validated; `where` names the file.
Result<vehicle::VehicleDef> vehicleDefFromTable(lua_State* L, int idx, const std::string& where);
/// Pushes the definition as a table in the file format (round-trips).
void pushVehicleDef(lua_State* L, const vehicle::VehicleDef& def);
/// Runs <mod>/vehicles/<name>.lua in a fresh state that has only `math`
/// (a vehicle file is data) and returns the validated definition.
Result<vehicle::VehicleDef> loadVehicleFile(const ModInfo& mod, const std::string& name);
/// The reference of a vehicle file's tables as doc blocks (`/// @class
/// VehicleDefinition` ...), for tools/luadoc.
std::string vehicleDefinitionDocBlocks();
/// Every problem in a mod's vehicles/*.lua, for `tumble check`.
std::vector<ModProblem> checkVehicles(const ModInfo& mod);

}  // namespace tumble::script
