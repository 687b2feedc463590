#pragma once
// Emitter definition files: mods/<mod>/emitters/<name>.lua returns a table of
// particles::EmitterDef fields (particles/emitter_def.h lists them with their
// units; docs/emitters.md shows each with an example). A file is data: it runs
// in an environment with only `math`, under a small budget.
//
//   return {
//     rate = 40, lifetime = {1, 2}, shape = "cone", radius = 0.2,
//     cone_angle = math.rad(15), speed = {1, 2}, gravity = -0.1, drag = 0.8,
//     size = {{0, 0.3}, {1, 1.2}}, color = {0.5, 0.5, 0.5},
//     alpha = {{0, 0}, {0.1, 0.6}, {1, 0}}, blend = "alpha", max_count = 400,
//   }
//
// Every problem names the file, the field (and the line where it is written)
// and what is expected; `tumble check` lists them all at once.
#include <string>
#include <vector>

#include "core/result.h"
#include "particles/emitter_def.h"
#include "script/mods.h"

namespace tumble::script {

/// Reads and validates an emitter file. The error lists every problem, one
/// per line, as "FILE:LINE: field 'x': ..." (LINE left out when unknown).
/// `modName` only labels Lua errors.
Result<particles::EmitterDef> loadEmitterFile(const std::string& path, const std::string& modName);

/// Every problem of one emitter file, for `tumble check` (empty: fine).
std::vector<ModProblem> checkEmitterFile(const std::string& path, const std::string& modName);

/// The Lua field names an emitter table may have, sorted.
const std::vector<std::string>& emitterFieldNames();

}  // namespace tumble::script
