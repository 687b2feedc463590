#pragma once
// The parameters a scenario declares it reads (`params = {...}` in the table
// a scenario file returns). `--set NAME=VALUE` for a scenario that declares
// its parameters must name one of them, with a value of the default's type;
// the app checks it before the run starts (a misspelt name must not pass
// silently), `param(NAME)` falls back to the declared default, the run report
// lists every declared parameter with the value the run used, and tools
// (tumble sweep) check a sweep against the list before anything runs.
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"

struct lua_State;

namespace tumble::script {

struct ParamDecl {
  enum class Type { Number, Boolean, String };
  std::string name;
  Type type = Type::Number;
  std::string defaultText;  ///< the default as --set would write it ("40", "true", "base:hatchback")
  std::string unit;         ///< e.g. "m/s"; empty: a count, a ratio or a name
  std::string description;
};

/// The scenario's declaration: absent (the scenario does not declare its
/// parameters; any --set NAME reaches param()) or the list, sorted by name.
using ParamDecls = std::optional<std::vector<ParamDecl>>;

/// Reads the `params` field of the table at `tableIndex`. `where` names the
/// file for messages ("mod base: scenarios/drive.lua").
Result<ParamDecls> readParamDecls(lua_State* L, int tableIndex, const std::string& where);

/// Checks one `--set NAME=VALUE` against a declaration: the name must be
/// declared, the value of the default's type (a number, true or false, any
/// text). The message names the scenario, the parameter and what is valid.
Status checkParamValue(const std::vector<ParamDecl>& decls, const std::string& scenario, const std::string& name,
                       const std::string& value);

/// "number", "boolean" or "string".
const char* paramTypeName(ParamDecl::Type type);

}  // namespace tumble::script
