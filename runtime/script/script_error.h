#pragma once
// What a script did wrong, as the HUD, the log and the run report show it.
#include <string>

namespace tumble::script {

struct ScriptError {
  std::string mod;        ///< mod name, e.g. "base"
  std::string file;       ///< path inside the mod, e.g. "scenarios/drop.lua"
  int line = 0;           ///< 0 when unknown
  std::string message;    ///< the Lua message without the "file:line:" prefix
  std::string traceback;  ///< Lua stack traceback
  /// Stopped by the instruction or memory budget. summary() then reads
  /// "mod X: scenarios/y.lua: on_update exceeded N instructions ...".
  bool limit = false;
  /// "mod base: scenarios/drop.lua:12: attempt to index a nil value"
  std::string summary() const;
};

}  // namespace tumble::script
