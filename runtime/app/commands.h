#pragma once
// The command line (ARCHITECTURE.md, "Command line"): play, run, check, list.
// Offline tools (meshgen, report, terrain, ...) are programs of their own
// that main() runs for commands not registered here (external_tools.h).
#include <CLI/CLI.hpp>

namespace tumble::app {

/// Registers every subcommand on `cli`; the chosen one sets *exitCode when run.
void addCommands(CLI::App& cli, int* exitCode);

}  // namespace tumble::app
