#pragma once
// The command line (ARCHITECTURE.md, "Command line"): play, run, check, list.
#include <CLI/CLI.hpp>

namespace tumble::app {

/// Registers every subcommand on `cli`; the chosen one sets *exitCode when run.
void addCommands(CLI::App& cli, int* exitCode);

}  // namespace tumble::app
