// tumble-meshgen: writes the project's generated models (`tumble meshgen [--out DIR]`).
#include <CLI/CLI.hpp>

#include "tools/meshgen/meshgen.h"

int main(int argc, char** argv) {
  CLI::App cli{"Write the project's generated models (.obj, .mtl, .png): the runtime's into assets/models, "
               "the base mod's into mods/base/assets/models",
               "tumble meshgen"};
  int exitCode = 0;
  tumble::tools::addMeshgenOptions(cli, exitCode);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? 0 : 1;  // usage errors: "could not start", as in tumble
  }
  return exitCode;
}
