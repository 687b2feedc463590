// tumble-terrain: make, filter and inspect height maps (`tumble terrain ...`).
#include <CLI/CLI.hpp>

#include "tools/terrain/terrain_commands.h"

int main(int argc, char** argv) {
  CLI::App cli{"Make, filter and inspect height maps", "tumble terrain"};
  int exitCode = 0;
  tumble::tools::addTerrainCommands(cli, exitCode);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? 0 : 1;  // usage errors: "could not start", as in tumble
  }
  return exitCode;
}
