#pragma once
// The sandbox every mod's scenario runs in (ARCHITECTURE.md "Mods"): an
// environment table with private copies of the safe standard tables (math,
// string, table, utf8, coroutine, os.clock/time/date/difftime), and
// replacements for what would break out: load (text chunks only),
// require (the mod's own files and scripts/tumble only), setmetatable
// (no __gc: finalizers run outside the instruction budget), xpcall (the
// handler runs after the error unwound, under the budget), collectgarbage
// (look and nudge only). Reading a forbidden global (io, debug, package,
// dofile, os.execute, string.dump, ...) raises a message that says why and
// what to use instead.
#include <cstdint>
#include <string>

struct lua_State;

namespace tumble::script {

struct SandboxPaths {
  std::string modDir;      ///< require "x.y" -> <modDir>/x/y.lua
  std::string scriptsDir;  ///< require "tumble.x" -> <scriptsDir>/tumble/x.lua
};

/// Pushes a new environment table holding the safe standard library and the
/// sandbox's replacements, and seeds math.random with `seed`. *requireCacheRef
/// receives a registry ref to require's table of loaded modules (hot reload
/// empties it). The caller adds the runtime's bindings, then calls
/// guardEnvironment.
void pushSandboxEnvironment(lua_State* L, const SandboxPaths& paths, std::uint64_t seed, int* requireCacheRef);

/// Pushes a fresh environment for a data file (emitter, vehicle, bindings):
/// private copies of math (without random), string and table, and the pure
/// base functions (pairs, ipairs, select, tonumber, tostring, type, error,
/// assert). Each file gets its own copies, so a file that changes
/// math.sin changes it for itself only, never for another file or mod.
void pushDataEnvironment(lua_State* L);

/// Makes reading a forbidden global from the environment at idx raise its
/// message (call once the environment is complete).
void guardEnvironment(lua_State* L, int idx);

}  // namespace tumble::script
