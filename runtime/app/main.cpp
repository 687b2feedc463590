// tumble: the runtime's command line. See ARCHITECTURE.md "Command line".
#include <CLI/CLI.hpp>

#include "app/commands.h"

int main(int argc, char** argv) {
  CLI::App cli{"Tumble: a physics-scenario runtime with a Lua gameplay layer", "tumble"};
  int exitCode = 0;
  tumble::app::addCommands(cli, &exitCode);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = cli.exit(e);
    return code == 0 ? 0 : 1;  // usage errors: "could not start"
  }
  return exitCode;
}
