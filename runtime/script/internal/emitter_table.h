#pragma once
// Lua side of emitter definitions, shared by emitter_files.cpp (files,
// `tumble check`) and bind_emitter.cpp (particles.spawn with overrides).
#include <string>
#include <vector>

#include "particles/emitter_def.h"

struct lua_State;

namespace tumble::script {

class LuaVm;

/// Reads the table at idx into `def` (fields absent keep def's values), then
/// validates the result. Each problem is appended as "field 'x': what is
/// wrong; what is expected". Leaves the stack as it was.
void readEmitterTable(lua_State* L, int idx, particles::EmitterDef& def, std::vector<std::string>& problems);

/// Loads the file at `path` as a data chunk (environment: `math` only) and
/// runs it under a small budget. On success pushes the returned table and
/// returns true; otherwise pushes nothing and sets *error (with the line
/// when Lua knows it, *line > 0).
bool runEmitterChunk(LuaVm& vm, const std::string& path, const std::string& modName, std::string* error, int* line);

/// Line of the first `field =` in the file (0 when not found), to point
/// `tumble check` at a problem.
int lineOfField(const std::string& path, const std::string& field);

}  // namespace tumble::script
