#pragma once
// The command line (ARCHITECTURE.md, "Command line"): play, run, check, list.
// Offline tools (meshgen, report, terrain, ...) are programs of their own
// that main() runs for commands not registered here (external_tools.h).
#include <CLI/CLI.hpp>

namespace tumble::app {

/// Registers every subcommand on `cli`; the chosen one sets *exitCode when run.
void addCommands(CLI::App& cli, int* exitCode);
/// Removes what killed atomic writes left behind (core/file_util.h) in the
/// user's folders: the config folder (bindings.json), tune/ and the mods'
/// saves. Called once at start.
void removeOrphanedUserTemporaries();

}  // namespace tumble::app
