#pragma once
// Offline tools are programs of their own (tools/README.md): `tumble TOOL
// ARGS...` runs tumble-TOOL from the folder of this binary, as git runs
// git-foo for `git foo`. The runtime links no tool code; it only finds the
// programs and hands over the command line.
#include <optional>
#include <string>
#include <vector>

namespace tumble::app {

/// The tools installed beside this binary: "terrain" for bin/tumble-terrain,
/// sorted. Empty when the folder cannot be read.
std::vector<std::string> externalTools();

/// Runs tumble-TOOL with argv[2..] when argv[1] names a tool beside this
/// binary and no built-in command (`builtins`). Does not return when the
/// tool started; returns the exit status when it could not start (1, after
/// a message), or nullopt when argv[1] is no tool (parse as usual).
std::optional<int> runExternalTool(int argc, char** argv, const std::vector<std::string>& builtins);

}  // namespace tumble::app
